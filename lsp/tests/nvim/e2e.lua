-- End-to-end check with Neovim (0.7+, headless) as the LSP client: diagnostics,
-- completion, hover, definition and formatting, and the concurrency lens (inlay hints,
-- the "run in simulator" code lens and its times), workspace symbols and document
-- highlights against the real server and a real `ilmrc run`.
-- Run by run.sh, which sets ILMR_LSP (the binary) and ILMR_WS (a scratch workspace).

local server = os.getenv('ILMR_LSP')
local ws = os.getenv('ILMR_WS')
local failures = 0

local function check(ok, what, detail)
  if ok then
    io.stdout:write('ok   ' .. what .. '\n')
  else
    failures = failures + 1
    io.stdout:write('FAIL ' .. what .. ': ' .. vim.inspect(detail) .. '\n')
  end
end

vim.cmd('edit ' .. ws .. '/task.ilmr')
local buf = vim.api.nvim_get_current_buf()
local client_id = vim.lsp.start_client({
  name = 'ilmr-lsp',
  cmd = { server },
  root_dir = ws,
  init_options = { robot = 'moro' },
  -- The server's messages (a run's summary) on lines of their own, not echoed into
  -- the checks' output.
  handlers = {
    ['window/showMessage'] = function(_, result)
      io.stdout:write('message: ' .. result.message:gsub('\n', '\n         ') .. '\n')
    end,
  },
})
vim.lsp.buf_attach_client(buf, client_id)

