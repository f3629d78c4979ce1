-- End-to-end check with Neovim (0.7+, headless) as the LSP client: diagnostics,
-- completion, hover, definition and formatting against the real server.
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

vim.lsp.stop_client(client_id)
io.stdout:write(string.format('%d failed\n', failures))
if failures > 0 then vim.cmd('cquit 1') else vim.cmd('qall!') end
