//! The planner registry: every planner kind of SPEC 3, one line each.
//!
//! A planner is one file that declares a [`Planner`]: its kind, the robots
//! it plans for, its parameters (type, default, range, help), its metrics,
//! the limits it honours, and a `check` that reads the validated parameters
//! into the planner's own typed [`Settings`] (reporting cross-parameter
//! problems with spans). The settings' [`Settings::plan`] runs the plan.
//! The analyzer, the runner, the language server, the generated planner
//! reference (`docs/planners.md`), the editors' generated word lists and
//! snippets, and the tests that cover every planner read this registry;
//! none of them names a planner.
//!
//! # Adding a planner
//! 1. Write `crates/planners/src/planners/KIND.rs` with `pub static PLANNER: Planner`, its
//!    settings struct (word values as [`word_enum!`](crate::word_enum)
//!    enums, defaults only in the schema) and `impl Settings`. Its module
//!    is `planners::registry::KIND`: reach other modules by `crate::` paths.
//! 2. Add its line to [`PLANNERS`]: `#[path = "KIND.rs"] KIND::PLANNER,`
//!    (the line declares the module too).
//! 3. Run `scripts/regenerate.sh` (`docs/planners.md`, the editors' word
//!    lists and `plan-KIND` snippets).
//!
//! The contract (`tests/contract.rs`: metrics, validator, determinism,
//! limits), `tests/start_is_goal.rs` (found at once:
//! [`Task::start_is_goal`], [`PlanOutcome::at_goal`]), `tests/limits.rs`
//! (a time limit spent before the set-up is done: [`super::deadline`]) and
//! the LSP, docs and editors tests cover it from that line;
//! `scripts/check_new_planner.sh` adds a planner this way and runs them.
//! Add scenarios under `scenarios/` and the planner's own tests.

use super::sampling::{prm, rrt, rrt_connect};
use super::{astar, coverage, online, potential, roadmap};
use crate::contract::Planner;
use crate::contract::schema::{COMMON_METRICS, COMMON_PARAMS, MetricSpec, MetricType, ParamSpec};

/// Declares [`PLANNERS`] from its lines, in their order. A line is
/// `module::ITEM,` for a planner whose module `crates/planners/src/planners/mod.rs`
/// declares (those that are several files, or libraries for others too),
/// or `#[path = "KIND.rs"] KIND::ITEM,` for a one-file planner: the line
/// declares its module, from that file of `crates/planners/src/planners/`.
macro_rules! planners {
    (@lines [$($done:expr,)*]) => {
        /// Every planner kind, in the order the docs list them.
        pub static PLANNERS: &[&Planner] = &[$($done,)*];
    };
    (@lines [$($done:expr,)*] #[path = $file:literal] $module:ident :: $item:ident, $($rest:tt)*) => {
        #[path = $file]
        pub mod $module;
        planners!(@lines [$($done,)* &$module::$item,] $($rest)*);
    };
    (@lines [$($done:expr,)*] $module:ident :: $item:ident, $($rest:tt)*) => {
        planners!(@lines [$($done,)* &$module::$item,] $($rest)*);
    };
    (@lines [$($done:expr,)*] $($bad:tt)*) => {
        compile_error!(concat!(
            "a registry line is `module::ITEM,` or `#[path = \"KIND.rs\"] KIND::ITEM,`, not: ",
            stringify!($($bad)*)
        ));
    };
    ($($lines:tt)*) => {
        planners!(@lines [] $($lines)*);
    };
}

planners! {
    astar::PLANNER,
    online::PLANNER,
    roadmap::PLANNER,
    potential::PLANNER,
    coverage::PLANNER,
    rrt::RRT,
    rrt_connect::PLANNER,
    rrt::RRT_STAR,
    prm::PRM,
    prm::PRM_STAR,
    #[path = "steer.rs"] steer::PLANNER,
    #[path = "hybrid_astar.rs"] hybrid_astar::PLANNER,
    #[path = "bug.rs"] bug::PLANNER,
    #[path = "sipp.rs"] sipp::PLANNER,
    #[path = "cbs.rs"] cbs::PLANNER,
    #[path = "lacam.rs"] lacam::PLANNER,
    #[path = "prioritized.rs"] prioritized::PLANNER,
}

/// The planner of a kind.
pub fn planner(kind: &str) -> Option<&'static Planner> {
    PLANNERS.iter().copied().find(|p| p.kind == kind)
}

