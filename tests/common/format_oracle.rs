//! The formatter's oracle, shared by `tests/fmt.rs` and the fuzzer: what
//! `scen fmt` must keep of any text it accepts.

use scen::format::{format_text, shape};

/// Formats `text` and checks that formatting twice changes nothing, that
/// the formatted text parses without a diagnostic into the same statements
/// (by [`shape`]) and keeps every comment in order. Returns the formatted
/// text, `Ok(None)` when the formatter refuses the text (a syntax error),
/// or what broke.
pub fn check_format(text: &str) -> Result<Option<String>, String> {
    let Ok(formatted) = format_text(text) else {
        return Ok(None);
    };
    match format_text(&formatted) {
        Ok(again) if again == formatted => {}
        Ok(again) => {
            return Err(format!(
                "formatting twice changed it:\n--- once ---\n{formatted}\n--- twice ---\n{again}"
            ));
        }
        Err(e) => {
            return Err(format!(
                "the formatted text does not format again ({e:?}):\n{formatted}"
            ));
        }
    }
    let (before, _) = scen::syntax::parse(text, 0);
    let (after, diags) = scen::syntax::parse(&formatted, 0);
    if !diags.is_empty() {
        return Err(format!(
            "the formatted text has diagnostics {diags:?}:\n{formatted}"
        ));
    }
    if shape(&before.statements) != shape(&after.statements) {
        return Err(format!(
            "formatting changed the statements:\n--- formatted ---\n{formatted}"
        ));
    }
    let comments = |t: &str, f: &scen::syntax::ast::File| -> Vec<String> {
        f.comments
            .iter()
            .map(|c| t[c.start..c.end].trim_end().to_string())
            .collect()
    };
    if comments(text, &before) != comments(&formatted, &after) {
        return Err(format!(
            "formatting lost or reordered a comment:\n--- formatted ---\n{formatted}"
        ));
    }
    Ok(Some(formatted))
}
