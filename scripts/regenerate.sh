#!/usr/bin/env bash
# Regenerates every file generated from the planner registry
# (crates/planners/src/planners/registry.rs), the robot kinds
# (crates/geometry/src/robots/mod.rs) and the analyser's lists:
# - docs/planners.md, the planner reference, and the generated blocks of
#   the pages (planner lists, the robot table of docs/language.md;
#   tests/docs.rs);
# - editors/vim/syntax/scen.vim and editors/vscode/syntaxes/scen.tmLanguage.json:
#   their lists of planner kinds, keys, words, limit kinds, metrics,
#   aggregates and bench keys (the parts marked generated), and
#   editors/vscode/snippets/plans.generated.json, the `plan-KIND` snippets
#   (tests/editors.rs).
# Those tests fail, naming this script, when a committed file is stale.
# Extra arguments go to cargo, e.g. `scripts/regenerate.sh --no-default-features`
# (no viewer: a faster first build).
set -euo pipefail
cd "$(dirname "$0")/.."
SCEN_BLESS=1 cargo test --release "$@" --test docs --test editors -- up_to_date
