//! `scen fmt [FILE...] [--check]`: files and folders (every `*.scen` under
//! them, include-only `_` fragments too) rewritten in place, or standard
//! input to standard output when no file is named.

use std::io::Read;
use std::path::{Path, PathBuf};

use super::{EXIT_BAD_INPUT, EXIT_CHECK_FAILED, EXIT_OK, collect_scen, out, outln, render_diags};
use crate::diagnostics::SourceMap;
use crate::files::read_regular_file;
use crate::format::{FormatError, format_text};
use crate::scenario::loader::MAX_SCENARIO_BYTES;

/// Runs `scen fmt`; returns the exit code: 0 when every file is (now) in
/// the canonical layout, 1 with `--check` when some would change (they are
/// listed on stdout), 2 when a file cannot be read, parsed or written.
pub(super) fn run(paths: &[PathBuf], check: bool) -> i32 {
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
        let text = match read_regular_file(file, MAX_SCENARIO_BYTES)
            .map_err(|e| e.to_string())
            .and_then(|b| String::from_utf8(b).map_err(|_| "it is not UTF-8 text".to_string()))
        {
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
            outln!("{}", file.display());
            code = code.max(EXIT_CHECK_FAILED);
        } else if let Err(e) = std::fs::write(file, formatted) {
            eprintln!("error: cannot write `{}`: {e}", file.display());
            code = EXIT_BAD_INPUT;
        }
    }
    code
}

fn stdin(check: bool) -> i32 {
    // At most the bound of a scenario's text: `scen fmt < /dev/zero` ends.
    let mut text = String::new();
    match std::io::stdin()
        .take(MAX_SCENARIO_BYTES + 1)
        .read_to_string(&mut text)
    {
        Err(e) => {
            eprintln!("error: cannot read standard input: {e}");
            return EXIT_BAD_INPUT;
        }
        Ok(n) if n as u64 > MAX_SCENARIO_BYTES => {
            eprintln!(
                "error: standard input is larger than {}, the bound of a scenario's text",
                crate::files::human_bytes(MAX_SCENARIO_BYTES)
            );
            return EXIT_BAD_INPUT;
        }
        Ok(_) => {}
    }
    let Some(formatted) = formatted(Path::new("<stdin>"), &text) else {
        return EXIT_BAD_INPUT;
    };
    if check {
        if formatted == text {
            return EXIT_OK;
        }
        outln!("<stdin>");
        return EXIT_CHECK_FAILED;
    }
    out!("{formatted}");
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
