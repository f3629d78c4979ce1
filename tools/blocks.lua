-- The Lua 5.4 side of tools/blocks_vs_lua.sh: N coroutines, each the counting block
-- of issue 14 (c=0; while c<100 do c=c+1; wait one tick end), resumed once a tick by
-- a round-robin scheduler, as the ILMR VM steps its blocks. A coroutine yields where
-- the block's wait(0.01) sleeps. Prints: lua N ns_per_step bytes_per_coroutine.
--   lua5.4 tools/blocks.lua N TICKS
local n, ticks = tonumber(arg[1]), tonumber(arg[2])
local yield = coroutine.yield
local function block()
  local c = 0
  while c < 100 do
    c = c + 1
    yield()
  end
end
collectgarbage("collect")
local before = collectgarbage("count")
local tasks = {}
for i = 1, n do
  tasks[i] = coroutine.create(block)
end
local resume = coroutine.resume
local function tick()
  for i = 1, n do
    resume(tasks[i])
  end
end
-- As the VM's first ticks: every block started and took its first step.
tick()
tick()
local bytes = (collectgarbage("count") - before) * 1024 / n
local start = os.clock()
for _ = 1, ticks do
  tick()
end
local elapsed = os.clock() - start
print(string.format("lua %d %.1f %.0f", n, elapsed * 1e9 / (ticks * n), bytes))
