#!/usr/bin/env bash
# Tests of the editor support (called by scripts/test.sh; needs Node.js and
# npm, and uses Vim when it is installed):
# - installs the pinned test tools (package-lock.json) with `npm ci`;
# - vscode-tmgrammar-test: the annotated files test/grammar/*.scen;
# - node --test test/*.test.js: every scenario in scenarios/ is coloured
#   without `invalid` scopes; Vim colours like VS Code; the problem matcher
#   reads `scen check --format json` on tests/bad_inputs.
# The `scen` binary is $SCEN, else target/release/scen (built if missing).
set -euo pipefail
cd "$(dirname "$0")"

if ! command -v npm >/dev/null; then
  echo "editors/test.sh: npm is required (Node.js 18 or later)" >&2
  exit 1
fi
npm ci --no-audit --no-fund --loglevel=error

if [ -z "${SCEN:-}" ]; then
  export SCEN="$PWD/../target/release/scen"
  [ -x "$SCEN" ] || (cd .. && cargo build --release --quiet)
fi

node_modules/.bin/vscode-tmgrammar-test --config vscode/package.json \
  -g vscode/syntaxes/scen.tmLanguage.json 'test/grammar/*.scen'
node --test test/*.test.js
