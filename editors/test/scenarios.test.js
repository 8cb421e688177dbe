// Every scenario in scenarios/ (globbed now, so new ones are covered) is
// coloured by the TextMate grammar without an `invalid` scope, and every
// character that is not blank gets a scope of its own (a construct the
// grammar does not know would be left with only `source.scen` or a `meta`
// scope).
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const fs = require('fs');
const path = require('path');
const { loadGrammar, tokenize, scenFiles, misScoped, ROOT } = require('./tokenize');


test('every scenario in scenarios/ is scoped without `invalid`', async () => {
  const grammar = await loadGrammar();
  const files = scenFiles(path.join(ROOT, 'scenarios'));
  assert.ok(files.length >= 5, `only ${files.length} scenarios found`);
  const report = [];
  for (const file of files) {
    const problems = misScoped(tokenize(grammar, fs.readFileSync(file, 'utf8')));
    if (problems.length) {
      report.push(`${path.relative(ROOT, file)}:\n  ${problems.join('\n  ')}`);
    }
  }
  assert.strictEqual(report.length, 0, `mis-scoped scenarios:\n${report.join('\n')}`);
});