local got = vim.wait(10000, function() return #vim.diagnostic.get(buf) > 0 end, 50)
local typo
for _, d in ipairs(vim.diagnostic.get(buf)) do
  if d.code == 'E0304' then typo = d end
end
check(got and typo ~= nil, 'diagnostics arrive with their codes', vim.diagnostic.get(buf))
-- `lft` follows `kääntö = followwall(`: UTF-16 column 20, which Neovim turns into
-- byte column 23 (three of the characters before it are two bytes each).
check(typo and typo.lnum == 2 and typo.col == 23, 'UTF-16 columns after Finnish names', typo)

local function request(method, line, character, extra)
  -- On the first document, task.ilmr.
  local params = {
    textDocument = { uri = vim.uri_from_bufnr(buf) },
    position = { line = line, character = character },
  }
  for k, v in pairs(extra or {}) do params[k] = v end
  local answers = vim.lsp.buf_request_sync(buf, method, params, 10000) or {}
  for _, answer in pairs(answers) do
    if answer.result then return answer.result end
  end
  return nil
end

-- Line 3 (0-based): `t = turn(` is being typed.
local items = request('textDocument/completion', 3, 9) or {}
local labels = {}
for _, item in ipairs(items.items or items) do labels[item.label] = true end
check(labels['left'] and labels['right'] and labels['d='] and labels['käännös'],
  'completion in turn( follows the grammar', vim.tbl_keys(labels))

local hover = request('textDocument/hover', 1, 7)
check(hover and hover.contents.value:find('variable holding a movement', 1, true),
  'hover on a variable with a Finnish name', hover)

local def = request('textDocument/definition', 4, 2)
check(def and def[1] and def[1].uri:find('skills.ilms', 1, true), 'definition of a skill', def)

-- Finish the typed line, then format.
vim.api.nvim_buf_set_lines(buf, 3, 4, false, { 't = TURN(left)' })
vim.wait(300)
local edits = request('textDocument/formatting', 0, 0, { options = { tabSize = 4, insertSpaces = true } })
if edits then vim.lsp.util.apply_text_edits(edits, buf, 'utf-16') end
local lines = vim.api.nvim_buf_get_lines(buf, 0, -1, false)
check(lines[4] == 't = turn(left)', 'formatting is ilmrc fmt', lines)

-- The concurrency lens on a second task (run.sh writes it):
--   1 m = goahead(0.5)       2 turn(d=20,c=0.5)   3 wait(m)   4 speed(0.3)
--   6 f = followwall(left,1) 7 break(followw)
vim.cmd('edit ' .. ws .. '/lens.ilmr')
local lens_buf = vim.api.nvim_get_current_buf()
vim.lsp.buf_attach_client(lens_buf, client_id)

local function ask(b, method, params, timeout)
  local answers = vim.lsp.buf_request_sync(b, method, params, timeout or 10000) or {}
  for _, answer in pairs(answers) do
    if answer.result then return answer.result end
  end
  return nil
end

local function hints(b)
  b = b or lens_buf
  local got = ask(b, 'textDocument/inlayHint', {
    textDocument = { uri = vim.uri_from_bufnr(b) },
    range = { start = { line = 0, character = 0 }, ['end'] = { line = 100, character = 0 } },
  }) or {}
  local by_line = {}
  for _, h in ipairs(got) do
    local line = h.position.line + 1
    by_line[line] = (by_line[line] or '') .. '|' .. h.label
  end
  return by_line
end

local function has(by_line, line, text)
  return by_line[line] ~= nil and by_line[line]:find(text, 1, true) ~= nil
end

local before = hints()
check(has(before, 1, 'starts at t=0 with block 2') and has(before, 1, '|m')
    and has(before, 2, 'queued after line 1 (movement)')
    and has(before, 4, 'held until `wait(m)` at line 3') and has(before, 4, '|m/s')
    and has(before, 6, 'ended by break at line 7'),
  'inlay hints: when each statement starts, what ends it, units', before)

-- A bare `break` and a `priority = highest` block, in a file of their own (never run).
vim.cmd('edit ' .. ws .. '/enders.ilmr')
local enders_buf = vim.api.nvim_get_current_buf()
vim.lsp.buf_attach_client(enders_buf, client_id)
local ended = hints(enders_buf)
check(has(ended, 1, 'ended when the priority block at line 5 starts')
    and has(ended, 1, 'ended by break at line 9')
    and has(ended, 6, 'ended by break at line 9')
    and not has(ended, 6, 'priority block'),
  'inlay hints: what a bare break and a priority block end', ended)
vim.cmd('buffer ' .. lens_buf)

local lenses = ask(lens_buf, 'textDocument/codeLens',
  { textDocument = { uri = vim.uri_from_bufnr(lens_buf) } }) or {}
local run = lenses[1] and lenses[1].command
check(run and run.command == 'ilmr.run' and run.title:find('run in simulator', 1, true),
  'a "run in simulator" code lens', lenses)

local symbols = ask(buf, 'workspace/symbol', { query = 'kier' }) or {}
check(#symbols == 1 and symbols[1].name == 'KIERROS' and symbols[1].location.uri:find('skills.ilms', 1, true),
  'workspace symbols find a skill by a fuzzy query', symbols)

-- `käännös` on line 1 (bound) and line 2 (waited on): Write = 3, Read = 2.
local marks = request('textDocument/documentHighlight', 0, 2) or {}
local kinds = {}
for _, h in ipairs(marks) do kinds[#kinds + 1] = h.range.start.line .. ':' .. h.kind end
check(table.concat(kinds, ' ') == '0:3 1:2', 'document highlights: binding and use', marks)

if run then
  local done = ask(lens_buf, 'workspace/executeCommand',
    { command = run.command, arguments = run.arguments }, 100000)
  check(done and done.exit == 0 and done.summary:find('finished: no command left', 1, true),
    'the lens runs the task in the simulator and answers its summary', done)
  local after = hints()
  check(has(after, 1, '|ran t=0.00') and has(after, 2, '|ran t=') and has(after, 4, '|issued t='),
    'after a run, each statement has its times from the trace', after)
  local again = ask(lens_buf, 'textDocument/codeLens',
    { textDocument = { uri = vim.uri_from_bufnr(lens_buf) } }) or {}
  local title = again[1] and again[1].command and again[1].command.title or ''
  check(title:find('last run: ', 1, true) ~= nil and title:find(': finished: no command left', 1, true) ~= nil,
    'the lens tells how the last run ended', again)
end

-- A test file (run.sh writes it): its problems as `ilmrc test` reports them, and
-- completion of assertions from the grammar and the task's lines.
vim.cmd('edit ' .. ws .. '/lens.test.toml')
local test_buf = vim.api.nvim_get_current_buf()
vim.lsp.buf_attach_client(test_buf, client_id)
vim.wait(10000, function() return #vim.diagnostic.get(test_buf) > 0 end, 50)
local unknown_key
for _, d in ipairs(vim.diagnostic.get(test_buf)) do
  if d.code == 'A0102' then unknown_key = d end
end
check(unknown_key and unknown_key.lnum == 1 and unknown_key.col == 0
    and unknown_key.message:find('did you mean `seeds`?', 1, true),
  'a test file gets its problems with their codes and spans', vim.diagnostic.get(test_buf))

local assert_line = vim.api.nvim_buf_get_lines(test_buf, 5, 6, false)[1]
local function complete_test(after)
  local _, col = assert_line:find(after, 1, true)
  local got = ask(test_buf, 'textDocument/completion', {
    textDocument = { uri = vim.uri_from_bufnr(test_buf) },
    position = { line = 5, character = col },
  }) or {}
  local found = {}
  for _, item in ipairs(got.items or got) do found[item.label] = item.detail or true end
  return found
end
local lines_offered = complete_test('"eventually: line ')
check(lines_offered['1'] == 'm = goahead(0.5)' and lines_offered['7'] == 'break(followw)'
    and lines_offered['5'] == nil,
  'completion of a line reference offers the task\'s statements', lines_offered)
local words = complete_test('"ev')
check(words['eventually'] and words['never'] and not words['always'],
  'completion of an assertion\'s first word', words)

vim.lsp.stop_client(client_id)
io.stdout:write(string.format('%d failed\n', failures))
if failures > 0 then vim.cmd('cquit 1') else vim.cmd('qall!') end
