//! Byte offsets ↔ LSP positions (line, column in UTF-16 code units, or in
//! bytes when the client accepts UTF-8), and incremental edits.

use lsp_types::{Position, Range};

/// How columns are counted, as negotiated at `initialize`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Encoding {
    Utf8,
    Utf16,
}

/// The line starts of one text.
pub(crate) struct LineIndex<'t> {
    text: &'t str,
    starts: Vec<usize>,
    encoding: Encoding,
}

impl<'t> LineIndex<'t> {
    pub(crate) fn new(text: &'t str, encoding: Encoding) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex {
            text,
            starts,
            encoding,
        }
    }

    pub(crate) fn position(&self, offset: usize) -> Position {
        let offset = floor_char_boundary(self.text, offset.min(self.text.len()));
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let prefix = &self.text[self.starts[line]..offset];
        let character = match self.encoding {
            Encoding::Utf8 => prefix.len(),
            Encoding::Utf16 => prefix.encode_utf16().count(),
        };
        Position::new(line as u32, character as u32)
    }

    pub(crate) fn range(&self, start: usize, end: usize) -> Range {
        Range::new(self.position(start), self.position(end))
    }

    /// The byte offset of a position; past the end of its line, the line's
    /// end; past the last line, the end of the text.
    pub(crate) fn offset(&self, position: Position) -> usize {
        let Some(&start) = self.starts.get(position.line as usize) else {
            return self.text.len();
        };
        let end = self
            .starts
            .get(position.line as usize + 1)
            .map_or(self.text.len(), |&next| next - 1);
        let line = &self.text[start..end];
        let wanted = position.character as usize;
        let mut units = 0;
        for (i, c) in line.char_indices() {
            if units >= wanted {
                return start + i;
            }
            units += match self.encoding {
                Encoding::Utf8 => c.len_utf8(),
                Encoding::Utf16 => c.len_utf16(),
            };
        }
        end
    }
}

fn floor_char_boundary(text: &str, mut offset: usize) -> usize {
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    offset
}

/// Applies one `didChange` edit: `range` replaced by `new_text`, or the
/// whole text when there is no range.
pub(crate) fn apply_change(
    text: &mut String,
    range: Option<Range>,
    new_text: &str,
    encoding: Encoding,
) {
    let Some(range) = range else {
        *text = new_text.to_string();
        return;
    };
    let index = LineIndex::new(text, encoding);
    let start = index.offset(range.start);
    let end = index.offset(range.end).max(start);
    text.replace_range(start..end, new_text);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_count_utf16_units_or_bytes() {
        let text = "aé𝄞b\nx";
        let utf16 = LineIndex::new(text, Encoding::Utf16);
        let b = text.find('b').unwrap();
        assert_eq!(utf16.position(b), Position::new(0, 4));
        assert_eq!(utf16.offset(Position::new(0, 4)), b);
        assert_eq!(utf16.offset(Position::new(0, 99)), b + 1);
        assert_eq!(utf16.offset(Position::new(5, 0)), text.len());
        assert_eq!(utf16.position(text.len()), Position::new(1, 1));
        let utf8 = LineIndex::new(text, Encoding::Utf8);
        assert_eq!(utf8.position(b), Position::new(0, 7));
        // Inside a character: its start.
        assert_eq!(utf8.position(2), Position::new(0, 1));
    }

    #[test]
    fn edits_replace_ranges() {
        let mut text = String::from("robot r point\nplan");
        let range = Range::new(Position::new(0, 6), Position::new(0, 7));
        apply_change(&mut text, Some(range), "rod", Encoding::Utf16);
        assert_eq!(text, "robot rod point\nplan");
        apply_change(&mut text, None, "", Encoding::Utf16);
        assert_eq!(text, "");
    }
}
