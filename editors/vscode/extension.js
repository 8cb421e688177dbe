// The `scen: check` task: runs `scen check --format json` on a .scen file;
// the `$scen` problem matcher (package.json) turns its diagnostics, one JSON
// object per line, into problems. Everything else of the extension
// (colouring, brackets, comments, snippets) is declarative.
'use strict';

const vscode = require('vscode');

const TYPE = 'scen';

/** The task for a definition `{ type: "scen", file }`. */
function checkTask(definition, scope) {
  const program = vscode.workspace.getConfiguration('scen').get('path') || 'scen';
  const execution = new vscode.ShellExecution(program, [
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
}

function deactivate() {}

module.exports = { activate, deactivate, checkTask };
