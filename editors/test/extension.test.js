// The extension (vscode/extension.js), with stand-ins for the `vscode` and
// `vscode-languageclient` modules: it starts `scen lsp` when `scen` is found
// ($SCEN, the binary under test), and always provides the task
// `scen: check` that runs `scen check --format json ${file}` with the
// `$scen` problem matcher (the fallback when `scen` is not found).
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const Module = require('module');

/** A minimal `vscode` API: what extension.js uses, recording its calls. */
function fakeVscode(settings) {
  const providers = {};
  const messages = [];
  return {
    providers,
    messages,
    window: { showInformationMessage: (m) => messages.push(m) },
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

/** A stand-in for vscode-languageclient, recording the clients started. */
function fakeLanguageClient() {
  const started = [];
  class LanguageClient {
    constructor(id, name, server, options) {
      Object.assign(this, { id, name, server, options });
    }
    start() {
      started.push(this);
      return Promise.resolve();
    }
    stop() {
      return Promise.resolve();
    }
    dispose() {}
  }
  return { started, module: { LanguageClient } };
}

/**
 * The extension with `vscode` and `vscode-languageclient/node` replaced by
 * the stand-ins, both while it loads and while each of its functions runs
 * (it requires the language client lazily, in `activate`, so that it works
 * without one when `scen` is not found).
 */
function loadExtension(vscode, languageClient = fakeLanguageClient()) {
  const withStandIns = (f) => {
    const load = Module._load;
    Module._load = function (request, ...rest) {
      if (request === 'vscode') return vscode;
      if (request === 'vscode-languageclient/node') return languageClient.module;
      return load.call(this, request, ...rest);
    };
    try {
      return f();
    } finally {
      Module._load = load;
    }
  };
  const extension = withStandIns(() => {
    const file = require.resolve('../vscode/extension.js');
    delete require.cache[file];
    return require(file);
  });
  const wrapped = {};
  for (const [name, value] of Object.entries(extension)) {
    wrapped[name] =
      typeof value === 'function' ? (...args) => withStandIns(() => value(...args)) : value;
  }
  return wrapped;
}

const path = require('path');
const SCEN = process.env.SCEN || path.join(__dirname, '..', '..', 'target', 'release', 'scen');

test('the language server `scen lsp` starts when `scen` is found', () => {
  const vscode = fakeVscode({ 'scen.path': SCEN });
  const client = fakeLanguageClient();
  const context = { subscriptions: [] };
  loadExtension(vscode, client).activate(context);
  assert.strictEqual(client.started.length, 1);
  const [started] = client.started;
  assert.deepStrictEqual(started.server, { command: SCEN, args: ['lsp'] });
  assert.deepStrictEqual(started.options.documentSelector[0], { scheme: 'file', language: 'scen' });
  assert.strictEqual(context.subscriptions.length, 2);
  assert.deepStrictEqual(vscode.messages, []);
});

test('without `scen`, the task remains and the user is told', () => {
  const vscode = fakeVscode({ 'scen.path': '/nonexistent/scen' });
  const client = fakeLanguageClient();
  const context = { subscriptions: [] };
  loadExtension(vscode, client).activate(context);
  assert.strictEqual(client.started.length, 0);
  assert.strictEqual(context.subscriptions.length, 1);
  assert.strictEqual(vscode.messages.length, 1);
  assert.match(vscode.messages[0], /scen: check/);
});

test('the task provider runs `scen check --format json` with the $scen matcher', () => {
  const vscode = fakeVscode({ 'scen.server.enable': false });
  const context = { subscriptions: [] };
  loadExtension(vscode).activate(context);
  assert.strictEqual(context.subscriptions.length, 1);
  assert.deepStrictEqual(vscode.messages, []);
  const [task] = vscode.providers.scen.provideTasks();
  assert.strictEqual(task.name, 'check');
  assert.strictEqual(task.source, 'scen');
  assert.strictEqual(task.execution.command, 'scen');
  assert.deepStrictEqual(task.execution.args, ['check', '--format', 'json', '${file}']);
  assert.deepStrictEqual(task.problemMatchers, ['$scen']);
});

test('a `"type": "scen"` task of tasks.json is resolved; `scen.path` is used', () => {
  const vscode = fakeVscode({ 'scen.path': '/opt/scen/bin/scen', 'scen.server.enable': false });
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
  assert.strictEqual(c.configuration.properties['scen.server.enable'].default, true);
  assert.ok(manifest.dependencies['vscode-languageclient']);
  assert.ok(manifest.activationEvents.includes('onLanguage:scen'));
});
