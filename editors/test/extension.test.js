// The extension's task provider (vscode/extension.js), with a stand-in for
// the `vscode` module: it provides the task `scen: check` that runs
// `scen check --format json ${file}` with the `$scen` problem matcher.
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const Module = require('module');

/** A minimal `vscode` API: what extension.js uses, recording its calls. */
function fakeVscode(settings) {
  const providers = {};
  return {
    providers,
    workspace: { getConfiguration: (section) => ({ get: (key) => settings[`${section}.${key}`] }) },
    tasks: {
      registerTaskProvider: (type, provider) => {
        providers[type] = provider;
        return { dispose() {} };
      },
    },
    ShellExecution: class {
      constructor(command, args) {
        Object.assign(this, { command, args });
      }
    },
    Task: class {
      constructor(definition, scope, name, source, execution, problemMatchers) {
        Object.assign(this, { definition, scope, name, source, execution, problemMatchers });
      }
    },
    TaskGroup: { Build: 'build' },
    TaskRevealKind: { Silent: 'silent' },
    TaskScope: { Workspace: 'workspace' },
  };
}

function loadExtension(vscode) {
  const load = Module._load;
  Module._load = function (request, ...rest) {
    return request === 'vscode' ? vscode : load.call(this, request, ...rest);
  };
  try {
    const file = require.resolve('../vscode/extension.js');
    delete require.cache[file];
    return require(file);
  } finally {
    Module._load = load;
  }
}

test('the task provider runs `scen check --format json` with the $scen matcher', () => {
  const vscode = fakeVscode({});
  const context = { subscriptions: [] };
  loadExtension(vscode).activate(context);
  assert.strictEqual(context.subscriptions.length, 1);
  const [task] = vscode.providers.scen.provideTasks();
  assert.strictEqual(task.name, 'check');
  assert.strictEqual(task.source, 'scen');
  assert.strictEqual(task.execution.command, 'scen');
  assert.deepStrictEqual(task.execution.args, ['check', '--format', 'json', '${file}']);
  assert.deepStrictEqual(task.problemMatchers, ['$scen']);
});

test('a `"type": "scen"` task of tasks.json is resolved; `scen.path` is used', () => {
  const vscode = fakeVscode({ 'scen.path': '/opt/scen/bin/scen' });
  loadExtension(vscode).activate({ subscriptions: [] });
  const provider = vscode.providers.scen;
  const task = provider.resolveTask({ definition: { type: 'scen', file: 'a.scen' }, scope: 'workspace' });
  assert.strictEqual(task.execution.command, '/opt/scen/bin/scen');
  assert.deepStrictEqual(task.execution.args, ['check', '--format', 'json', 'a.scen']);
  assert.strictEqual(provider.resolveTask({ definition: { type: 'scen' }, scope: 'workspace' }), undefined);
});

test('the manifest declares what the provider uses', () => {
  const manifest = require('../vscode/package.json');
  const c = manifest.contributes;
  assert.ok(c.problemMatchers.some((m) => m.name === 'scen'));
  assert.ok(c.taskDefinitions.some((d) => d.type === 'scen'));
  assert.ok(c.configuration.properties['scen.path']);
  assert.ok(manifest.activationEvents.includes('onLanguage:scen'));
});
