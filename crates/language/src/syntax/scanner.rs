//! The first pass of the parser: the file → top-level statement chunks.
//!
//! The scanner tracks strings, comments and bracket depth, so a chunk starts
//! only at a statement keyword outside any bracket (see [`split_statements`]).
//! It also reports what pest must never see: unterminated strings and
//! brackets nested more than [`MAX_NESTING`] deep (pest's rules recurse once
//! per bracket).

use super::parser::{PIECE_BYTES, Rule};
use crate::diagnostics::{Diag, FileId, Span};

/// The deepest bracket nesting accepted (`(`, `[` and `{` together).
const MAX_NESTING: usize = 64;

/// The keywords that start a statement, as the grammar names them.
pub const STATEMENT_KEYWORDS: [&str; 10] = [
    "scenario", "include", "world", "robot", "team", "plan", "expect", "bench", "param", "require",
];

/// The words of a `team` statement after its shape (SPEC 2.10).
pub const TEAM_KEYWORDS: [&str; 2] = ["from", "agents"];

/// The keywords that start an item of a `world` block.
pub const WORLD_ITEM_KEYWORDS: [&str; 8] = [
    "bounds", "rect", "polygon", "segment", "disk", "grid", "scatter", "moving",
];

/// The words of a `moving` obstacle's route (SPEC 2.9).
pub const MOVING_KEYWORDS: [&str; 4] = ["at", "then", "stay", "vanish"];

/// The words of a `scatter` item and of a `param`'s `choice` (SPEC 2.8).
#[cfg(test)]
pub(crate) const FAMILY_KEYWORDS: [&str; 3] = ["in", "gap", "choice"];

/// What may follow `param NAME =`: the distributions and `choice`.
pub const FAMILY_VALUE_WORDS: [&str; 4] = ["uniform", "normal", "int", "choice"];

/// The robot kinds the grammar has rules of its own for (every kind of the
/// registry, `scen_geometry::robots`, parses: these get precise syntax
/// errors), a grid's options, and the words of `expect` expressions: with
/// the two lists above, every keyword of grammar/scen.pest (a test checks
/// it).
pub const ROBOT_SHAPE_KEYWORDS: [&str; 4] = ["point", "disk", "rect", "polygon"];

/// The keywords of the clauses that may follow a robot's shape.
pub const ROBOT_CLAUSE_KEYWORDS: [&str; 2] = ["steer", "speed"];
pub const GRID_OPTION_KEYWORDS: [&str; 2] = ["cell", "origin"];
pub const EXPRESSION_WORDS: [&str; 5] = ["and", "or", "not", "true", "false"];

/// The statement chunk of `text` that `offset` lies in or after: its start
/// and keyword (`None` before the first statement).
pub fn statement_at(text: &str, offset: usize) -> Option<(usize, &'static str)> {
    let scan = split_statements(text, 0);
    let chunk = scan
        .chunks
        .iter()
        .rev()
        .find(|c| c.start <= offset && c.rule.is_some())?;
    let keyword = STATEMENT_KEYWORDS
        .iter()
        .copied()
        .find(|k| text[chunk.start..].starts_with(k))?;
    Some((chunk.start, keyword))
}

/// A top-level piece of the file: one statement, or leading text that is not one.
#[derive(Debug)]
pub(super) struct Chunk {
    pub(super) start: usize,
    /// End of the chunk's last token; trailing blanks and comments are left out.
    pub(super) end: usize,
    /// The rule for the statement keyword it starts with (see [`chunk_rule`]);
    /// `None` for leading text that does not start with one.
    pub(super) rule: Option<Rule>,
    /// Rarely needed facts, boxed to keep the common chunk small.
    details: Option<Box<ChunkDetails>>,
}

#[derive(Debug, Default)]
struct ChunkDetails {
    /// Unterminated strings and too-deep nesting found by the scanner; pest
    /// does not run on a chunk that has any.
    lexical_errors: Vec<Diag>,
    /// Offsets of the brackets still open at the chunk's end, outermost first
    /// (at most `MAX_NESTING + 1`).
    unclosed: Vec<usize>,
    /// Where a large `world` or `plan` statement may be cut into pieces that
    /// parse on their own (see `FileParser::pieces` in parser.rs).
    splits: Vec<usize>,
}

