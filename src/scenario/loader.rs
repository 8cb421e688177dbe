//! Reading files: the main `.scen` file, its includes (resolved relative to
//! the including file, cycles refused) and size/encoding checks, so that no
//! input can exhaust memory.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::diagnostics::{Diag, FileId, SourceMap, Span};
use crate::syntax::{self, ast};

use super::Scenario;

/// The largest `.scen` file accepted.
pub const MAX_SCEN_BYTES: u64 = 4 << 20;
/// The largest map file (`grid "x.map"`) accepted.
pub const MAX_MAP_BYTES: u64 = 64 << 20;
/// How deep includes may nest.
const MAX_INCLUDE_DEPTH: usize = 32;

/// A scenario that could not be loaded: all its diagnostics and the sources
/// they point into.
#[derive(Debug)]
pub struct LoadFailure {
    pub sources: SourceMap,
    pub diags: Vec<Diag>,
}

/// A statement and whether it comes from the main file.
#[derive(Clone, Debug)]
pub(crate) struct SourcedStmt {
    pub stmt: ast::Stmt,
    pub in_main_file: bool,
}

/// The text of `.scen` files that are not (only) on disk: the language
/// server's open documents, by canonical path. The loader asks it first,
/// for the main file and for every include.
pub type Overlay<'a> = &'a dyn Fn(&Path) -> Option<Arc<str>>;

/// A scenario's files read and parsed, includes spliced in, before analysis.
#[derive(Debug, Default)]
pub(crate) struct Parsed {
    pub sources: SourceMap,
    pub statements: Vec<SourcedStmt>,
    /// Every `include` that was followed: the span of its path string and
    /// the file it read.
    pub includes: Vec<(Span, FileId)>,
    /// Read and syntax errors (analysis adds its own).
    pub diags: Vec<Diag>,
}

/// Reads, parses and analyses a scenario file.
pub fn load(path: &Path) -> Result<Scenario, LoadFailure> {
    load_with(path, &|_| None)
}

/// [`load`], with the text of the files in `overlay` instead of the disk's.
pub fn load_with(path: &Path, overlay: Overlay<'_>) -> Result<Scenario, LoadFailure> {
    let mut parsed = parse_scenario(path, overlay);
    if parsed.diags.iter().any(Diag::is_error) {
        crate::diagnostics::sort_diags(&mut parsed.diags);
        return Err(LoadFailure {
            sources: parsed.sources,
            diags: parsed.diags,
        });
    }
    super::analyze(path, parsed.statements, parsed.sources)
}

/// Reads and parses a scenario file and its includes (the first half of
/// [`load_with`]); the main file is [`FileId`] 0 when it could be read.
pub(crate) fn parse_scenario(path: &Path, overlay: Overlay<'_>) -> Parsed {
    let mut parsed = Parsed::default();
    match read_scen(path, None, "scenario", overlay, &mut parsed.sources) {
        Ok(id) => {
            let mut stack = vec![canonical(path)];
            parse_into(id, true, &mut stack, overlay, &mut parsed);
        }
        Err(d) => parsed.diags.push(d),
    }
    parsed
}

pub(crate) fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

fn parse_into(
    id: FileId,
    in_main_file: bool,
    stack: &mut Vec<PathBuf>,
    overlay: Overlay<'_>,
    parsed: &mut Parsed,
) {
    let Some(file) = parsed.sources.get(id) else {
        return;
    };
    let text = file.text.clone();
    let dir = file
        .path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let (ast, mut errors) = syntax::parse(&text, id);
    parsed.diags.append(&mut errors);
    for stmt in ast.statements {
        if let ast::Stmt::Include { path, span } = &stmt {
            let target = dir.join(&path.value);
            let canon = canonical(&target);
            if stack.contains(&canon) {
                parsed.diags.push(
                    Diag::error(
                        "scen::load::include_cycle",
                        format!("`{}` includes itself (through {} file(s))", path.value, stack.len()),
                    )
                    .at(path.span, "this include closes a cycle")
                    .help("remove one of the includes; a file may be included only once along a chain"),
                );
                continue;
            }
            if stack.len() >= MAX_INCLUDE_DEPTH {
                parsed.diags.push(
                    Diag::error("scen::load::include_depth", "includes nest too deeply")
                        .at(
                            *span,
                            format!("more than {MAX_INCLUDE_DEPTH} nested includes"),
                        )
                        .help("flatten the chain of includes"),
                );
                continue;
            }
            match read_scen(
                &target,
                Some(path.span),
                "included",
                overlay,
                &mut parsed.sources,
            ) {
                Ok(child) => {
                    parsed.includes.push((path.span, child));
                    stack.push(canon);
                    parse_into(child, false, stack, overlay, parsed);
                    stack.pop();
                }
                Err(d) => parsed.diags.push(d),
            }
            continue;
        }
        parsed.statements.push(SourcedStmt { stmt, in_main_file });
    }
}

