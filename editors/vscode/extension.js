// The rigor extension: starts `rigor lsp` and hands it the documents it reads
// (derivations, and Markdown and LaTeX notes unless `rigor.notes` is off).
'use strict';

const vscode = require('vscode');
const { LanguageClient } = require('vscode-languageclient/node');

let client;

function activate(context) {
  const config = vscode.workspace.getConfiguration('rigor');
  const command = config.get('path', 'rigor');
  const args = ['--timeout', String(config.get('timeout', 10)), 'lsp'];
  const documentSelector = [{ scheme: 'file', language: 'rigor' }, { scheme: 'untitled', language: 'rigor' }];
  if (config.get('notes', true)) {
    documentSelector.push({ scheme: 'file', language: 'markdown' }, { scheme: 'file', language: 'latex' });
  }
  client = new LanguageClient(
    'rigor',
    'rigor',
    { run: { command, args }, debug: { command, args } },
    { documentSelector }
  );
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