impl Chunk {
    fn new(start: usize, end: usize, rule: Option<Rule>) -> Self {
        Chunk {
            start,
            end,
            rule,
            details: None,
        }
    }

    fn details_mut(&mut self) -> &mut ChunkDetails {
        self.details.get_or_insert_with(Box::default)
    }

    pub(super) fn lexical_errors(&self) -> &[Diag] {
        self.details.as_ref().map_or(&[], |d| &d.lexical_errors)
    }

    pub(super) fn unclosed(&self) -> &[usize] {
        self.details.as_ref().map_or(&[], |d| &d.unclosed)
    }

    pub(super) fn splits(&self) -> &[usize] {
        self.details.as_ref().map_or(&[], |d| &d.splits)
    }

    pub(super) fn is_clean(&self) -> bool {
        self.rule.is_some() && self.lexical_errors().is_empty()
    }

    /// The chunk without its split points, so that it is parsed whole.
    #[cfg(test)]
    pub(super) fn uncut(mut self) -> Self {
        if let Some(details) = &mut self.details {
            details.splits.clear();
        }
        self
    }
}

pub(super) fn is_ident_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// The blanks of the grammar's `WHITESPACE`.
pub(super) fn is_blank(c: char) -> bool {
    matches!(c, ' ' | '\t'..='\r')
}

/// The rule that parses a chunk starting with the statement keyword `keyword`.
fn chunk_rule(keyword: &str) -> Rule {
    match keyword {
        "scenario" => Rule::scenario_chunk,
        "include" => Rule::include_chunk,
        "world" => Rule::world_chunk,
        "robot" => Rule::robot_chunk,
        "team" => Rule::team_chunk,
        "plan" => Rule::plan_chunk,
        "bench" => Rule::bench_chunk,
        "param" => Rule::param_chunk,
        "require" => Rule::require_chunk,
        _ => Rule::expect_chunk,
    }
}

/// What [`split_statements`] finds: the statement chunks, and every comment.
#[derive(Debug)]
pub(super) struct Scan {
    pub(super) chunks: Vec<Chunk>,
    /// Each comment from its `#` to the end of its line (a `\r` before the
    /// newline included), in source order.
    pub(super) comments: Vec<Span>,
}

