//! A small pretty printer in the style of Wadler's "prettier printer": a
//! document of text, line breaks and groups; a group is printed on one line
//! when it fits in the width and has no forced break, else each of its
//! [`Doc::Line`]s becomes a newline.

/// Spaces per indentation level.
pub(super) const INDENT: usize = 2;

#[derive(Clone, Debug)]
pub(super) enum Doc {
    /// Text without newlines.
    Text(String),
    /// A space on one line, a newline in a broken group.
    Line,
    /// Nothing on one line, a newline in a broken group.
    SoftLine,
    /// Always a newline; a group that holds one is broken.
    HardLine,
    /// An empty line, then a newline (two [`Doc::HardLine`]s without the
    /// first one's indentation).
    BlankLine,
    /// Text printed only when the enclosing group is broken (a list's
    /// trailing comma).
    IfBreak(&'static str),
    /// Its contents, with newlines indented one level deeper.
    Indent(Vec<Doc>),
    /// Its contents on one line if they fit, else broken.
    Group(Vec<Doc>),
}

/// Prints `docs` in `width` columns.
pub(super) fn print(docs: &[Doc], width: usize) -> String {
    let mut out = String::new();
    let mut column = 0;
    // (indentation, printed flat, document), the next one on top.
    let mut stack: Vec<(usize, bool, &Doc)> = docs.iter().rev().map(|d| (0, false, d)).collect();
    let newline = |out: &mut String, column: &mut usize, indent: usize| {
        let kept = out.trim_end_matches(' ').len();
        out.truncate(kept);
        out.push('\n');
        out.extend(std::iter::repeat_n(' ', indent));
        *column = indent;
    };
    while let Some((indent, flat, doc)) = stack.pop() {
        match doc {
            Doc::Text(s) => {
                out.push_str(s);
                column += s.chars().count();
            }
            Doc::Line if flat => {
                out.push(' ');
                column += 1;
            }
            Doc::SoftLine if flat => {}
            Doc::Line | Doc::SoftLine | Doc::HardLine => newline(&mut out, &mut column, indent),
            Doc::BlankLine => {
                newline(&mut out, &mut column, 0);
                newline(&mut out, &mut column, indent);
            }
            Doc::IfBreak(s) => {
                if !flat {
                    out.push_str(s);
                    column += s.chars().count();
                }
            }
            Doc::Indent(docs) => {
                stack.extend(docs.iter().rev().map(|d| (indent + INDENT, flat, d)));
            }
            Doc::Group(docs) => {
                let flat = flat || fits(docs, width.saturating_sub(column));
                stack.extend(docs.iter().rev().map(|d| (indent, flat, d)));
            }
        }
    }
    out
}

/// Whether `docs` fit in `room` columns on one line (no forced break).
fn fits(docs: &[Doc], room: usize) -> bool {
    fn width(docs: &[Doc], used: &mut usize, room: usize) -> bool {
        for doc in docs {
            match doc {
                Doc::Text(s) => *used += s.chars().count(),
                Doc::Line => *used += 1,
                Doc::SoftLine | Doc::IfBreak(_) => {}
                Doc::HardLine | Doc::BlankLine => return false,
                Doc::Indent(inner) | Doc::Group(inner) => {
                    if !width(inner, used, room) {
                        return false;
                    }
                }
            }
            if *used > room {
                return false;
            }
        }
        true
    }
    width(docs, &mut 0, room)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(s: &str) -> Doc {
        Doc::Text(s.into())
    }

    fn list(items: &[&str]) -> Doc {
        let mut inner = vec![Doc::SoftLine];
        for (k, item) in items.iter().enumerate() {
            if k > 0 {
                inner.extend([text(","), Doc::Line]);
            }
            inner.push(text(item));
        }
        inner.push(Doc::IfBreak(","));
        Doc::Group(vec![
            text("["),
            Doc::Indent(inner),
            Doc::SoftLine,
            text("]"),
        ])
    }

    #[test]
    fn a_group_is_flat_when_it_fits_and_broken_otherwise() {
        let doc = [text("x "), list(&["a", "b", "c"])];
        assert_eq!(print(&doc, 20), "x [a, b, c]");
        assert_eq!(print(&doc, 8), "x [\n  a,\n  b,\n  c,\n]");
    }

    #[test]
    fn a_forced_break_breaks_the_group_and_blank_lines_carry_no_spaces() {
        let doc = [Doc::Indent(vec![
            text("a"),
            Doc::BlankLine,
            Doc::Group(vec![text("b"), Doc::Line, text("c"), Doc::HardLine]),
        ])];
        assert_eq!(print(&doc, 80), "a\n\n  b\n  c\n  ");
    }
}
