#!/usr/bin/env bash
# Proves that adding a planner is its file plus one registry line, and one
# command to regenerate what is generated (issue 22). In a copy of HEAD (a
# fresh git repository in a temporary folder), it
# 1. adds a trivial planner `straight` (the straight line from the start to
#    the goal, found when the motion checker accepts it) in crates/planners/src/planners/straight.rs
#    and its one line in crates/planners/src/planners/registry.rs;
# 2. shows that the tests of generated files now fail, naming the command;
# 3. runs that command, scripts/regenerate.sh;
# 4. runs the tests that list planners (the registry's own, docs, editors,
#    lsp, contract, start_is_goal, limits), `cargo fmt --check`, the editors'
#    grammar tests (editors/test.sh, when npm is there) and a scenario with
#    the new planner;
# 5. checks that `git status` lists only the new file, the registry line and
#    the regenerated files.
# CI runs it after the tests (.ci/run): it builds the crate (in
# target/check_new_planner, apart from target/release, whose dependencies it
# copies the first time; about 2.5 minutes on 2 cores) and runs the tests
# that list planners. Extra arguments go to cargo, e.g.
# `scripts/check_new_planner.sh --no-default-features` (no viewer).
set -euo pipefail
# A copy of HEAD to change, and its build folder.
source "$(dirname "$0")/scratch_copy.sh" new-planner

step "1. the planner's file and its registry line"
cat > crates/planners/src/planners/straight.rs <<'EOF'
//! `straight`: the straight line from the start to the goal, found when
//! the motion checker accepts it (scripts/check_new_planner.sh adds it).

use std::any::Any;

use crate::contract::schema::RobotKind;
use crate::contract::{PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::geometry::motion::MotionChecker;
use crate::planners::deadline::Deadline;

pub static PLANNER: Planner = Planner {
    kind: "straight",
    summary: "the straight line from the start to the goal, when it is free",
    robots: &[RobotKind::Point, RobotKind::Disk, RobotKind::Polygon],
    params: &[],
    metrics: &[],
    limits: &["time"],
    needs_goal: true,
    randomized: false,
    grids: false,
    time: false,
    check,
};

#[derive(Debug)]
struct StraightSettings;

fn check(_: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    Some(Box::new(StraightSettings))
}

impl Settings for StraightSettings {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        if task.start_is_goal() {
            return PlanOutcome::at_goal(task.start);
        }
        if Deadline::start(&task.limits).passed() {
            return PlanOutcome {
                gave_up: true,
                notes: vec!["the time limit was reached before the line was checked".into()],
                ..PlanOutcome::default()
            };
        }
        let Some(goal) = task.goal else {
            return PlanOutcome::default();
        };
        let line = vec![task.start, goal];
        let free = MotionChecker::new(task.world, task.robot).motion_free(task.start, goal);
        PlanOutcome {
            cost: free.then(|| (goal.x - task.start.x).hypot(goal.y - task.start.y)),
            path: free.then_some(line),
            expanded: 1,
            ..PlanOutcome::default()
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
EOF
# The one line, last in the `planners! { ... }` list.
awk '/^planners! \{/ { inside = 1 }
     inside && /^\}/ { print "    #[path = \"straight.rs\"] straight::PLANNER,"; inside = 0 }
     { print }' crates/planners/src/planners/registry.rs > "$work/registry.rs"
cp "$work/registry.rs" crates/planners/src/planners/registry.rs
git diff crates/planners/src/planners/registry.rs
[ "$(git diff --numstat crates/planners/src/planners/registry.rs)" = "$(printf '1\t0\tcrates/planners/src/planners/registry.rs')" ] \
  || { echo "the registry change is not one added line" >&2; exit 1; }

step "2. before regenerating, the generated files are stale"
if stale="$(cargo test --release --no-fail-fast "$@" --test docs --test editors -- up_to_date 2>&1)"; then
  echo "the tests of generated files pass with a planner they do not list" >&2
  exit 1
fi
grep -E 'stale.*scripts/regenerate.sh' <<<"$stale"
[ "$(grep -cE 'stale.*scripts/regenerate.sh' <<<"$stale")" = 3 ] \
  || { echo "not all three tests (docs: the reference and the pages' lists; editors) name the command:" >&2; echo "$stale" >&2; exit 1; }

step "3. scripts/regenerate.sh $*"
scripts/regenerate.sh "$@" > "$work/regenerate.log" 2>&1 \
  || { cat "$work/regenerate.log" >&2; exit 1; }
grep -E '^test |test result' "$work/regenerate.log"

step "4. the tests that list planners"
cargo fmt --check
# (A test-name filter would apply to every target: the registry's unit
# tests run apart.)
{
  cargo test --release "$@" --lib planners::registry &&
  cargo test --release "$@" \
    --test docs --test editors --test lsp --test contract --test start_is_goal --test limits
} > "$work/tests.log" 2>&1 || { cat "$work/tests.log" >&2; exit 1; }
grep -E '^test |test result' "$work/tests.log"
cat > "$work/straight.scen" <<'EOF'
scenario "straight"
world {
  bounds (0, 0) (10, 10)
  rect wall (4, 6) (6, 10)
}
robot r disk 0.5
plan below straight r { start (1, 1) goal (9, 1) }
plan across straight r { start (1, 9) goal (9, 9) }
expect below.found and below.collision_free and below.length ~ 8 +- 1e-9
expect not across.found
EOF
"$CARGO_TARGET_DIR/release/scen" test "$work/straight.scen"
# The grammars colour the new kind as a planner (editors/test.sh installs
# their test tools; needs npm).
if command -v npm >/dev/null; then
  SCEN="$CARGO_TARGET_DIR/release/scen" bash editors/test.sh > "$work/editors.log" 2>&1 \
    || { cat "$work/editors.log" >&2; exit 1; }
  grep -E '^(✓|ok|# (pass|fail))' "$work/editors.log"
  node editors/test/tokenize.js "$work/straight.scen" | grep '"straight"' | tee "$work/tokens"
  [ "$(grep -c 'support.type.planner.scen' "$work/tokens")" = 2 ] \
    || { echo "VS Code does not colour \`straight\` as a planner kind" >&2; exit 1; }
else
  echo "editors/test.sh skipped: no npm"
fi

step "5. git status: the new file, the registry line and the regenerated files only"
git status --porcelain
expected=' M README.md
 M crates/planners/src/planners/registry.rs
 M docs/diagnostics.md
 M docs/language.md
 M docs/planners.md
 M docs/tutorial.md
 M editors/vim/syntax/scen.vim
 M editors/vscode/snippets/plans.generated.json
 M editors/vscode/syntaxes/scen.tmLanguage.json
?? crates/planners/src/planners/straight.rs'
if [ "$(git status --porcelain | sort)" != "$expected" ]; then
  echo "git status lists other changes; expected:" >&2
  echo "$expected" >&2
  exit 1
fi
git diff --stat
echo
echo "OK: a planner is its file, one registry line and scripts/regenerate.sh"
