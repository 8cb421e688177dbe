//! Diagnostics: every input error is a value with a span; the source text is
//! attached only when the error is reported (nushell style).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::{LabeledSpan, MietteDiagnostic, NamedSource, Report, Severity};

/// Index of a file in a [`SourceMap`].
pub type FileId = u32;

/// A byte range in one source file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Span {
    pub file: FileId,
    pub start: usize,
    pub end: usize,
}

impl Span {
    pub fn new(file: FileId, start: usize, end: usize) -> Self {
        Span { file, start, end }
    }

    /// The smallest span covering both (they must be in the same file).
    pub fn to(self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }

    pub fn len(&self) -> usize {
        self.end.saturating_sub(self.start)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A value with the span of the text it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    pub value: T,
    pub span: Span,
}

impl<T> Spanned<T> {
    pub fn new(value: T, span: Span) -> Self {
        Spanned { value, span }
    }
}

/// One loaded source file.
#[derive(Clone, Debug)]
pub struct SourceFile {
    /// The path as the user gave it (or as resolved for an include).
    pub path: PathBuf,
    pub text: Arc<str>,
}

impl SourceFile {
    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let mut line = 1;
        let mut line_start = 0;
        for (i, b) in self.text.as_bytes()[..offset].iter().enumerate() {
            if *b == b'\n' {
                line += 1;
                line_start = i + 1;
            }
        }
        let col = self
            .text
            .get(line_start..offset)
            .map(|s| s.chars().count())
            .unwrap_or(offset - line_start)
            + 1;
        (line, col)
    }
}

/// All files of one scenario (the main file and its includes).
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    pub files: Vec<SourceFile>,
}

impl SourceMap {
    /// A hash of every source's text, in the order they were read (FNV-1a,
    /// 64 bits, as hex): the same files give the same hash on any machine,
    /// whatever their paths.
    pub fn content_hash(&self) -> String {
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for f in &self.files {
            for b in f.text.bytes().chain(std::iter::once(0)) {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
        }
        format!("{h:016x}")
    }

    pub fn add(&mut self, path: &Path, text: impl Into<Arc<str>>) -> FileId {
        self.files.push(SourceFile {
            path: path.to_path_buf(),
            text: text.into(),
        });
        (self.files.len() - 1) as FileId
    }

    pub fn get(&self, id: FileId) -> Option<&SourceFile> {
        self.files.get(id as usize)
    }

    /// The text a span covers ("" when out of range).
    pub fn snippet(&self, span: Span) -> &str {
        self.get(span.file)
            .and_then(|f| f.text.get(span.start..span.end))
            .unwrap_or("")
    }

    /// `file:line:col` of a span's start.
    pub fn location(&self, span: Span) -> String {
        match self.get(span.file) {
            Some(f) => {
                let (l, c) = f.line_col(span.start);
                format!("{}:{}:{}", f.path.display(), l, c)
            }
            None => "<unknown>".to_string(),
        }
    }

    pub fn line_of(&self, span: Span) -> usize {
        self.get(span.file)
            .map(|f| f.line_col(span.start).0)
            .unwrap_or(0)
    }
}

/// Severity of a [`Diag`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    Error,
    Warning,
}

/// A diagnostic: a code such as `scen::analyze::unknown_key`, a message that
/// names things in backticks, a primary label on a span, and a help line.
#[derive(Clone, Debug)]
pub struct Diag {
    pub code: &'static str,
    pub message: String,
    pub span: Option<Span>,
    pub label: String,
    pub help: Option<String>,
    pub level: Level,
    /// Secondary labels (e.g. "first declared here").
    pub related: Vec<(Span, String)>,
}

impl Diag {
    pub fn error(code: &'static str, message: impl Into<String>) -> Self {
        Diag {
            code,
            message: message.into(),
            span: None,
            label: String::new(),
            help: None,
            level: Level::Error,
            related: Vec::new(),
        }
    }

    pub fn warning(code: &'static str, message: impl Into<String>) -> Self {
        Diag {
            level: Level::Warning,
            ..Diag::error(code, message)
        }
    }

    pub fn at(mut self, span: Span, label: impl Into<String>) -> Self {
        self.span = Some(span);
        self.label = label.into();
        self
    }

    pub fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    pub fn with_related(mut self, span: Span, label: impl Into<String>) -> Self {
        self.related.push((span, label.into()));
        self
    }

    pub fn is_error(&self) -> bool {
        self.level == Level::Error
    }

