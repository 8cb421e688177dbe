// Tokenizes .scen files with the extension's TextMate grammar, using the
// engine of VS Code (vscode-textmate and vscode-oniguruma, installed with
// vscode-tmgrammar-test).
'use strict';

const fs = require('fs');
const path = require('path');
const vsctm = require('vscode-textmate');
const oniguruma = require('vscode-oniguruma');

const GRAMMAR = path.join(__dirname, '..', 'vscode', 'syntaxes', 'scen.tmLanguage.json');

/** The grammar, loaded once per process. */
async function loadGrammar() {
  const wasm = fs.readFileSync(require.resolve('vscode-oniguruma/release/onig.wasm'));
  await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
  const registry = new vsctm.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (sources) => new oniguruma.OnigScanner(sources),
      createOnigString: (s) => new oniguruma.OnigString(s),
    }),
    loadGrammar: async (scopeName) => {
      if (scopeName !== 'source.scen') return null;
      return vsctm.parseRawGrammar(fs.readFileSync(GRAMMAR, 'utf8'), GRAMMAR);
    },
  });
  return registry.loadGrammar('source.scen');
}

/** Every token of `text`: { line, column (1-based), text, scopes }. */
function tokenize(grammar, text) {
  const tokens = [];
  let stack = vsctm.INITIAL;
  text.split(/\r?\n/).forEach((line, k) => {
    const result = grammar.tokenizeLine(line, stack);
    for (const t of result.tokens) {
      tokens.push({
        line: k + 1,
        column: t.startIndex + 1,
        text: line.slice(t.startIndex, t.endIndex),
        scopes: t.scopes,
      });
    }
    stack = result.ruleStack;
  });
  return tokens;
}

const ROOT = path.join(__dirname, '..', '..');

/** Whether `p` holds MovingAI's rows of a team (first word `version`):
 * data that teams read, not a scenario. */
function isMovingaiRows(p) {
  return fs.readFileSync(p, 'utf8').trimStart().split(/\s+/, 1)[0] === 'version';
}

/** Every `*.scen` scenario under `dir` (MovingAI rows left out), sorted. */
function scenFiles(dir) {
  const out = [];
  for (const entry of fs.readdirSync(dir, { withFileTypes: true })) {
    const p = path.join(dir, entry.name);
    if (entry.isDirectory()) out.push(...scenFiles(p));
    else if (entry.name.endsWith('.scen') && !isMovingaiRows(p)) out.push(p);
  }
  return out.sort();
}

/** The problems of one file's tokens. */
function misScoped(tokens) {
  const problems = [];
  for (const t of tokens) {
    if (t.text.trim() === '') continue;
    const where = `${t.line}:${t.column} ${JSON.stringify(t.text)}`;
    const invalid = t.scopes.find((s) => s.startsWith('invalid.'));
    const inner = t.scopes[t.scopes.length - 1];
    if (invalid) problems.push(`${where}: ${invalid}`);
    else if (inner === 'source.scen' || inner.startsWith('meta.')) {
      problems.push(`${where}: no scope of its own (${t.scopes.join(' ')})`);
    }
  }
  return problems;
}

module.exports = { loadGrammar, tokenize, scenFiles, misScoped, ROOT };

// `node tokenize.js FILE`: prints the tokens, for writing grammar tests.
if (require.main === module) {
  loadGrammar().then((grammar) => {
    const text = fs.readFileSync(process.argv[2], 'utf8');
    for (const t of tokenize(grammar, text)) {
      if (t.text.trim() === '') continue;
      console.log(`${t.line}:${t.column}\t${JSON.stringify(t.text)}\t${t.scopes.slice(1).join(' ')}`);
    }
  });
}