/// Splits `text` into statement chunks; see the module docs.
///
/// A statement keyword starts a chunk when it stands at a word boundary,
/// outside brackets, and is not part of a metric reference (`world.found`).
/// The words right after `plan` (3) and `robot` (1) on the same line are
/// names, so `plan world astar rod` stays one statement. Inside an unclosed
/// block, a statement keyword in the first column also starts a chunk, so a
/// missing `}` is reported at the block rather than swallowing the file.
pub(super) fn split_statements(text: &str, file: FileId) -> Scan {
    let bytes = text.as_bytes();
    let mut chunks: Vec<Chunk> = Vec::new();
    let mut comments: Vec<Span> = Vec::new();
    let mut current: Option<Chunk> = None;
    let mut depth = 0usize;
    let mut open: Vec<usize> = Vec::new();
    let mut names_to_skip = 0u8;
    let mut prev_byte = 0u8;
    // The previous token when it was a word (for the world's split points).
    let mut prev_word: Option<&str> = None;
    let mut last_split = 0;
    let finish = |mut chunk: Chunk, open: &mut Vec<usize>, chunks: &mut Vec<Chunk>| {
        if !open.is_empty() {
            chunk.details_mut().unclosed = std::mem::take(open);
        }
        chunks.push(chunk);
    };
    for token in Lexer::new(text) {
        if token.after_newline {
            names_to_skip = 0;
        }
        let (token_start, i) = (token.start, token.end);
        let b = bytes[token_start];
        let mut word = None;
        match token.kind {
            TokenKind::Comment => {
                comments.push(Span::new(file, token_start, i));
                continue;
            }
            TokenKind::Word => {
                let this = &text[token_start..i];
                word = Some(this);
                let at_line_start = token_start == 0 || bytes[token_start - 1] == b'\n';
                let starts_statement = !b.is_ascii_digit()
                    && STATEMENT_KEYWORDS.contains(&this)
                    && prev_byte != b'.'
                    && next_nonblank_byte(bytes, i) != Some(b'.')
                    && ((depth == 0 && names_to_skip == 0) || (depth > 0 && at_line_start));
                if starts_statement {
                    if let Some(done) = current.take() {
                        finish(done, &mut open, &mut chunks);
                    }
                    depth = 0;
                    names_to_skip = match this {
                        "plan" => 3,
                        "robot" | "team" | "bench" => 1,
                        _ => 0,
                    };
                    current = Some(Chunk::new(token_start, i, Some(chunk_rule(this))));
                    prev_byte = bytes[i - 1];
                    prev_word = Some(this);
                    last_split = token_start;
                    continue;
                }
                if depth == 0 {
                    names_to_skip = names_to_skip.saturating_sub(1);
                }
            }
            _ => names_to_skip = 0,
        }
        let chunk = current.get_or_insert_with(|| Chunk::new(token_start, token_start, None));
        if depth == 1
            && token_start - last_split >= PIECE_BYTES
            && is_split_point(text, chunk.rule, token_start, word, prev_word)
        {
            chunk.details_mut().splits.push(token_start);
            last_split = token_start;
        }
        match token.kind {
            TokenKind::Str { closed: false } => {
                let end = if i > token_start + 1 && bytes[i - 1] == b'\r' {
                    i - 1
                } else {
                    i
                };
                chunk.details_mut().lexical_errors.push(
                    Diag::error("scen::syntax::unterminated_string", "unterminated string")
                        .at(
                            Span::new(file, token_start, end),
                            "this string is never closed",
                        )
                        .help("add the closing `\"` on the same line: a string cannot span lines"),
                );
            }
            TokenKind::Open => {
                depth += 1;
                if open.len() <= MAX_NESTING {
                    open.push(token_start);
                }
                // Reported once per chunk, at the first bracket too deep.
                if depth == MAX_NESTING + 1
                    && !chunk
                        .lexical_errors()
                        .iter()
                        .any(|d| d.code == "scen::syntax::too_deep")
                {
                    chunk.details_mut().lexical_errors.push(
                        Diag::error(
                            "scen::syntax::too_deep",
                            format!("brackets are nested more than {MAX_NESTING} deep"),
                        )
                        .at(
                            Span::new(file, token_start, i),
                            format!("this `{}` is too deep", b as char),
                        )
                        .help("flatten the value: `scen` accepts at most 64 nested brackets"),
                    );
                }
            }
            TokenKind::Close => {
                depth = depth.saturating_sub(1);
                open.truncate(depth);
            }
            _ => {}
        }
        chunk.end = i;
        prev_byte = bytes[i - 1];
        prev_word = word;
    }
    if let Some(done) = current {
        finish(done, &mut open, &mut chunks);
    }
    Scan { chunks, comments }
}

/// What a [`Token`] is. The scanner needs no finer classes: a number is a
/// `Word` when it starts with a digit and runs of digits and letters
/// (`1e`, `-`, `3` are three tokens of `1e-3`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TokenKind {
    /// A run of `[A-Za-z0-9_]`.
    Word,
    /// A string literal; `closed` is false when its line ends first.
    Str { closed: bool },
    /// `(`, `[` or `{`.
    Open,
    /// `)`, `]` or `}`.
    Close,
    /// `#` to the end of the line.
    Comment,
    /// Any other character.
    Other,
}

/// A token of the scanner's [`Lexer`]: a byte range of the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Token {
    pub kind: TokenKind,
    pub start: usize,
    pub end: usize,
    /// A newline lies between the previous token (or the start) and this one.
    pub after_newline: bool,
}

/// The tokens of a text, blanks skipped, comments included: the lexical
/// rules of the grammar (strings with escapes ending at their line, `#`
/// comments, a byte order mark ignored at the start), shared by the
/// statement splitter and the language server's cursor context.
pub struct Lexer<'t> {
    text: &'t str,
    at: usize,
}

impl<'t> Lexer<'t> {
    pub fn new(text: &'t str) -> Self {
        Lexer { text, at: 0 }
    }

    /// The tokens of `text[from..]`; `from` must start a token or a blank.
    pub fn starting_at(text: &'t str, from: usize) -> Self {
        Lexer { text, at: from }
    }
}

