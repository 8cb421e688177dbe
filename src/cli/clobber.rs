//! An output never replaces an input (SPEC §4): `scen run a.scen --csv
//! a.scen`, `scen falsify fam.scen --out fam.scen` or an `--out` onto an
//! include, a map or a part given to `merge` would destroy the file the run
//! reads. Every command checks its output paths against the files it reads
//! once it knows them (after loading, before any planner runs) and refuses,
//! naming both, with exit 2 and nothing written.
//!
//! Paths are compared as files, not as text ([`file_identity`]): a symbolic
//! link, a hard link or `./d/../a.scen` is caught, and an output that does
//! not exist yet cannot be an input.

use std::path::Path;

use crate::diagnostics::SourceMap;
use crate::files::file_identity;

/// A file the command reads, and what it is to the command (for the
/// message: "the scenario", "a part given to `merge`", ...).
pub(crate) struct Input<'a> {
    pub path: &'a Path,
    pub role: &'static str,
}

/// The files a loaded scenario read: the scenario itself (the loader reads
/// it first), its includes (`.scen` files) and its map files.
pub(crate) fn scenario_inputs(sources: &SourceMap) -> Vec<Input<'_>> {
    sources
        .files
        .iter()
        .enumerate()
        .map(|(i, f)| Input {
            path: &f.path,
            role: if i == 0 {
                "the scenario"
            } else if f.path.extension().is_some_and(|e| e == "scen") {
                "a file the scenario includes"
            } else {
                "a map file the scenario reads"
            },
        })
        .collect()
}

/// Whether any of `outputs` (each an option and its path, when given)
/// names a file that exists: only such an output can be an input, so the
/// inputs need not be gathered otherwise.
pub(crate) fn any_output_exists<P: AsRef<Path>>(outputs: &[(&str, Option<P>)]) -> bool {
    outputs
        .iter()
        .filter_map(|(_, p)| p.as_ref())
        .any(|p| file_identity(p.as_ref()).is_some())
}

/// The first of `outputs` (each an option and its path, when given) that
/// is one of `inputs`, as an error naming both.
pub(crate) fn output_is_input<P: AsRef<Path>>(
    outputs: &[(&str, Option<P>)],
    inputs: &[Input<'_>],
) -> Result<(), String> {
    for (flag, path) in outputs {
        let Some(path): Option<&Path> = path.as_ref().map(|p| p.as_ref()) else {
            continue;
        };
        let Some(out) = file_identity(path) else {
            continue;
        };
        if let Some(input) = inputs
            .iter()
            .find(|i| file_identity(i.path).as_ref() == Some(&out))
        {
            return Err(format!(
                "`{flag}` would write `{}`, which is `{}`, {}: an output never replaces a file the command reads; choose another path (nothing was written)",
                path.display(),
                input.path.display(),
                input.role
            ));
        }
    }
    Ok(())
}

/// [`output_is_input`], the refusal printed; `false` when refused.
pub(crate) fn outputs_are_not_inputs<P: AsRef<Path>>(
    outputs: &[(&str, Option<P>)],
    inputs: &[Input<'_>],
) -> bool {
    match output_is_input(outputs, inputs) {
        Ok(()) => true,
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_existing_output_that_is_an_input_is_refused_by_any_path() {
        let dir = std::env::temp_dir().join(format!("scen-clobber-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("d")).unwrap();
        let scen = dir.join("a.scen");
        std::fs::write(&scen, "robot p point\n").unwrap();
        let inputs = [Input {
            path: &scen,
            role: "the scenario",
        }];
        let same = dir.join("d/../a.scen");
        let e = output_is_input(&[("--csv", Some(&same))], &inputs).unwrap_err();
        assert!(e.contains("`--csv`"), "{e}");
        assert!(e.contains(&same.display().to_string()), "{e}");
        assert!(e.contains(&scen.display().to_string()), "{e}");
        assert!(e.contains("the scenario"), "{e}");
        // Another file, a file not written yet, no output: nothing to refuse.
        let other = dir.join("b.csv");
        std::fs::write(&other, "").unwrap();
        let missing = dir.join("c.csv");
        assert!(output_is_input(&[("--csv", Some(&other))], &inputs).is_ok());
        assert!(output_is_input(&[("--csv", Some(&missing))], &inputs).is_ok());
        assert!(output_is_input(&[("--csv", None::<&Path>)], &inputs).is_ok());
        assert!(any_output_exists(&[("--csv", Some(&other))]));
        assert!(!any_output_exists(&[
            ("--csv", Some(&missing)),
            ("--svg", None)
        ]));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