/// A `.scen` file's text: the overlay's if it has the file, else the disk's
/// (see [`read_text`]). Both are held to [`MAX_SCEN_BYTES`].
#[allow(clippy::result_large_err)]
fn read_scen(
    path: &Path,
    from: Option<Span>,
    what: &str,
    overlay: Overlay<'_>,
    sources: &mut SourceMap,
) -> Result<FileId, Diag> {
    match overlay(&canonical(path)) {
        Some(text) if text.len() as u64 <= MAX_SCEN_BYTES => Ok(sources.add(path, text)),
        Some(_) => {
            let id = sources.add(path, "");
            Err(too_large(path, MAX_SCEN_BYTES, what, id))
        }
        None => read_text(path, MAX_SCEN_BYTES, from, what, sources),
    }
}

fn too_large(path: &Path, max_bytes: u64, what: &str, id: FileId) -> Diag {
    Diag::error(
        "scen::load::too_large",
        format!(
            "{what} file `{}` is larger than the limit of {} MiB",
            path.display(),
            max_bytes >> 20
        ),
    )
    .at(Span::new(id, 0, 0), "file too large")
    .help("split the scenario with `include`, or load large maps with `grid \"file.map\"`")
}

/// Reads a text file into the source map. `from` is the span that named the
/// file (an include or a grid), where a failure is reported.
/// (The error is a full diagnostic; it is returned once per file read.)
#[allow(clippy::result_large_err)]
pub(crate) fn read_text(
    path: &Path,
    max_bytes: u64,
    from: Option<Span>,
    what: &str,
    sources: &mut SourceMap,
) -> Result<FileId, Diag> {
    let fail = |message: String, label: &str, help: &str| {
        let d = Diag::error("scen::load::read", message).help(help.to_string());
        match from {
            Some(span) => d.at(span, label.to_string()),
            None => d,
        }
    };
    if path.is_dir() {
        return Err(fail(
            format!("`{}` is a folder, not a {what} file", path.display()),
            "a folder",
            "name a file",
        ));
    }
    let file = std::fs::File::open(path).map_err(|e| {
        fail(
            format!("cannot read {what} file `{}`: {e}", path.display()),
            "cannot be read",
            if from.is_some() {
                "paths are relative to the folder of the file that names them"
            } else {
                "check the file's path"
            },
        )
    })?;
    let mut bytes = Vec::new();
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| {
            fail(
                format!("cannot read {what} file `{}`: {e}", path.display()),
                "cannot be read",
                "check the file's permissions",
            )
        })?;
    if bytes.len() as u64 > max_bytes {
        let id = sources.add(path, "");
        return Err(too_large(path, max_bytes, what, id));
    }
    match String::from_utf8(bytes) {
        Ok(text) => Ok(sources.add(path, text)),
        Err(e) => {
            let valid = e.utf8_error().valid_up_to();
            let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
            let id = sources.add(path, text);
            Err(Diag::error(
                "scen::load::not_utf8",
                format!("{what} file `{}` is not UTF-8 text", path.display()),
            )
            .at(Span::new(id, valid, valid + 1), "invalid UTF-8 here")
            .help("`.scen` files are UTF-8 text; is this a binary file?"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_overlay_is_read_before_the_disk_for_the_main_file_and_includes() {
        let dir = std::env::temp_dir().join(format!("scen-overlay-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let main = dir.join("main.scen");
        let part = dir.join("_part.scen");
        std::fs::write(&main, "this is not a scenario").unwrap();
        std::fs::write(&part, "robot r point\n").unwrap();
        let (main_c, part_c) = (canonical(&main), canonical(&part));
        let overlay = |p: &Path| -> Option<Arc<str>> {
            if p == main_c {
                Some("include \"_part.scen\"\nworld { bounds (0, 0) (2, 2) }\n".into())
            } else if p == part_c {
                Some("robot q point\n".into())
            } else {
                None
            }
        };
        let s = load_with(&main, &overlay).expect("the overlay's text loads");
        assert_eq!(s.robots[0].name, "q");
        let parsed = parse_scenario(&main, &overlay);
        assert_eq!(parsed.includes.len(), 1);
        assert_eq!(
            parsed.sources.snippet(parsed.includes[0].0),
            "\"_part.scen\""
        );
        assert_eq!(parsed.sources.get(parsed.includes[0].1).unwrap().path, part);
        // Without it, the disk's text.
        assert!(load(&main).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