impl Iterator for Lexer<'_> {
    type Item = Token;

    fn next(&mut self) -> Option<Token> {
        let bytes = self.text.as_bytes();
        let mut after_newline = self.at == 0;
        let mut i = self.at;
        while i < bytes.len() {
            match bytes[i] {
                b'\n' => after_newline = true,
                b' ' | b'\t' | b'\r' | 0x0B | 0x0C => {}
                // A byte order mark is ignored at the start of the file only.
                _ if i == 0 && self.text.starts_with('\u{FEFF}') => {
                    i += 3;
                    continue;
                }
                _ => break,
            }
            i += 1;
        }
        if i >= bytes.len() {
            self.at = i;
            return None;
        }
        let start = i;
        let kind = match bytes[i] {
            b'#' => {
                i = bytes[i..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(bytes.len(), |k| i + k);
                TokenKind::Comment
            }
            b if is_ident_byte(b) => {
                while i < bytes.len() && is_ident_byte(bytes[i]) {
                    i += 1;
                }
                TokenKind::Word
            }
            b'"' => {
                let (end, closed) = scan_string(bytes, i);
                i = end;
                TokenKind::Str { closed }
            }
            b'(' | b'[' | b'{' => {
                i += 1;
                TokenKind::Open
            }
            b')' | b']' | b'}' => {
                i += 1;
                TokenKind::Close
            }
            _ => {
                i += self.text[i..].chars().next().map_or(1, char::len_utf8);
                TokenKind::Other
            }
        };
        self.at = i;
        Some(Token {
            kind,
            start,
            end: i,
            after_newline,
        })
    }
}

/// Whether a large statement may be cut before the token at `at` (in its
/// top-level block) so that both sides parse on their own exactly as they
/// would together. In a plan body any word after a blank starts a token. In
/// a world block, an item keyword at the start of a line starts an item,
/// unless the token before is an item keyword itself (`grid` followed by a
/// word on the next line takes that word as its name).
fn is_split_point(
    text: &str,
    rule: Option<Rule>,
    at: usize,
    word: Option<&str>,
    prev_word: Option<&str>,
) -> bool {
    let Some(word) = word.filter(|w| !w.starts_with(|c: char| c.is_ascii_digit())) else {
        return false;
    };
    let before = &text[..at];
    match rule {
        Some(Rule::plan_chunk) => before.ends_with(is_blank),
        Some(Rule::world_chunk) => {
            let line_start = before.trim_end_matches([' ', '\t']);
            WORLD_ITEM_KEYWORDS.contains(&word)
                && (line_start.is_empty() || line_start.ends_with('\n'))
                && !prev_word.is_some_and(|w| WORLD_ITEM_KEYWORDS.contains(&w))
        }
        _ => false,
    }
}

/// The end of the string literal opening at `start`, and whether it is closed.
/// It stops (unclosed) at a newline, like the grammar's `string` rule.
pub(super) fn scan_string(bytes: &[u8], start: usize) -> (usize, bool) {
    let mut j = start + 1;
    while j < bytes.len() {
        match bytes[j] {
            b'"' => return (j + 1, true),
            b'\n' => return (j, false),
            b'\\' if bytes.get(j + 1).is_some_and(|&b| b != b'\n') => j += 2,
            _ => j += 1,
        }
    }
    (bytes.len(), false)
}

