//! `scen fmt [FILE...] [--check]`: files and folders (every `*.scen` under
//! them, include-only `_` fragments too) rewritten in place, or standard
//! input to standard output when no file is named.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use super::{FormatError, format_text};
use crate::cli::{EXIT_BAD_INPUT, EXIT_CHECK_FAILED, EXIT_OK, collect_scen, render_diags};
use crate::diagnostics::SourceMap;

/// Runs `scen fmt`; returns the exit code: 0 when every file is (now) in
/// the canonical layout, 1 with `--check` when some would change (they are
/// listed on stdout), 2 when a file cannot be read, parsed or written.
pub fn run(paths: &[PathBuf], check: bool) -> i32 {
    if paths.is_empty() {
        return stdin(check);
    }
    let mut files = Vec::new();
    for path in paths {
        if !path.exists() {
            eprintln!("error: `{}` does not exist", path.display());
            return EXIT_BAD_INPUT;
        }
        collect_scen(path, true, &mut files);
    }
    let mut code = EXIT_OK;
    for file in &files {
        let text = match std::fs::read_to_string(file) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: cannot read `{}`: {e}", file.display());
                code = EXIT_BAD_INPUT;
                continue;
            }
        };
        let formatted = match formatted(file, &text) {
            Some(f) => f,
            None => {
                code = EXIT_BAD_INPUT;
                continue;
            }
        };
        if formatted == text {
            continue;
        }
        if check {
            println!("{}", file.display());
            code = code.max(EXIT_CHECK_FAILED);
        } else if let Err(e) = std::fs::write(file, formatted) {
            eprintln!("error: cannot write `{}`: {e}", file.display());
            code = EXIT_BAD_INPUT;
        }
    }
    code
}

fn stdin(check: bool) -> i32 {
    let mut text = String::new();
    if let Err(e) = std::io::stdin().read_to_string(&mut text) {
        eprintln!("error: cannot read standard input: {e}");
        return EXIT_BAD_INPUT;
    }
    let Some(formatted) = formatted(Path::new("<stdin>"), &text) else {
        return EXIT_BAD_INPUT;
    };
    if check {
        if formatted == text {
            return EXIT_OK;
        }
        println!("<stdin>");
        return EXIT_CHECK_FAILED;
    }
    let _ = std::io::stdout().write_all(formatted.as_bytes());
    EXIT_OK
}

/// The formatted text, or `None` with the reason printed on stderr.
fn formatted(file: &Path, text: &str) -> Option<String> {
    match format_text(text) {
        Ok(f) => Some(f),
        Err(FormatError::Syntax(diags)) => {
            let mut sources = SourceMap::default();
            sources.add(file, text);
            eprint!("{}", render_diags(&diags, &sources));
            eprintln!(
                "error: `{}` has syntax errors: not formatted",
                file.display()
            );
            None
        }
        Err(FormatError::Changed(why)) => {
            eprintln!(
                "error: `{}` not formatted: {why} (a bug in `scen fmt`; please report it)",
                file.display()
            );
            None
        }
    }
}