/// The planner reference (`docs/planners.md`): every planner's robots,
/// limits, parameters and metrics, and the common ones, as Markdown.
pub fn reference() -> String {
    use crate::contract::schema::{CAR_METRICS, DRIVE, DRIVE_METRICS, DefaultValue, TIME_METRICS};
    use std::fmt::Write as _;
    let mut md = String::from(
        "# Planners\n\n\
         Generated from the planner registry (`crates/planners/src/planners/registry.rs`) by\n\
         `scripts/regenerate.sh`; do not edit by hand.\n",
    );
    let params = |md: &mut String, specs: &mut dyn Iterator<Item = &ParamSpec>| {
        md.push_str("\n| key | value | default | meaning |\n|---|---|---|---|\n");
        for p in specs {
            let default = match p.default {
                DefaultValue::None => "—".to_string(),
                DefaultValue::Derived(how) => how.to_string(),
                other => format!("`{}`", other.text()),
            };
            let _ = writeln!(
                md,
                "| `{}` | {} | {default} | {} |",
                p.key,
                p.value.describe(),
                p.help
            );
        }
    };
    let metrics = |md: &mut String, specs: &mut dyn Iterator<Item = &MetricSpec>| {
        md.push_str("\n| metric | type | meaning |\n|---|---|---|\n");
        for m in specs {
            let ty = match m.ty {
                MetricType::Bool => "true/false",
                MetricType::Num => "number",
            };
            let _ = writeln!(md, "| `{}` | {ty} | {} |", m.name, m.help);
        }
    };
    md.push_str("\n## Every planner\n\nParameters every plan takes (SPEC 2.5):\n");
    params(&mut md, &mut COMMON_PARAMS.iter());
    md.push_str("\nMetrics every plan reports (SPEC 3):\n");
    metrics(&mut md, &mut COMMON_METRICS.iter());
    md.push_str(
        "\nMetrics every plan of a planner that plans for cars reports (measured from the car's \
         segments; no value for a robot that is not a car, or without a path):\n",
    );
    metrics(&mut md, &mut CAR_METRICS.iter());
    md.push_str(
        "\nMetrics every plan of a planner that knows time reports (measured from its trajectory, \
         SPEC 2.9):\n",
    );
    metrics(&mut md, &mut TIME_METRICS.iter());
    for model in DRIVE {
        let _ = writeln!(
            md,
            "\n`drive {} {{ ... }}` — {}. It takes:",
            model.name, model.help
        );
        params(&mut md, &mut model.params.iter());
    }
    md.push_str("\nA plan with `drive` adds the metrics:\n");
    metrics(&mut md, &mut DRIVE_METRICS.iter());
    for p in PLANNERS {
        let robots: Vec<&str> = p.robots.iter().map(|r| r.name()).collect();
        let limits: Vec<String> = p.limits.iter().map(|l| format!("`{l}`")).collect();
        let _ = write!(
            md,
            "\n## `{}` — {}\n\nRobots: {}. Limits: {}. {}\n",
            p.kind,
            p.summary,
            robots.join(", "),
            limits.join(", "),
            if p.needs_goal {
                "Needs a `goal`."
            } else {
                "Needs no `goal`."
            }
        );
        if !p.params.is_empty() {
            params(&mut md, &mut p.params.iter());
        }
        if !p.metrics.is_empty() {
            metrics(&mut md, &mut p.metrics.iter());
        }
    }
    md
}

/// The marker that opens a generated block in a page of the manual or the
/// README: `<!-- generated: NAME -->`, closed by [`GENERATED_END`].
pub const GENERATED_START: &str = "<!-- generated: ";
/// The marker that closes a generated block.
pub const GENERATED_END: &str = "<!-- end of generated -->";

/// The text of a generated block of a page (`scripts/regenerate.sh`
/// rewrites them, `tests/docs.rs` checks them): `planner-list` is every kind
/// in backticks, in the registry's order; `planner-table` a Markdown table
/// of every kind with its robots and summary; `robot-table` one of every
/// robot kind (`scen_geometry::robots`). `None` for an unknown name.
pub fn generated_block(name: &str) -> Option<String> {
    use std::fmt::Write as _;
    match name {
        "planner-list" => {
            let kinds: Vec<String> = PLANNERS.iter().map(|p| format!("`{}`", p.kind)).collect();
            Some(kinds.join(", "))
        }
        "planner-table" => {
            let mut md = String::from("| planner | robots | what it does |\n|---|---|---|\n");
            for p in PLANNERS {
                let robots: Vec<&str> = p.robots.iter().map(|r| r.name()).collect();
                let _ = writeln!(
                    md,
                    "| `{}` | {} | {} |",
                    p.kind,
                    robots.join(", "),
                    p.summary
                );
            }
            Some(md.trim_end().to_string())
        }
        "robot-table" => {
            let mut md = String::from("| kind | written | the body |\n|---|---|---|\n");
            for m in crate::geometry::robots::ROBOTS {
                let _ = writeln!(md, "| `{}` | `{}` | {} |", m.keyword, m.example, m.summary);
            }
            Some(md.trim_end().to_string())
        }
        _ => None,
    }
}

