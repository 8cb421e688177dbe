#!/usr/bin/env bash
# Proves that adding a robot kind is its file plus one registry line, and
# one command to regenerate what is generated (issue 40, item 2). In a copy
# of HEAD (a fresh git repository in a temporary folder), it
# 1. adds a kind `ellipse A B` (an axis-aligned ellipse of semi-axes A and
#    B, as the polygon of 32 sides around it) in
#    crates/geometry/src/robots/ellipse.rs and its one line in
#    crates/geometry/src/robots/mod.rs;
# 2. shows that the tests of the generated robot table (docs/language.md)
#    and editor lists fail, naming the command, and runs that command
#    (scripts/regenerate.sh);
# 3. runs the registry's tests, the docs' and editors' tests and
#    `cargo fmt --check`,
#    and a scenario in which planners for polygons plan for an ellipse and
#    the validator accepts their paths; its picture draws the body;
# 4. checks that `git status` lists only the new file, the registry line
#    and the regenerated page and editor grammars.
# CI runs it after check_new_planner.sh, in the same target folder
# (target/check_new_planner). Extra arguments go to cargo.
set -euo pipefail
# A copy of HEAD to change, and its build folder.
source "$(dirname "$0")/scratch_copy.sh" new-robot

step "1. the kind's file and its registry line"
cat > crates/geometry/src/robots/ellipse.rs <<'EOF'
//! `robot NAME ellipse A B`: an axis-aligned ellipse of semi-axes A (along
//! the robot's x) and B, as the polygon of 32 sides around it (so every
//! check of the polygon holds for the ellipse). Added by
//! scripts/check_new_robot.sh.

use super::{Arg, ArgValue, BodyError, RobotModel};
use crate::{ConvexPolygon, Point, RobotShape};

pub static MODEL: RobotModel = RobotModel {
    keyword: "ellipse",
    summary: "an ellipse of semi-axes A and B about the reference point, as the 32-gon around it",
    example: "robot r ellipse 0.6 0.3",
    args: &[Arg::Length("the semi-axis along x"), Arg::Length("the semi-axis along y")],
    body,
};

const SIDES: usize = 32;

fn body(args: &[ArgValue]) -> Result<RobotShape, BodyError> {
    let mut lengths = RobotModel::lengths(args);
    let (a, b) = (lengths.next().unwrap_or(0.0), lengths.next().unwrap_or(0.0));
    // The regular polygon around the unit circle, stretched.
    let out = 1.0 / (std::f64::consts::PI / SIDES as f64).cos();
    let vertices = (0..SIDES)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / SIDES as f64;
            Point::new(a * out * t.cos(), b * out * t.sin())
        })
        .collect();
    Ok(RobotShape::Polygon(ConvexPolygon { vertices }))
}
EOF
# The one line, last in the `robots! { ... }` list.
awk '/^robots! \{/ { inside = 1 }
     inside && /^\}/ { print "    ellipse,"; inside = 0 }
     { print }' crates/geometry/src/robots/mod.rs > "$work/mod.rs"
cp "$work/mod.rs" crates/geometry/src/robots/mod.rs
git diff crates/geometry/src/robots/mod.rs
[ "$(git diff --numstat crates/geometry/src/robots/mod.rs)" = "$(printf '1\t0\tcrates/geometry/src/robots/mod.rs')" ] \
  || { echo "the registry change is not one added line" >&2; exit 1; }

step "2. the robot table is stale until scripts/regenerate.sh $*"
if stale="$(cargo test --release --no-fail-fast "$@" --test docs --test editors -- up_to_date 2>&1)"; then
  echo "the tests of generated files pass with a robot kind they do not list" >&2
  exit 1
fi
grep -E 'stale.*scripts/regenerate.sh' <<<"$stale"
[ "$(grep -cE 'stale.*scripts/regenerate.sh' <<<"$stale")" = 2 ] \
  || { echo "not both tests (docs: the robot table; editors) name the command:" >&2; echo "$stale" >&2; exit 1; }
scripts/regenerate.sh "$@" > "$work/regenerate.log" 2>&1 \
  || { cat "$work/regenerate.log" >&2; exit 1; }
grep -q '| `ellipse` |' docs/language.md || { echo "docs/language.md does not list the ellipse" >&2; exit 1; }
grep -q 'scenRobotShape contained point disk rect polygon ellipse' editors/vim/syntax/scen.vim \
  || { echo "the Vim syntax does not colour the ellipse" >&2; exit 1; }
grep -q 'point|disk|rect|polygon|ellipse' editors/vscode/syntaxes/scen.tmLanguage.json \
  || { echo "the VS Code grammar does not colour the ellipse" >&2; exit 1; }

step "3. the registry's tests, the docs, and a scenario with the new kind"
cargo fmt --check
{
  cargo test --release "$@" -p scen-geometry robots &&
  cargo test --release "$@" --test docs --test editors
} > "$work/tests.log" 2>&1 || { cat "$work/tests.log" >&2; exit 1; }
grep -E '^test |test result' "$work/tests.log"
cat > "$work/ellipse.scen" <<'EOF'
scenario "an ellipse robot"
world {
  bounds (0, 0) (10, 10)
  rect wall (4, 0) (6, 7)
}
robot e ellipse 0.8 0.4
plan tree rrt_connect e { start (2, 2, 90deg) goal (8, 2, 90deg) seed 3 }
plan grid astar e { start (2, 2, 0deg) goal (8, 2, 0deg) cell 0.5 }
expect tree.found and tree.collision_free
expect grid.found and grid.collision_free
expect grid.clearance > 0
EOF
"$CARGO_TARGET_DIR/release/scen" test "$work/ellipse.scen"
"$CARGO_TARGET_DIR/release/scen" run "$work/ellipse.scen" --svg "$work/ellipse.svg" > /dev/null
grep -c '<polygon' "$work/ellipse.svg" > /dev/null || { echo "the picture draws no polygon" >&2; exit 1; }
# A kind misspelt is suggested from the registry.
printf 'world { bounds (0, 0) (10, 10) }\nrobot e elipse 1 0.5\n' > "$work/typo.scen"
if "$CARGO_TARGET_DIR/release/scen" check "$work/typo.scen" > "$work/typo.log" 2>&1; then
  echo "a misspelt kind was accepted" >&2
  exit 1
fi
grep -q 'did you mean `ellipse`' "$work/typo.log" || { cat "$work/typo.log" >&2; exit 1; }

step "4. git status: the new file, the registry line and the regenerated page only"
git status --porcelain
expected=' M crates/geometry/src/robots/mod.rs
 M docs/language.md
 M editors/vim/syntax/scen.vim
 M editors/vscode/syntaxes/scen.tmLanguage.json
?? crates/geometry/src/robots/ellipse.rs'
if [ "$(git status --porcelain | sort)" != "$expected" ]; then
  echo "git status lists other changes; expected:" >&2
  echo "$expected" >&2
  exit 1
fi
git diff --stat
echo
echo "OK: a robot kind is its file, one registry line and scripts/regenerate.sh"