fn next_nonblank_byte(bytes: &[u8], from: usize) -> Option<u8> {
    bytes[from.min(bytes.len())..]
        .iter()
        .copied()
        .find(|b| !matches!(b, b' ' | b'\t' | b'\r' | b'\n'))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::ast::Stmt;
    use crate::syntax::parse;
    use crate::syntax::testing::{errors, expr, line_of, parse_ok, sexp, snippet};

    #[test]
    fn empty_and_comment_only_files_have_no_statements_and_no_errors() {
        assert!(parse_ok("").is_empty());
        assert!(parse_ok("  \n\t\r\n").is_empty());
        assert!(parse_ok("# just a comment\n   # another one").is_empty());
    }

    #[test]
    fn keywords_are_names_where_unambiguous() {
        let s = parse_ok(
            "robot disk1 disk 1\nrobot pointy point\nrobot point point\nrobot plan rect 1 2\n\
             plan world astar disk1 { start (0, 0) }\nplan offline roadmap pointy {}\n\
             world { rect rect1 (0,0) (1,1) disk world (0,0) 1 }\n",
        );
        assert_eq!(s.len(), 7, "{s:#?}");
        let Stmt::Robot(r) = &s[0] else { panic!() };
        assert_eq!(r.name.value, "disk1");
        let Stmt::Robot(r) = &s[1] else { panic!() };
        assert_eq!(r.name.value, "pointy");
        assert_eq!(r.shape.kind.value, "point");
        let Stmt::Robot(r) = &s[3] else { panic!() };
        assert_eq!(r.name.value, "plan");
        let Stmt::Plan(p) = &s[4] else { panic!() };
        assert_eq!(
            (p.name.value.as_str(), p.robot.value.as_str()),
            ("world", "disk1")
        );
        assert_eq!(
            sexp(&expr("world.found and not.found or and.x")),
            "(or (and world.found not.found) and.x)"
        );
        assert_eq!(sexp(&expr("not not.found")), "(not not.found)");
        assert_eq!(sexp(&expr("true or false")), "(or true false)");
    }

    #[test]
    fn comments_and_layout_are_insignificant() {
        let text = "# header\nrobot#c\nr#c\npoint#c\nplan a k r{start(0,0)#c\n}expect a.f#c\nexpect\n  a.g\n";
        let s = parse_ok(text);
        assert_eq!(s.len(), 4);
        let Stmt::Expect(e) = &s[3] else { panic!() };
        assert_eq!(snippet(text, e.span), "a.g");
        // `#` inside a string is not a comment.
        let Stmt::Scenario { title, .. } = &parse_ok("scenario \"a # b\" # c")[0] else {
            panic!()
        };
        assert_eq!(title.value, "a # b");
    }

    #[test]
    fn comments_are_kept_with_their_spans() {
        let text = "# head\r\nworld { # in a block\n  rect (0, 0) (1, 1)#glued\n}\n\
                    scenario \"a # b\" # after a string\nexpect a.f # \"x\n# last";
        let (_, diags) = parse(text, 0);
        assert!(diags.is_empty(), "{diags:?}");
        let comments: Vec<&str> = parse(text, 0)
            .0
            .comments
            .iter()
            .map(|&c| snippet(text, c))
            .collect();
        assert_eq!(
            comments,
            [
                "# head\r",
                "# in a block",
                "#glued",
                "# after a string",
                "# \"x",
                "# last"
            ]
        );
        // In a broken statement too, and not inside an unterminated string.
        let broken = "plan p astar r { # open\nscenario \"no end # not a comment\n";
        let (file, _) = parse(broken, 0);
        assert_eq!(file.comments.len(), 1);
        assert_eq!(snippet(broken, file.comments[0]), "# open");
    }

    #[test]
    fn the_keyword_lists_are_the_grammars() {
        let grammar = include_str!("../../grammar/scen.pest");
        let mut named: Vec<&str> = grammar
            .lines()
            .filter_map(|l| l.strip_prefix("kw_")?.split_whitespace().next())
            .filter(|k| !["true", "false"].contains(k))
            .collect();
        named.sort();
        let mut ours: Vec<&str> = [
            &STATEMENT_KEYWORDS[..],
            &WORLD_ITEM_KEYWORDS,
            &ROBOT_SHAPE_KEYWORDS,
            &ROBOT_CLAUSE_KEYWORDS,
            &MOVING_KEYWORDS,
            &TEAM_KEYWORDS,
            &GRID_OPTION_KEYWORDS,
            &FAMILY_KEYWORDS,
        ]
        .concat();
        ours.sort();
        ours.dedup();
        assert_eq!(ours, named);
        for w in EXPRESSION_WORDS {
            assert!(grammar.contains(&format!("\"{w}\"")), "{w}");
        }
    }

    #[test]
    fn the_statement_at_an_offset() {
        let text = "robot r point\nplan p astar r {\n  start (0, 0)\n";
        assert_eq!(statement_at(text, 0), Some((0, "robot")));
        assert_eq!(statement_at(text, 20), Some((14, "plan")));
        assert_eq!(statement_at(text, text.len()), Some((14, "plan")));
        assert_eq!(statement_at("  # nothing\n", 3), None);
    }

    #[test]
    fn the_lexer_marks_tokens_after_a_newline() {
        let text = "\u{FEFF}plan p(1)\n  x.y # c\n\"s";
        let tokens: Vec<(TokenKind, &str, bool)> = Lexer::new(text)
            .map(|t| (t.kind, &text[t.start..t.end], t.after_newline))
            .collect();
        use TokenKind::*;
        assert_eq!(
            tokens,
            [
                (Word, "plan", true),
                (Word, "p", false),
                (Open, "(", false),
                (Word, "1", false),
                (Close, ")", false),
                (Word, "x", true),
                (Other, ".", false),
                (Word, "y", false),
                (Comment, "# c", false),
                (Str { closed: false }, "\"s", true),
            ]
        );
    }

    #[test]
    fn a_missing_closing_brace_points_at_the_opening_one() {
        let text =
            "world {\n  bounds (0,0) (1,1)\n\nrobot r point\nplan p astar r {\n  start (0, 0)\n";
        let (file, diags) = parse(text, 0);
        assert_eq!(diags.len(), 2, "{diags:#?}");
        assert_eq!(line_of(text, diags[0].span.unwrap()), 2);
        assert_eq!(snippet(text, diags[0].span.unwrap()), ")");
        assert!(
            diags[0].message.ends_with("or `}`, found `robot`"),
            "{}",
            diags[0].message
        );
        assert_eq!(snippet(text, diags[0].related[0].0), "{");
        assert_eq!(diags[0].related[0].0.start, 6);
        assert_eq!(diags[0].help.as_deref(), Some("add the missing `}`"));
        assert_eq!(line_of(text, diags[1].related[0].0), 5);
        assert!(
            diags[1].message.ends_with("found the end of the file"),
            "{}",
            diags[1].message
        );
        // The robot between the two broken blocks still parses.
        assert_eq!(file.statements.len(), 1);
    }

    #[test]
    fn nesting_deeper_than_the_limit_is_an_error_at_the_first_bracket_too_deep() {
        let ok = format!(
            "plan p k r {{ x {}1, 2{} }}",
            "(".repeat(MAX_NESTING - 1),
            ")".repeat(MAX_NESTING - 1)
        );
        let (_, diags) = parse(&ok, 0);
        assert!(
            diags.iter().all(|d| d.code != "scen::syntax::too_deep"),
            "{diags:#?}"
        );
        let deep = format!("expect {}1{}", "(".repeat(100_000), ")".repeat(100_000));
        let diags = errors(&deep);
        assert_eq!(diags.len(), 1);
        assert_eq!(diags[0].code, "scen::syntax::too_deep");
        assert_eq!(diags[0].span.unwrap().start, "expect ".len() + MAX_NESTING);
        // At the limit the expression grammar still parses (and does not overflow
        // a test thread's stack).
        let at_limit = format!(
            "expect {}1{}",
            "(".repeat(MAX_NESTING),
            ")".repeat(MAX_NESTING)
        );
        assert_eq!(sexp(&expr(&at_limit["expect ".len()..])), "1");
        // The same on the parser's worker threads (a file of many units).
        let many = format!("{}{at_limit}\n", "expect a.found\n".repeat(20_000));
        let (file, diags) = parse(&many, 0);
        assert!(diags.is_empty());
        assert_eq!(file.statements.len(), 20_001);
        let mixed = format!("world {{ polygon {} }}", "[(".repeat(40));
        assert_eq!(errors(&mixed)[0].code, "scen::syntax::too_deep");
    }

    #[test]
    fn unterminated_strings() {
        let text = "scenario \"title\nrobot r point\ninclude \"x";
        let (file, diags) = parse(text, 0);
        assert_eq!(diags.len(), 2, "{diags:#?}");
        assert!(
            diags
                .iter()
                .all(|d| d.code == "scen::syntax::unterminated_string")
        );
        assert_eq!(snippet(text, diags[0].span.unwrap()), "\"title");
        assert_eq!(snippet(text, diags[1].span.unwrap()), "\"x");
        assert!(diags[0].help.is_some());
        assert_eq!(file.statements.len(), 1);
        // An escaped quote does not close the string.
        assert_eq!(
            errors("scenario \"a\\\"")[0].code,
            "scen::syntax::unterminated_string"
        );
    }

    #[test]
    fn a_byte_order_mark_is_ignored_at_the_start_only() {
        assert_eq!(parse_ok("\u{FEFF}robot r point").len(), 1);
        let diags = errors("robot r \u{FEFF}point");
        assert_eq!(diags[0].code, "scen::syntax::expected");
    }

    #[test]
    fn crlf_line_endings_are_blanks() {
        let text = "world {\r\n  bounds (0, 0) (1, 1)\r\n}\r\nexpect a.f # c\r\n";
        assert_eq!(parse_ok(text).len(), 2);
    }
}