/// `text` with every generated block's content replaced by
/// [`generated_block`]'s, or the name of a block that is unknown or not
/// closed. A block's content sits between its marker line's end and the
/// end marker, each on lines of their own for a table and inline for a list.
pub fn refresh_generated_blocks(text: &str) -> Result<String, String> {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(GENERATED_START) {
        let after_start = &rest[at + GENERATED_START.len()..];
        let Some(close) = after_start.find("-->") else {
            return Err("a generated block's marker is not closed by `-->`".into());
        };
        let name = after_start[..close].trim();
        let content_from = at + GENERATED_START.len() + close + "-->".len();
        let Some(len) = rest[content_from..].find(GENERATED_END) else {
            return Err(format!(
                "the generated block `{name}` has no `{GENERATED_END}`"
            ));
        };
        let Some(block) = generated_block(name) else {
            return Err(format!("no generated block is called `{name}`"));
        };
        let old = &rest[content_from..content_from + len];
        out.push_str(&rest[..content_from]);
        // A block whose marker ends its line keeps its content on lines of
        // its own (a table); an inline one stays inline (a list in prose).
        if old.starts_with('\n') {
            out.push('\n');
            out.push_str(&block);
            out.push('\n');
        } else {
            out.push_str(&block);
        }
        out.push_str(GENERATED_END);
        rest = &rest[content_from + len + GENERATED_END.len()..];
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::schema::{DefaultValue, LIMIT_KINDS, ValueSpec};

    #[test]
    fn generated_blocks_are_refreshed_in_place_and_errors_are_named() {
        let text = "Kinds: <!-- generated: planner-list -->`old`<!-- end of generated -->.\n\
                    <!-- generated: planner-table -->\n| stale |\n<!-- end of generated -->\nend\n";
        let fresh = refresh_generated_blocks(text).expect("known blocks");
        let list = generated_block("planner-list").expect("list");
        assert!(list.starts_with("`astar`, `online`"), "{list}");
        assert!(fresh.starts_with(&format!(
            "Kinds: <!-- generated: planner-list -->{list}<!--"
        )));
        assert!(
            fresh.contains("-->\n| planner | robots | what it does |\n"),
            "{fresh}"
        );
        assert!(!fresh.contains("stale") && fresh.ends_with("<!-- end of generated -->\nend\n"));
        assert_eq!(
            refresh_generated_blocks(&fresh).as_deref(),
            Ok(fresh.as_str())
        );
        let unknown =
            refresh_generated_blocks("<!-- generated: nope -->x<!-- end of generated -->");
        assert_eq!(
            unknown,
            Err("no generated block is called `nope`".to_string())
        );
        let open = refresh_generated_blocks("<!-- generated: planner-list -->x");
        assert!(open.is_err_and(|e| e.contains("planner-list")));
    }

    #[test]
    fn kinds_keys_and_metrics_are_unique() {
        let mut kinds: Vec<_> = PLANNERS.iter().map(|p| p.kind).collect();
        kinds.sort();
        kinds.dedup();
        assert_eq!(kinds.len(), PLANNERS.len());
        for p in PLANNERS {
            let mut keys: Vec<_> = p.all_params().map(|s| s.key).collect();
            keys.sort();
            let n = keys.len();
            keys.dedup();
            assert_eq!(keys.len(), n, "duplicate key in {}", p.kind);
            let mut metrics: Vec<_> = p.all_metrics().map(|m| m.name).collect();
            metrics.sort();
            let n = metrics.len();
            metrics.dedup();
            assert_eq!(metrics.len(), n, "duplicate metric in {}", p.kind);
        }
    }

    #[test]
    fn every_declaration_is_complete() {
        for p in PLANNERS {
            assert!(!p.summary.is_empty() && !p.robots.is_empty(), "{}", p.kind);
            assert!(
                p.limits.iter().all(|l| LIMIT_KINDS.contains(l)),
                "{}",
                p.kind
            );
            for s in p.params {
                assert!(!s.help.is_empty(), "{}.{} has no help", p.kind, s.key);
                if let (ValueSpec::Word(words), DefaultValue::Word(w)) = (s.value, s.default) {
                    assert!(words.contains(&w), "{}.{}: default `{w}`", p.kind, s.key);
                }
            }
            for m in p.metrics {
                assert!(!m.help.is_empty(), "{}.{} has no help", p.kind, m.name);
            }
        }
    }
}