    /// A miette report with the source of the span's file attached.
    pub fn to_report(&self, sources: &SourceMap) -> Report {
        let mut d = MietteDiagnostic::new(self.message.clone())
            .with_code(self.code)
            .with_severity(match self.level {
                Level::Error => Severity::Error,
                Level::Warning => Severity::Warning,
            });
        if let Some(help) = &self.help {
            d = d.with_help(help.clone());
        }
        let file = self.span.and_then(|s| sources.get(s.file).map(|f| (s, f)));
        if let Some((span, f)) = file
            && has_long_lines(&f.text, span)
        {
            // miette cannot draw under columns past 65535 (and nobody wants
            // to read such a line): give the location in words instead.
            let (line, col) = f.line_col(span.start);
            let located = MietteDiagnostic::new(format!(
                "{}\n  at {}:{}:{}: {}",
                self.message,
                f.path.display(),
                line,
                col,
                self.label
            ))
            .with_code(self.code);
            let located = match &self.help {
                Some(h) => located.with_help(h.clone()),
                None => located,
            };
            return Report::new(located);
        }
        if let Some((span, f)) = file {
            let mut labels = vec![LabeledSpan::new_primary_with_span(
                Some(self.label.clone()).filter(|l| !l.is_empty()),
                clamp(span, &f.text),
            )];
            for (s, l) in &self.related {
                if s.file == span.file {
                    labels.push(LabeledSpan::new_with_span(
                        Some(l.clone()),
                        clamp(*s, &f.text),
                    ));
                }
            }
            d = d.with_labels(labels);
            // miette prints `[file:line:col]` from the name and the label.
            let name = f.path.display().to_string();
            Report::new(d).with_source_code(NamedSource::new(name, f.text.to_string()))
        } else {
            Report::new(d)
        }
    }

    /// The JSON form used by `scen check --format json`. Editors read it
    /// line by line with regular expressions (editors/vscode/package.json's
    /// problem matcher, editors/vim's errorformat) that expect the keys in
    /// this order; editors/test.sh checks them on the bad-input corpus.
    pub fn to_json(&self, sources: &SourceMap) -> serde_json::Value {
        let mut obj = serde_json::json!({
            "severity": match self.level { Level::Error => "error", Level::Warning => "warning" },
            "code": self.code,
            "message": self.message,
            "label": self.label,
            "help": self.help,
        });
        if let Some(span) = self.span
            && let Some(f) = sources.get(span.file)
        {
            let (line, column) = f.line_col(span.start);
            let (end_line, end_column) = f.line_col(span.end);
            obj["file"] = serde_json::json!(f.path.display().to_string());
            obj["line"] = serde_json::json!(line);
            obj["column"] = serde_json::json!(column);
            obj["end_line"] = serde_json::json!(end_line);
            obj["end_column"] = serde_json::json!(end_column);
        }
        obj
    }
}

/// Whether the lines around a span (one line of context each side) are too
/// long to draw.
fn has_long_lines(text: &str, span: Span) -> bool {
    const MAX_LINE: usize = 2000;
    let start = span.start.min(text.len());
    let end = span.end.clamp(start, text.len());
    let bytes = text.as_bytes();
    // Two line breaks back and two forward cover the context lines.
    let mut from = start;
    let mut breaks = 0;
    while from > 0 {
        if bytes[from - 1] == b'\n' {
            breaks += 1;
            if breaks == 2 {
                break;
            }
        }
        from -= 1;
    }
    let mut to = end;
    breaks = 0;
    while to < bytes.len() {
        if bytes[to] == b'\n' {
            breaks += 1;
            if breaks == 2 {
                break;
            }
        }
        to += 1;
    }
    bytes[from..to]
        .split(|b| *b == b'\n')
        .any(|l| l.len() > MAX_LINE)
}

fn clamp(span: Span, text: &str) -> (usize, usize) {
    let start = span.start.min(text.len());
    let end = span.end.clamp(start, text.len());
    (start, end - start)
}

/// A list of diagnostics, sorted by position when reported.
pub type Diags = Vec<Diag>;

/// Sort diagnostics by file and offset, errors without a span first.
pub fn sort_diags(diags: &mut [Diag]) {
    diags.sort_by_key(|d| {
        d.span
            .map(|s| (s.file, s.start, s.end))
            .unwrap_or((0, 0, 0))
    });
}

/// The Levenshtein distance between two sequences, for "did you mean"
/// suggestions. Callers choose the unit: the parser compares the bytes of
/// keywords, the analyzer the characters of names.
pub fn edit_distance<T: PartialEq>(a: &[T], b: &[T]) -> usize {
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

/// Renders diagnostics with their sources (miette), one after another.
pub fn render_diags(diags: &[Diag], sources: &SourceMap) -> String {
    let mut s = String::new();
    for d in diags {
        s.push_str(&format!("{:?}\n", d.to_report(sources)));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_insertions_deletions_and_substitutions() {
        let bytes = |a: &str, b: &str| edit_distance(a.as_bytes(), b.as_bytes());
        assert_eq!(bytes("", ""), 0);
        assert_eq!(bytes("", "plan"), 4);
        assert_eq!(bytes("plan", ""), 4);
        assert_eq!(bytes("robot", "robot"), 0);
        assert_eq!(bytes("dsk", "disk"), 1);
        assert_eq!(bytes("robots", "robot"), 1);
        assert_eq!(bytes("wrold", "world"), 2);
        assert_eq!(bytes("kitten", "sitting"), 3);
        // The unit matters beyond ASCII: `é` is two bytes but one character.
        assert_eq!(bytes("\"xpéct", "expect"), 3);
        let chars = |a: &str, b: &str| {
            edit_distance(
                &a.chars().collect::<Vec<_>>(),
                &b.chars().collect::<Vec<_>>(),
            )
        };
        assert_eq!(chars("\"xpéct", "expect"), 2);
        assert_eq!(chars("kitten", "sitting"), 3);
    }
}
