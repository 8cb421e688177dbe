//! `docs/planners.md` is the planner registry as Markdown
//! (`scen::planners::registry::reference`): it fails when the committed
//! file is stale. `SCEN_BLESS=1 cargo test --release --test docs` rewrites
//! it.

use std::path::PathBuf;

#[test]
fn the_planner_reference_is_up_to_date() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/planners.md");
    let generated = scen::planners::registry::reference();
    if std::env::var_os("SCEN_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().expect("docs/")).expect("create docs/");
        std::fs::write(&path, &generated).expect("write docs/planners.md");
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "docs/planners.md is stale: run `SCEN_BLESS=1 cargo test --release --test docs`"
    );
}
