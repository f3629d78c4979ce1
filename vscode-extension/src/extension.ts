// The ILMR extension: starts ilmr-lsp over stdio and hands it the ILMR documents and
// the workspace's ROBO.INI. All language smarts live in the server.

import * as vscode from 'vscode';
import {
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
  TransportKind,
} from 'vscode-languageclient/node';

let client: LanguageClient | undefined;

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  context.subscriptions.push(
    vscode.commands.registerCommand('ilmr.restartServer', () => restart()),
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      // The robot setting reaches the running server as a configuration change; only
      // a different executable (the server's, or the `ilmrc` its run lens starts)
      // needs a restart.
      if (
        event.affectsConfiguration('ilmr.server.path') ||
        event.affectsConfiguration('ilmr.ilmrc.path')
      ) {
        await restart();
      }
    }),
  );
  await start();
}

export async function deactivate(): Promise<void> {
  await stop();
}

function serverCommand(): string {
  const configured = vscode.workspace.getConfiguration('ilmr').get<string>('server.path', '');
  return configured.trim() !== '' ? configured : 'ilmr-lsp';
}

async function start(): Promise<void> {
  const command = serverCommand();
  const serverOptions: ServerOptions = {
    run: { command, transport: TransportKind.stdio },
    debug: { command, transport: TransportKind.stdio },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [
      { scheme: 'file', language: 'ilmr' },
      { scheme: 'untitled', language: 'ilmr' },
      { scheme: 'file', pattern: '**/{ROBO,robo,Robo}.{INI,ini}' },
      // Test files of `ilmrc test`, whatever language the editor gives TOML.
      { scheme: 'file', pattern: '**/*.test.toml' },
    ],
    // The concurrency lens (inlay hints), the "run in simulator" code lens and its
    // `ilmr.run` command come from the server: the client shows hints and lenses and
    // forwards the command to it (workspace/executeCommand) by itself.
    initializationOptions: {
      robot: vscode.workspace.getConfiguration('ilmr').get<string>('robot', 'moro'),
      ilmrc: vscode.workspace.getConfiguration('ilmr').get<string>('ilmrc.path', ''),
    },
    synchronize: {
      configurationSection: 'ilmr',
    },
  };
  client = new LanguageClient('ilmr', 'ILMR Language Server', serverOptions, clientOptions);
  try {
    await client.start();
  } catch (error) {
    client = undefined;
    const message = error instanceof Error ? error.message : String(error);
    void vscode.window.showErrorMessage(
      `Cannot start the ILMR language server \`${command}\`: ${message}. ` +
        'Install it with `cargo install --path lsp` from the ILMR repository, ' +
        'or set `ilmr.server.path`.',
    );
  }
}

async function stop(): Promise<void> {
  if (client !== undefined) {
    const running = client;
    client = undefined;
    await running.stop();
  }
}

async function restart(): Promise<void> {
  await stop();
  await start();
}
