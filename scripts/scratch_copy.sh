# Sourced by check_new_planner.sh and check_new_robot.sh: a copy of HEAD (a
# fresh git repository in a temporary folder, removed on exit) to change in
# a scratch, built in target/check_new_planner (apart from target/release,
# whose dependencies it copies the first time: not links, a rebuild there
# must not write into target/release). Sets `repo`, `work` and `step`, and
# leaves the shell in the copy.
#
#   source "$(dirname "$0")/scratch_copy.sh" TAG
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$repo/target/check_new_planner}"
if [ ! -d "$CARGO_TARGET_DIR/release" ] && [ -d "$repo/target/release/deps" ]; then
  mkdir -p "$CARGO_TARGET_DIR/release"
  for dir in deps build .fingerprint; do
    cp -a --reflink=auto "$repo/target/release/$dir" "$CARGO_TARGET_DIR/release/"
  done
fi
work="$(mktemp -d "${TMPDIR:-/tmp}/scen-$1.XXXXXX")"
trap 'rm -rf "$work"' EXIT
step() { printf '\n=== %s\n' "$*"; }

step "a copy of $(git -C "$repo" rev-parse --short HEAD) in $work/repo"
mkdir "$work/repo"
git -C "$repo" archive HEAD | tar -x -C "$work/repo"
cd "$work/repo"
git init -q
git add -A
git -c user.name=check -c user.email=check@localhost commit -qm "HEAD of $repo"
