// The extension's lenses, short of VS Code itself (an in-editor test with
// @vscode/test-electron downloads VS Code, which CI cannot): the client library the
// extension starts registers the inlay-hint, code-lens and execute-command features
// with no middleware in the way, and the real ilmr-lsp, spoken to over stdio with the
// same protocol library and the client capabilities those features declare, answers
// with hints, a "run in simulator" lens whose command the client registers (it is in
// the server's executeCommandProvider), and a run when that command is executed.
//
// Run by test.sh: `node --test tests/`. ILMR_LSP names the server (default: the
// workspace's target/debug/ilmr-lsp, with ilmrc beside it for the run).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const require = createRequire(import.meta.url);
const here = dirname(fileURLToPath(import.meta.url));
const extension = join(here, '..');
const server = process.env.ILMR_LSP ?? join(extension, '..', 'target', 'debug', 'ilmr-lsp');

// The protocol library vscode-languageclient itself speaks with (the locked version).
const protocol = require('vscode-languageserver-protocol/node');

test('the extension starts the stock client, which shows hints and lenses and registers server commands', () => {
  const source = readFileSync(join(extension, 'src', 'extension.ts'), 'utf8');
  assert.match(source, /from 'vscode-languageclient\/node'/);
  assert.match(source, /new LanguageClient\(/);
  // Middleware could swallow hints, lenses or commands: the client runs without any.
  assert.doesNotMatch(source, /middleware/);
  const library = join(extension, 'node_modules', 'vscode-languageclient', 'lib', 'common');
  const builtin = readFileSync(join(library, 'client.js'), 'utf8');
  for (const feature of ['CodeLensFeature', 'InlayHintsFeature', 'ExecuteCommandFeature']) {
    assert.match(builtin, new RegExp(`registerFeature\\(new \\w+\\.${feature}\\(this\\)\\)`), feature);
  }
  // Each command of the server's executeCommandProvider becomes a VS Code command that
  // sends workspace/executeCommand: so a lens's command runs on the server when clicked.
  const execute = readFileSync(join(library, 'executeCommand.js'), 'utf8');
  assert.match(execute, /for \(const command of data\.registerOptions\.commands\)/);
  assert.match(execute, /commands\.registerCommand\(command,/);
  assert.match(execute, /ExecuteCommandRequest\.type/);
});

/// The client capabilities of those three features (fillClientCapabilities).
const capabilities = {
  textDocument: {
    inlayHint: {
      dynamicRegistration: true,
      resolveSupport: { properties: ['tooltip', 'textEdits', 'label.tooltip', 'label.location', 'label.command'] },
    },
    codeLens: { dynamicRegistration: true, resolveSupport: { properties: ['command'] } },
  },
  workspace: {
    inlayHint: { refreshSupport: true },
    codeLens: { refreshSupport: true },
    executeCommand: { dynamicRegistration: true },
  },
};

test('ilmr-lsp gives the lens hints, a run lens the client can execute, and runs the task', async () => {
  const ws = mkdtempSync(join(tmpdir(), 'ilmr-vscode-'));
  const child = spawn(server, [], { stdio: ['pipe', 'pipe', 'inherit'] });
  const connection = protocol.createMessageConnection(
    new protocol.StreamMessageReader(child.stdout),
    new protocol.StreamMessageWriter(child.stdin),
  );
  const refreshed = { lenses: 0, hints: 0 };
  connection.onRequest(protocol.CodeLensRefreshRequest.type, () => {
    refreshed.lenses += 1;
  });
  connection.onRequest(protocol.InlayHintRefreshRequest.type, () => {
    refreshed.hints += 1;
  });
  connection.onRequest(protocol.ConfigurationRequest.type, (params) => params.items.map(() => null));
  const messages = [];
  connection.onNotification(protocol.ShowMessageNotification.type, (m) => messages.push(m.message));
  connection.onNotification(protocol.PublishDiagnosticsNotification.type, () => {});
  connection.listen();
  try {
    const init = await connection.sendRequest(protocol.InitializeRequest.type, {
      processId: process.pid,
      rootUri: pathToFileURL(ws).href,
      capabilities,
      initializationOptions: { robot: 'moro', ilmrc: '' },
      workspaceFolders: [{ uri: pathToFileURL(ws).href, name: 'ws' }],
    });
    const caps = init.capabilities;
    assert.equal(caps.inlayHintProvider, true);
    assert.ok(caps.codeLensProvider, 'a code lens provider');
    const commands = caps.executeCommandProvider?.commands ?? [];
    await connection.sendNotification(protocol.InitializedNotification.type, {});

    const path = join(ws, 'task.ilmr');
    const text = 'm = goahead(0.5)\nturn(d=20,c=0.5)\nwait(m)\nspeed(0.3)\n';
    writeFileSync(path, text);
    const uri = pathToFileURL(path).href;
    await connection.sendNotification(protocol.DidOpenTextDocumentNotification.type, {
      textDocument: { uri, languageId: 'ilmr', version: 1, text },
    });
    const range = { start: { line: 0, character: 0 }, end: { line: 10, character: 0 } };
    const labels = (hints) => hints.map((h) => `${h.position.line + 1}: ${h.label}`);
    const hints = await connection.sendRequest(protocol.InlayHintRequest.type, { textDocument: { uri }, range });
    assert.ok(labels(hints).includes('2: queued after line 1 (movement)'), labels(hints).join('\n'));
    assert.ok(labels(hints).includes('4: held until `wait(m)` at line 3'), labels(hints).join('\n'));

    const lenses = await connection.sendRequest(protocol.CodeLensRequest.type, { textDocument: { uri } });
    const run = lenses[0]?.command;
    assert.ok(run?.title.includes('run in simulator'), JSON.stringify(lenses));
    assert.ok(commands.includes(run.command), `${run.command} is registered client-side: ${commands}`);

    const done = await connection.sendRequest(protocol.ExecuteCommandRequest.type, {
      command: run.command,
      arguments: run.arguments,
    });
    assert.equal(done.exit, 0, JSON.stringify(done));
    assert.match(done.summary, /finished: no command left/);
    assert.ok(messages.some((m) => m.includes('finished: no command left')), messages.join('\n'));
    assert.ok(refreshed.lenses > 0 && refreshed.hints > 0, JSON.stringify(refreshed));
    const after = await connection.sendRequest(protocol.InlayHintRequest.type, { textDocument: { uri }, range });
    assert.ok(labels(after).some((l) => l.startsWith('1: ran t=0.00')), labels(after).join('\n'));
    const again = await connection.sendRequest(protocol.CodeLensRequest.type, { textDocument: { uri } });
    assert.match(again[0].command.title, /last run: .*finished: no command left/);

    await connection.sendRequest(protocol.ShutdownRequest.type);
    await connection.sendNotification(protocol.ExitNotification.type);
  } finally {
    connection.dispose();
    child.kill();
    rmSync(ws, { recursive: true, force: true });
  }
});
