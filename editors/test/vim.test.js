// The Vim syntax (editors/vim) gives every scenario in scenarios/ and every
// grammar test file the same colouring classes as the VS Code grammar,
// character by character, and marks no error in the scenarios. Runs Vim
// headless; skipped when `vim` is not installed.
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { execFileSync } = require('child_process');
const { loadGrammar, tokenize, scenFiles, ROOT } = require('./tokenize');
const { textmateClass, vimClass } = require('./classes');

function hasVim() {
  try {
    execFileSync('vim', ['--version'], { stdio: 'ignore' });
    return true;
  } catch {
    return false;
  }
}

/** Vim's groups, for each file in order: Map("line:byteColumn" → [group, linked]). */
function vimGroups(files) {
  const out = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'scen-vim-')), 'groups.txt');
  execFileSync('vim', ['-Nu', 'NONE', '-i', 'NONE', '-es', '--cmd', `let g:out=${JSON.stringify(out)}`,
    '-S', path.join(__dirname, 'vim_dump.vim'), ...files], { stdio: 'inherit', timeout: 120000 });
  const groups = [];
  let current = null;
  for (const line of fs.readFileSync(out, 'utf8').split('\n')) {
    if (line.startsWith('FILE ')) {
      const [, file, filetype] = line.match(/^FILE (.*) (\S*)$/);
      assert.strictEqual(filetype, 'scen', `${file}: Vim did not detect the filetype`);
      current = new Map();
      groups.push(current);
    } else if (line) {
      const [l, c, group, linked] = line.split(':');
      current.set(`${l}:${c}`, [group, linked]);
    }
  }
  return groups;
}

/** Differences between the two editors' classes, one line each. */
function compare(grammar, file, groups) {
  const problems = [];
  const text = fs.readFileSync(file, 'utf8');
  const lines = text.split(/\r?\n/);
  for (const t of tokenize(grammar, text)) {
    const lineText = lines[t.line - 1];
    const tmClass = textmateClass(t.scopes);
    let column = t.column - 1;
    for (const ch of t.text) {
      if (ch.trim() !== '') {
        const byte = Buffer.byteLength(lineText.slice(0, column)) + 1;
        const [group, linked] = groups.get(`${t.line}:${byte}`) || ['?', '?'];
        const vClass = vimClass(group, linked);
        if (vClass !== tmClass) {
          problems.push(`${t.line}:${column + 1} ${JSON.stringify(ch)} in ${JSON.stringify(t.text)}: ` +
            `VS Code ${tmClass} (${t.scopes.slice(1).join(' ')}), Vim ${vClass} (${group})`);
        }
      }
      column += ch.length;
    }
  }
  return problems;
}

const skip = hasVim() ? false : 'vim is not installed';

test('Vim colours like VS Code', { skip }, async () => {
  const grammar = await loadGrammar();
  const scenarios = scenFiles(path.join(ROOT, 'scenarios'));
  const grammarTests = scenFiles(path.join(__dirname, 'grammar'));
  const files = [...scenarios, ...grammarTests];
  const groups = vimGroups(files);
  const report = [];
  assert.strictEqual(groups.length, files.length, 'Vim did not read every file');
  files.forEach((file, k) => {
    const problems = compare(grammar, file, groups[k]);
    if (scenarios.includes(file)) {
      for (const [where, [group, linked]] of groups[k]) {
        if (linked === 'Error') problems.push(`${where}: Vim marks an error (${group})`);
      }
    }
    if (problems.length) report.push(`${path.relative(ROOT, file)}:\n  ${problems.join('\n  ')}`);
  });
  assert.strictEqual(report.length, 0, `Vim and VS Code disagree:\n${report.join('\n')}`);
});

test("Vim's errorformat reads `scen check --format json`", { skip }, () => {
  const scen = process.env.SCEN || path.join(ROOT, 'target', 'release', 'scen');
  assert.ok(fs.existsSync(scen), `no scen binary at ${scen}: run \`cargo build --release\` or set SCEN`);
  const corpus = path.join(ROOT, 'tests', 'bad_inputs');
  const files = fs.readdirSync(corpus).filter((f) => f.endsWith('.scen')).sort();
  let json;
  try {
    json = execFileSync(scen, ['check', '--format', 'json', ...files], { cwd: corpus, encoding: 'utf8' });
  } catch (e) {
    json = e.stdout; // exit status 2: the files are bad
  }
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'scen-vim-'));
  fs.writeFileSync(path.join(dir, 'out.json'), json);
  const out = path.join(dir, 'qf.txt');
  execFileSync('vim', ['-Nu', 'NONE', '-i', 'NONE', '-es', '--cmd', `let g:json=${JSON.stringify(path.join(dir, 'out.json'))}`,
    '--cmd', `let g:out=${JSON.stringify(out)}`, '-S', path.join(__dirname, 'vim_quickfix.vim')],
  { cwd: corpus, stdio: 'inherit', timeout: 60000 });
  const entries = fs.readFileSync(out, 'utf8').split('\n').filter((l) => l);
  const diags = json.split('\n').filter((l) => l).map((l) => JSON.parse(l));
  assert.strictEqual(entries.length, diags.length);
  diags.forEach((d, k) => {
    const want = [d.file, d.line, d.column, d.severity[0], JSON.stringify(d.message).slice(1, -1), 1].join('|');
    assert.strictEqual(entries[k], want);
  });
});
