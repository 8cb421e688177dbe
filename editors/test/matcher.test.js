// The problem matcher of the VS Code extension reads what
// `scen check --format json` prints: every diagnostic of the bad-input
// corpus (tests/bad_inputs) is one line that the matcher's regexp matches,
// with the file, position, severity, code and message of the JSON object.
// The `scen` binary is $SCEN, or target/release/scen.
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const fs = require('fs');
const path = require('path');
const { spawnSync } = require('child_process');
const { ROOT } = require('./tokenize');

const SCEN = process.env.SCEN || path.join(ROOT, 'target', 'release', 'scen');
const CORPUS = path.join(ROOT, 'tests', 'bad_inputs');
const manifest = JSON.parse(fs.readFileSync(path.join(__dirname, '..', 'vscode', 'package.json'), 'utf8'));

/** JSON-string escapes as the matcher leaves them: `\"` stays `\"`. */
function escaped(s) {
  return JSON.stringify(s).slice(1, -1);
}

test('the problem matcher reads every diagnostic of `scen check --format json`', () => {
  assert.ok(fs.existsSync(SCEN), `no scen binary at ${SCEN}: run \`cargo build --release\` or set SCEN`);
  const matcher = manifest.contributes.problemMatchers.find((m) => m.name === 'scen');
  const p = matcher.pattern;
  const regexp = new RegExp(p.regexp);
  const files = fs.readdirSync(CORPUS).filter((f) => f.endsWith('.scen')).sort();
  assert.ok(files.length >= 40, `only ${files.length} bad inputs`);
  const out = spawnSync(SCEN, ['check', '--format', 'json', ...files], { cwd: CORPUS, encoding: 'utf8' });
  assert.strictEqual(out.status, 2, `scen check exit status ${out.status}: ${out.stderr}`);
  const lines = out.stdout.split('\n').filter((l) => l !== '');
  assert.ok(lines.length >= files.length, `${lines.length} diagnostics for ${files.length} files`);
  const problems = [];
  const seen = new Set();
  for (const line of lines) {
    const d = JSON.parse(line);
    const m = regexp.exec(line);
    if (!m) {
      problems.push(`not matched: ${line}`);
      continue;
    }
    const got = {
      severity: m[p.severity], code: m[p.code], message: m[p.message], file: m[p.file],
      line: m[p.line], column: m[p.column], endLine: m[p.endLine], endColumn: m[p.endColumn],
    };
    const want = {
      severity: d.severity, code: d.code, message: escaped(d.message), file: escaped(d.file),
      line: String(d.line), column: String(d.column),
      endLine: String(d.end_line), endColumn: String(d.end_column),
    };
    if (JSON.stringify(got) !== JSON.stringify(want)) {
      problems.push(`misread: ${line}\n    got  ${JSON.stringify(got)}\n    want ${JSON.stringify(want)}`);
    }
    seen.add(path.basename(d.file));
  }
  // A file with an `# at: OTHER` header is reported in OTHER.
  const pointsElsewhere = (f) => /^# at:/m.test(fs.readFileSync(path.join(CORPUS, f), 'utf8'));
  const silent = files.filter((f) => !seen.has(f) && !pointsElsewhere(f));
  assert.deepStrictEqual(silent, [], 'files without a diagnostic pointing into them');
  assert.deepStrictEqual(problems, []);
});
