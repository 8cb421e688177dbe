// The scen extension: the language server `scen lsp` (diagnostics as you
// type, completion, hover, definition, references, outline, formatting)
// through vscode-languageclient; when `scen` is not found (or
// `scen.server.enable` is off), the `scen: check` task, whose `$scen`
// problem matcher (package.json) shows `scen check --format json`'s
// diagnostics. The task is there in both cases. Colouring, brackets,
// comments and snippets are declarative.
'use strict';

const childProcess = require('child_process');
const vscode = require('vscode');

const TYPE = 'scen';

/** The `scen` program of the settings. */
function program() {
  return vscode.workspace.getConfiguration('scen').get('path') || 'scen';
}

/** Whether `scen` runs and knows `lsp` (an older `scen` does not). */
function hasServer(command) {
  const probe = childProcess.spawnSync(command, ['lsp', '--help'], { timeout: 10000 });
  return probe.status === 0;
}

/** The task for a definition `{ type: "scen", file }`. */
function checkTask(definition, scope) {
  const execution = new vscode.ShellExecution(program(), [
    'check',
    '--format',
    'json',
    definition.file,
  ]);
  const task = new vscode.Task(definition, scope, 'check', TYPE, execution, ['$scen']);
  task.group = vscode.TaskGroup.Build;
  task.presentationOptions = { reveal: vscode.TaskRevealKind.Silent, clear: true };
  return task;
}

let client;

function activate(context) {
  context.subscriptions.push(
    vscode.tasks.registerTaskProvider(TYPE, {
      // `scen: check` for the file in the active editor (`${file}` is
      // resolved when the task runs).
      provideTasks: () => [checkTask({ type: TYPE, file: '${file}' }, vscode.TaskScope.Workspace)],
      // A `"type": "scen"` task written in tasks.json.
      resolveTask: (task) =>
        task.definition.file ? checkTask(task.definition, task.scope) : undefined,
    }),
  );
  const command = program();
  if (vscode.workspace.getConfiguration('scen').get('server.enable') === false) {
    return;
  }
  if (!hasServer(command)) {
    vscode.window.showInformationMessage(
      `scen: \`${command} lsp\` did not start; errors are shown by the task "scen: check". ` +
        'Put `scen` on PATH or set `scen.path`.',
    );
    return;
  }
  const { LanguageClient } = require('vscode-languageclient/node');
  client = new LanguageClient(
    'scen',
    'scen language server',
    { command, args: ['lsp'] },
    {
      documentSelector: [
        { scheme: 'file', language: 'scen' },
        { scheme: 'untitled', language: 'scen' },
      ],
    },
  );
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate, checkTask, hasServer };
