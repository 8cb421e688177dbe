//! Reading files: the main `.scen` file, its includes (resolved relative to
//! the including file, cycles refused) and size/encoding checks, so that no
//! input can exhaust memory.

use std::io::Read;
use std::path::{Path, PathBuf};

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
pub(crate) struct SourcedStmt {
    pub stmt: ast::Stmt,
    pub in_main_file: bool,
}

/// Reads, parses and analyses a scenario file.
pub fn load(path: &Path) -> Result<Scenario, LoadFailure> {
    let mut sources = SourceMap::default();
    let mut diags = Vec::new();
    let mut statements = Vec::new();
    match read_text(path, MAX_SCEN_BYTES, None, "scenario", &mut sources) {
        Ok(id) => {
            let mut stack = vec![canonical(path)];
            parse_into(
                id,
                true,
                &mut stack,
                &mut sources,
                &mut statements,
                &mut diags,
            );
        }
        Err(d) => diags.push(d),
    }
    if diags.iter().any(Diag::is_error) {
        crate::diagnostics::sort_diags(&mut diags);
        return Err(LoadFailure { sources, diags });
    }
    super::analyze(path, statements, sources)
}

fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

fn parse_into(
    id: FileId,
    in_main_file: bool,
    stack: &mut Vec<PathBuf>,
    sources: &mut SourceMap,
    out: &mut Vec<SourcedStmt>,
    diags: &mut Vec<Diag>,
) {
    let Some(file) = sources.get(id) else { return };
    let text = file.text.clone();
    let dir = file
        .path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let (ast, mut errors) = syntax::parse(&text, id);
    diags.append(&mut errors);
    for stmt in ast.statements {
        if let ast::Stmt::Include { path, span } = &stmt {
            let target = dir.join(&path.value);
            let canon = canonical(&target);
            if stack.contains(&canon) {
                diags.push(
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
                diags.push(
                    Diag::error("scen::load::include_depth", "includes nest too deeply")
                        .at(
                            *span,
                            format!("more than {MAX_INCLUDE_DEPTH} nested includes"),
                        )
                        .help("flatten the chain of includes"),
                );
                continue;
            }
            match read_text(
                &target,
                MAX_SCEN_BYTES,
                Some(path.span),
                "included",
                sources,
            ) {
                Ok(child) => {
                    stack.push(canon);
                    parse_into(child, false, stack, sources, out, diags);
                    stack.pop();
                }
                Err(d) => diags.push(d),
            }
            continue;
        }
        out.push(SourcedStmt { stmt, in_main_file });
    }
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
        return Err(Diag::error(
            "scen::load::too_large",
            format!(
                "{what} file `{}` is larger than the limit of {} MiB",
                path.display(),
                max_bytes >> 20
            ),
        )
        .at(Span::new(id, 0, 0), "file too large")
        .help("split the scenario with `include`, or load large maps with `grid \"file.map\"`"));
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
