//! Source text → [`ast::File`], in two passes.
//!
//! 1. A scanner splits the file into top-level statement chunks. It tracks
//!    strings, comments and bracket depth, so a chunk starts only at a
//!    statement keyword outside any bracket. It also reports what pest must
//!    never see: unterminated strings and brackets nested more than
//!    [`MAX_NESTING`] deep (pest's rules recurse once per bracket).
//! 2. pest parses each chunk with the rule for its keyword (grammar/scen.pest), and
//!    the pairs are turned into AST nodes with file-relative spans; `expect`
//!    expressions get their precedence here, by precedence climbing.
//!
//! Because each statement is parsed on its own, an error in one statement
//! does not hide the errors of the others: [`parse`] returns them all.
//!
//! Large files stay fast and small: runs of error-free chunks are parsed by
//! one pest call (up to [`BATCH_BYTES`]), the runs in parallel, and a huge
//! `world` or `plan` statement is cut into pieces parsed in parallel. Either
//! shortcut gives exactly the result of parsing chunk by chunk, or is not
//! taken.

use std::ops::Range;

use pest::Parser as _;
use pest::error::{ErrorVariant, InputLocation};
use pest::iterators::Pair;
use rayon::prelude::*;

use super::ast::{
    self, ArithOp, CompareOp, Expr, ExprKind, GridSpec, Ident, ObstacleDecl, ObstacleKind,
    ObstacleShape, ParamToken, PlanDecl, RobotDecl, RobotShape, Stmt, Value, ValueKind, WorldBlock,
    WorldItem,
};
use crate::diagnostics::{Diag, FileId, Span, Spanned, edit_distance, sort_diags};

#[derive(pest_derive::Parser)]
#[grammar = "grammar/scen.pest"]
struct ScenParser;

/// The deepest bracket nesting accepted (`(`, `[` and `{` together).
pub(crate) const MAX_NESTING: usize = 64;

/// The tallest `expect` expression tree accepted. Long operator chains build
/// left-deep trees, and every later pass walks them recursively.
const MAX_EXPR_HEIGHT: usize = 256;

const STATEMENT_KEYWORDS: [&str; 6] = ["scenario", "include", "world", "robot", "plan", "expect"];

const WORLD_ITEM_KEYWORDS: [&str; 6] = ["bounds", "rect", "polygon", "segment", "disk", "grid"];

const EXPECTED_STATEMENT: &str =
    "expected a statement: `world`, `robot`, `plan`, `expect`, `include` or `scenario`";

/// Words that are units when written right after a number.
const UNIT_WORDS: [&str; 4] = ["deg", "rad", "ms", "s"];

const UNITS_HELP: &str = "units are `deg` and `rad` for angles, `%` for percentages, `ms` and `s` \
                          for durations, written right after the number: `90deg`";

/// Parses one file. Returns the statements that parsed and every error found,
/// sorted by position.
///
/// When the diagnostics contain errors the file is incomplete: statements
/// that failed to parse are missing, and a statement with a bad literal (an
/// out-of-range number, an unknown unit or escape) is kept with a placeholder
/// in its place. An empty file parses to no statements and no error.
pub fn parse(text: &str, file: FileId) -> (ast::File, Vec<Diag>) {
    let chunks = split_statements(text, file);
    let units = work_units(&chunks);
    let parse_unit = |unit: &Range<usize>| {
        let mut parser = FileParser::new(text, file);
        parser.unit(&chunks[unit.clone()]);
        parser
    };
    let mut parsed = FileParser::new(text, file);
    // Units are independent, so a large file is parsed on all cores; in
    // groups, so that the results waiting to be joined stay small.
    for group in units.chunks(PARALLEL_UNITS) {
        let results: Vec<FileParser<'_>> = if group.len() > 1 {
            group.par_iter().map(parse_unit).collect()
        } else {
            group.iter().map(parse_unit).collect()
        };
        for result in results {
            parsed.append(result);
        }
    }
    sort_diags(&mut parsed.diags);
    (
        ast::File {
            statements: parsed.statements,
        },
        parsed.diags,
    )
}

/// Consecutive clean statements are parsed by one pest call of up to this
/// many bytes: pest's per-call setup dominates for short statements.
const BATCH_BYTES: usize = 64 * 1024;

/// A larger `world` or `plan` statement is cut into pieces of about this
/// size, parsed in parallel: pest keeps a token queue for the whole input it
/// parses, of many times its size.
const PIECE_BYTES: usize = BATCH_BYTES;

/// How many units of work are parsed in parallel before their results are
/// joined.
const PARALLEL_UNITS: usize = 64;

/// Groups chunks into units of work: a run of clean chunks of at most
/// [`BATCH_BYTES`] (or a single larger one), or one chunk with an error.
fn work_units(chunks: &[Chunk]) -> Vec<Range<usize>> {
    let mut units = Vec::new();
    let mut start = 0;
    while start < chunks.len() {
        let mut end = start + 1;
        if chunks[start].is_clean() {
            while end < chunks.len()
                && chunks[end].is_clean()
                && chunks[end].end - chunks[start].start <= BATCH_BYTES
            {
                end += 1;
            }
        }
        units.push(start..end);
        start = end;
    }
    units
}

struct FileParser<'t> {
    text: &'t str,
    file: FileId,
    statements: Vec<Stmt>,
    diags: Vec<Diag>,
}

impl<'t> FileParser<'t> {
    fn new(text: &'t str, file: FileId) -> Self {
        FileParser {
            text,
            file,
            statements: Vec::new(),
            diags: Vec::new(),
        }
    }

    fn append(&mut self, mut other: FileParser<'_>) {
        self.statements.append(&mut other.statements);
        self.diags.append(&mut other.diags);
    }

    /// Parses one unit of [`work_units`].
    fn unit(&mut self, chunks: &[Chunk]) {
        match chunks {
            [chunk] if chunk.rule.is_none() => {
                self.diags
                    .push(not_a_statement(self.text, self.file, chunk.start));
            }
            [chunk] if !chunk.lexical_errors().is_empty() => {
                self.diags.extend(chunk.lexical_errors().iter().cloned());
            }
            [chunk] => self.one(chunk),
            _ => {
                if !self.batch(chunks) {
                    chunks.iter().for_each(|chunk| self.one(chunk));
                }
            }
        }
    }

    /// Parses one chunk, reporting its syntax error if any.
    fn one(&mut self, chunk: &Chunk) {
        if !chunk.splits().is_empty() && self.pieces(chunk) {
            return;
        }
        let rule = chunk.rule.expect("only statement chunks are parsed");
        match ScenParser::parse(rule, &self.text[chunk.start..chunk.end]) {
            Ok(mut pairs) => {
                let pair = pairs.next().expect("grammar guarantees a statement pair");
                self.build(pair, chunk.start);
            }
            Err(error) => self
                .diags
                .push(syntax_error(self.text, self.file, chunk, &error)),
        }
    }

    /// Parses clean chunks in one go. Returns false, having added nothing,
    /// unless they parse to exactly the statements the chunks delimit (so the
    /// result never differs from parsing them one by one).
    fn batch(&mut self, chunks: &[Chunk]) -> bool {
        let (Some(first), Some(last)) = (chunks.first(), chunks.last()) else {
            return true;
        };
        let base = first.start;
        let Ok(pairs) = ScenParser::parse(Rule::statement_chunks, &self.text[base..last.end])
        else {
            return false;
        };
        let pairs: Vec<P<'_>> = pairs.filter(|p| p.as_rule() != Rule::EOI).collect();
        // Statements that start where the chunks start end where they end
        // too: only blanks and comments lie between a chunk's end and the
        // next chunk's start.
        let same = pairs.len() == chunks.len()
            && pairs
                .iter()
                .zip(chunks)
                .all(|(pair, chunk)| base + pair.as_span().start() == chunk.start);
        if !same {
            return false;
        }
        for pair in pairs {
            self.build(pair, base);
        }
        true
    }

    /// Parses a large `world` or `plan` chunk cut at its split points, each
    /// piece wrapped into a statement of its own: the first keeps the real
    /// header and gets a closing `}`, the others get a made-up header (whose
    /// nodes are dropped). Returns false, having added nothing, when a piece
    /// fails: the whole chunk is then parsed for the error messages.
    fn pieces(&mut self, chunk: &Chunk) -> bool {
        let rule = chunk.rule.expect("only statement chunks are parsed");
        let header = match rule {
            Rule::world_chunk => "world{",
            Rule::plan_chunk => "plan p k r{",
            _ => return false,
        };
        let bounds: Vec<usize> = std::iter::once(chunk.start)
            .chain(chunk.splits().iter().copied())
            .chain([chunk.end])
            .collect();
        let last = bounds.len() - 2;
        let pieces: Vec<Option<(Stmt, Vec<Diag>)>> = bounds
            .windows(2)
            .enumerate()
            .collect::<Vec<_>>()
            .par_iter()
            .map(|&(k, window)| {
                let (start, end) = (window[0], window[1]);
                let prefix = if k == 0 { "" } else { header };
                let suffix = if k == last { "" } else { "}" };
                let source = format!("{prefix}{}{suffix}", &self.text[start..end]);
                let mut pairs = ScenParser::parse(rule, &source).ok()?;
                let mut piece = FileParser::new(self.text, self.file);
                // Real tokens sit at or after `prefix.len()` in `source`, so
                // their file offsets come out right.
                piece.build(pairs.next()?, start - prefix.len());
                Some((piece.statements.pop()?, piece.diags))
            })
            .collect();
        if pieces.iter().any(Option::is_none) {
            return false;
        }
        let span = Span::new(self.file, chunk.start, chunk.end);
        let mut pieces = pieces.into_iter().flatten();
        let Some((mut statement, diags)) = pieces.next() else {
            return false;
        };
        self.diags.extend(diags);
        for (piece, diags) in pieces {
            self.diags.extend(diags);
            match (&mut statement, piece) {
                (Stmt::World(world), Stmt::World(more)) => world.items.extend(more.items),
                (Stmt::Plan(plan), Stmt::Plan(more)) => {
                    // `90 deg` may straddle the cut.
                    if let (Some(before), Some(after)) = (plan.body.last(), more.body.first()) {
                        let pair = [before.clone(), after.clone()];
                        let mut builder = Builder {
                            text: self.text,
                            file: self.file,
                            base: 0,
                            diags: &mut self.diags,
                            expr_too_deep: false,
                        };
                        builder.check_detached_units(&pair);
                    }
                    plan.body.extend(more.body);
                }
                _ => unreachable!("every piece parses with the chunk's rule"),
            }
        }
        match &mut statement {
            Stmt::World(world) => world.span = span,
            Stmt::Plan(plan) => plan.span = span,
            _ => unreachable!("only world and plan chunks are cut"),
        }
        self.statements.push(statement);
        true
    }

    fn build(&mut self, pair: P<'_>, base: usize) {
        let mut builder = Builder {
            text: self.text,
            file: self.file,
            base,
            diags: &mut self.diags,
            expr_too_deep: false,
        };
        if let Some(statement) = builder.statement(pair) {
            self.statements.push(statement);
        }
    }
}

// ------------------------------------------------------------------ scanner

/// A top-level piece of the file: one statement, or leading text that is not one.
#[derive(Debug)]
struct Chunk {
    start: usize,
    /// End of the chunk's last token; trailing blanks and comments are left out.
    end: usize,
    /// The rule for the statement keyword it starts with (see [`chunk_rule`]);
    /// `None` for leading text that does not start with one.
    rule: Option<Rule>,
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
    /// parse on their own (see [`FileParser::pieces`]).
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

    fn lexical_errors(&self) -> &[Diag] {
        self.details.as_ref().map_or(&[], |d| &d.lexical_errors)
    }

    fn unclosed(&self) -> &[usize] {
        self.details.as_ref().map_or(&[], |d| &d.unclosed)
    }

    fn splits(&self) -> &[usize] {
        self.details.as_ref().map_or(&[], |d| &d.splits)
    }

    fn is_clean(&self) -> bool {
        self.rule.is_some() && self.lexical_errors().is_empty()
    }
}

fn is_ident_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// The blanks of the grammar's `WHITESPACE`.
fn is_blank(c: char) -> bool {
    matches!(c, ' ' | '\t'..='\r')
}

/// The rule that parses a chunk starting with the statement keyword `keyword`.
fn chunk_rule(keyword: &str) -> Rule {
    match keyword {
        "scenario" => Rule::scenario_chunk,
        "include" => Rule::include_chunk,
        "world" => Rule::world_chunk,
        "robot" => Rule::robot_chunk,
        "plan" => Rule::plan_chunk,
        _ => Rule::expect_chunk,
    }
}

/// Splits `text` into statement chunks; see the module docs.
///
/// A statement keyword starts a chunk when it stands at a word boundary,
/// outside brackets, and is not part of a metric reference (`world.found`).
/// The words right after `plan` (3) and `robot` (1) on the same line are
/// names, so `plan world astar rod` stays one statement. Inside an unclosed
/// block, a statement keyword in the first column also starts a chunk, so a
/// missing `}` is reported at the block rather than swallowing the file.
fn split_statements(text: &str, file: FileId) -> Vec<Chunk> {
    let bytes = text.as_bytes();
    let mut chunks: Vec<Chunk> = Vec::new();
    let mut current: Option<Chunk> = None;
    let mut depth = 0usize;
    let mut open: Vec<usize> = Vec::new();
    let mut names_to_skip = 0u8;
    let mut prev_byte = 0u8;
    // The previous token when it was a word (for the world's split points).
    let mut prev_word: Option<&str> = None;
    let mut last_split = 0;
    let mut i = 0;
    let finish = |mut chunk: Chunk, open: &mut Vec<usize>, chunks: &mut Vec<Chunk>| {
        if !open.is_empty() {
            chunk.details_mut().unclosed = std::mem::take(open);
        }
        chunks.push(chunk);
    };
    while i < bytes.len() {
        let b = bytes[i];
        match b {
            b'\n' => {
                names_to_skip = 0;
                i += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' | 0x0B | 0x0C => {
                i += 1;
                continue;
            }
            b'#' => {
                i = bytes[i..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(bytes.len(), |k| i + k);
                continue;
            }
            // A byte order mark is ignored at the start of the file only.
            _ if i == 0 && text.starts_with('\u{FEFF}') => {
                i += 3;
                continue;
            }
            _ => {}
        }
        let token_start = i;
        let mut word = None;
        if is_ident_byte(b) {
            while i < bytes.len() && is_ident_byte(bytes[i]) {
                i += 1;
            }
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
                    "robot" => 1,
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
        } else {
            names_to_skip = 0;
        }
        let chunk = current.get_or_insert_with(|| Chunk::new(token_start, token_start, None));
        if depth == 1
            && token_start - last_split >= PIECE_BYTES
            && is_split_point(text, chunk.rule, token_start, word, prev_word)
        {
            chunk.details_mut().splits.push(token_start);
            last_split = token_start;
        }
        match b {
            _ if word.is_some() => {}
            b'"' => {
                let (end, closed) = scan_string(bytes, i);
                i = end;
                if !closed {
                    let end = if end > token_start + 1 && bytes[end - 1] == b'\r' {
                        end - 1
                    } else {
                        end
                    };
                    chunk.details_mut().lexical_errors.push(
                        Diag::error("scen::syntax::unterminated_string", "unterminated string")
                            .at(
                                Span::new(file, token_start, end),
                                "this string is never closed",
                            )
                            .help(
                                "add the closing `\"` on the same line: a string cannot span lines",
                            ),
                    );
                }
            }
            b'(' | b'[' | b'{' => {
                depth += 1;
                if open.len() <= MAX_NESTING {
                    open.push(i);
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
                            Span::new(file, i, i + 1),
                            format!("this `{}` is too deep", b as char),
                        )
                        .help("flatten the value: `scen` accepts at most 64 nested brackets"),
                    );
                }
                i += 1;
            }
            b')' | b']' | b'}' => {
                depth = depth.saturating_sub(1);
                open.truncate(depth);
                i += 1;
            }
            _ => i += text[i..].chars().next().map_or(1, char::len_utf8),
        }
        chunk.end = i;
        prev_byte = bytes[i - 1];
        prev_word = word;
    }
    if let Some(done) = current {
        finish(done, &mut open, &mut chunks);
    }
    chunks
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
fn scan_string(bytes: &[u8], start: usize) -> (usize, bool) {
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

// ---------------------------------------------------------- syntax errors

/// The offset of the next token at or after `from`, skipping blanks and comments.
fn skip_trivia(text: &str, mut from: usize) -> usize {
    loop {
        let rest = &text[from..];
        let trimmed = rest.trim_start_matches(is_blank);
        from += rest.len() - trimmed.len();
        if trimmed.starts_with('#') {
            from += trimmed.find('\n').unwrap_or(trimmed.len());
        } else {
            return from;
        }
    }
}

/// The end of the token starting at `start`, as a person would read it.
fn token_end(text: &str, start: usize) -> usize {
    let rest = &text[start..];
    let bytes = rest.as_bytes();
    let Some(c) = rest.chars().next() else {
        return start;
    };
    let starts_number = c.is_ascii_digit()
        || (matches!(c, '.' | '-') && bytes.get(1).is_some_and(u8::is_ascii_digit));
    let len = if starts_number {
        1 + bytes[1..]
            .iter()
            .take_while(|&&b| is_ident_byte(b) || b == b'.' || b == b'%')
            .count()
    } else if is_ident_byte(bytes[0]) {
        // A word, or a (perhaps unfinished) metric reference `plan.metric`.
        let word = bytes.iter().take_while(|&&b| is_ident_byte(b)).count();
        if bytes.get(word) == Some(&b'.') {
            word + 1
                + bytes[word + 1..]
                    .iter()
                    .take_while(|&&b| is_ident_byte(b))
                    .count()
        } else {
            word
        }
    } else if c == '"' {
        match bytes[1..].iter().position(|&b| b == b'"' || b == b'\n') {
            Some(k) if bytes[1 + k] == b'"' => k + 2,
            Some(k) => k + 1,
            None => bytes.len(),
        }
    } else if ["<=", ">=", "==", "!=", "+-"]
        .iter()
        .any(|op| rest.starts_with(op))
    {
        2
    } else {
        c.len_utf8()
    };
    start + len
}

/// A token for a message: in backticks, control characters escaped, long ones cut.
fn show(token: &str) -> String {
    const MAX_CHARS: usize = 24;
    let mut shown: String = token
        .chars()
        .take(MAX_CHARS)
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect();
    if token.chars().count() > MAX_CHARS {
        shown.push('…');
    }
    format!("`{shown}`")
}

/// The span of the last character before `end` (for errors at the end of input).
fn last_char_span(text: &str, file: FileId, end: usize) -> Span {
    let len = text[..end].chars().next_back().map_or(0, char::len_utf8);
    Span::new(file, end - len, end)
}

/// A help line for a word that looks like one of `keywords` misspelt.
fn keyword_help(word: &str, keywords: &[&str]) -> Option<String> {
    let lower = word.to_ascii_lowercase();
    if lower != word && keywords.contains(&lower.as_str()) {
        return Some(format!("keywords are lowercase: `{lower}`"));
    }
    closest_keyword(word, keywords).map(|keyword| format!("did you mean `{keyword}`?"))
}

/// Leading text that is not a statement.
fn not_a_statement(text: &str, file: FileId, start: usize) -> Diag {
    let end = token_end(text, start);
    let token = &text[start..end];
    let diag = Diag::error("scen::syntax::expected", EXPECTED_STATEMENT).at(
        Span::new(file, start, end),
        format!("unexpected {}", show(token)),
    );
    diag.help(keyword_help(token, &STATEMENT_KEYWORDS).unwrap_or_else(|| {
        "a file is a list of statements, each beginning with its keyword; `#` starts a comment"
            .to_string()
    }))
}

/// What a rule looks like in "expected ..." messages; `None` hides it.
fn describe(rule: Rule) -> Option<&'static str> {
    Some(match rule {
        Rule::EOI => "the end of the statement",
        Rule::ident => "a name",
        Rule::plan_kind => "a planner kind (such as `astar`)",
        Rule::word => "a word",
        Rule::number | Rule::expr_number => "a number",
        // Silent and atomic helper rules never reach an error message.
        Rule::WHITESPACE
        | Rule::COMMENT_TEXT
        | Rule::STRING_TEXT
        | Rule::scenario_chunk
        | Rule::include_chunk
        | Rule::world_chunk
        | Rule::robot_chunk
        | Rule::plan_chunk
        | Rule::expect_chunk
        | Rule::statement_chunks
        | Rule::IDENT_START
        | Rule::IDENT_CHAR
        | Rule::IDENT
        | Rule::value
        | Rule::element
        | Rule::world_item
        | Rule::grid_name
        | Rule::WORD_END
        // A missing operand is reported as "an expression" (`primary`).
        | Rule::prefix => return None,
        Rule::string => "a string",
        Rule::lbrace | Rule::param_block | Rule::grid_rows => "`{`",
        Rule::rbrace => "`}`",
        Rule::lparen | Rule::paren => "`(`",
        Rule::rparen => "`)`",
        Rule::lbracket => "`[`",
        Rule::rbracket => "`]`",
        Rule::comma => "`,`",
        Rule::kw_scenario | Rule::scenario => "`scenario`",
        Rule::kw_include | Rule::include => "`include`",
        Rule::kw_world | Rule::world => "`world`",
        Rule::kw_robot | Rule::robot => "`robot`",
        Rule::kw_plan | Rule::plan => "`plan`",
        Rule::kw_expect | Rule::expect => "`expect`",
        Rule::kw_bounds | Rule::bounds => "`bounds`",
        Rule::kw_rect | Rule::rect_obstacle | Rule::rect_shape => "`rect`",
        Rule::kw_polygon | Rule::polygon_obstacle | Rule::polygon_shape => "`polygon`",
        Rule::kw_segment | Rule::segment_obstacle => "`segment`",
        Rule::kw_disk | Rule::disk_obstacle | Rule::disk_shape => "`disk`",
        Rule::kw_grid | Rule::grid_obstacle => "`grid`",
        Rule::kw_cell | Rule::grid_cell => "`cell`",
        Rule::kw_origin | Rule::grid_origin => "`origin`",
        Rule::kw_point | Rule::point_shape => "`point`",
        Rule::kw_true => "`true`",
        Rule::kw_false => "`false`",
        Rule::tuple => "a point `(x, y)`",
        Rule::list => "a list `[...]`",
        Rule::expr | Rule::operand | Rule::primary => "an expression",
        Rule::metric => "a metric `PLAN.METRIC`",
        Rule::operator => "an operator",
    })
}

/// "A", "A or B", "A, B or C".
fn one_of(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => (*one).to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// A pest error in `chunk` → a diagnostic with a readable message and, where
/// the likely fix is known, a help line.
fn syntax_error(text: &str, file: FileId, chunk: &Chunk, error: &pest::error::Error<Rule>) -> Diag {
    let pos = match error.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    let at = skip_trivia(text, (chunk.start + pos).min(chunk.end));
    let at_end = at >= chunk.end;
    let token_start = if at_end {
        skip_trivia(text, chunk.end)
    } else {
        at
    };
    let token = &text[token_start..token_end(text, token_start)];
    let found = if token.is_empty() {
        "the end of the file".to_string()
    } else {
        show(token)
    };

    let positives: Vec<Rule> = match &error.variant {
        ErrorVariant::ParsingError { positives, .. } => positives.clone(),
        ErrorVariant::CustomError { message } => {
            // pest's own call or stack limit: the depth check should prevent it.
            return Diag::error(
                "scen::syntax::too_deep",
                format!("statement too complex to parse ({message})"),
            )
            .at(
                Span::new(file, chunk.start, token_end(text, chunk.start)),
                "in this statement",
            )
            .help("split the statement or reduce its nesting");
        }
    };
    let mut expected: Vec<&str> = Vec::new();
    for description in positives.iter().filter_map(|&r| describe(r)) {
        if !expected.contains(&description) {
            expected.push(description);
        }
    }
    // pest lists rules in grammar order; closing brackets and the end of the
    // statement read best last.
    let closing = ["`)`", "`]`", "`}`", "the end of the statement"];
    expected.sort_by_key(|d| closing.iter().position(|c| c == d));
    // `value` is silent, so that pest does less work per value.
    let value_parts = ["a number", "a string", "`(`", "`[`"];
    if let Some(first) = expected.iter().position(|d| value_parts.contains(d))
        && value_parts.iter().all(|part| expected.contains(part))
    {
        expected.retain(|d| !value_parts.contains(d));
        expected.insert(first.min(expected.len()), "a value");
    }
    let only_end = expected == ["the end of the statement"];

    let span = if at_end {
        last_char_span(text, file, chunk.end)
    } else {
        Span::new(file, at, token_end(text, at))
    };
    let what = one_of(&expected);
    let message = if only_end {
        EXPECTED_STATEMENT.to_string()
    } else if expected.is_empty() {
        format!("unexpected {found}")
    } else {
        format!("expected {what}, found {found}")
    };
    let label = if at_end && !expected.is_empty() {
        format!("expected {what} after this")
    } else {
        format!("unexpected {found}")
    };
    let mut diag = Diag::error("scen::syntax::expected", message).at(span, label);

    // The innermost bracket still open where the error is.
    let open = if at_end {
        chunk.unclosed().last().copied()
    } else {
        innermost_open_bracket(text, chunk.start, at)
    };
    let open_closer = open.map(|k| match text.as_bytes()[k] {
        b'(' => "`)`",
        b'[' => "`]`",
        _ => "`}`",
    });
    let context = HelpContext {
        text,
        chunk,
        token,
        token_start,
        expected: &expected,
        positives: &positives,
        open_closer,
    };
    if let Some(help) = context.help() {
        diag = diag.help(help);
    }
    if let (Some(open), Some(closer)) = (open, open_closer)
        && expected.contains(&closer)
    {
        let bracket = &text[open..open + 1];
        let state = if at_end {
            "never closed"
        } else {
            "not closed yet"
        };
        diag = diag.with_related(
            Span::new(file, open, open + 1),
            format!("this `{bracket}` is {state}"),
        );
    }
    diag
}

/// What [`HelpContext::help`] looks at to suggest a fix for a pest error.
struct HelpContext<'a> {
    text: &'a str,
    chunk: &'a Chunk,
    /// The token found where the error is ("" at the end of the file).
    token: &'a str,
    token_start: usize,
    /// What was expected, as described to the user.
    expected: &'a [&'a str],
    positives: &'a [Rule],
    /// The closer of the innermost bracket open at the error, in backticks.
    open_closer: Option<&'static str>,
}

impl HelpContext<'_> {
    /// The likely fix, most specific first.
    fn help(&self) -> Option<String> {
        let (token, expected) = (self.token, self.expected);
        let has = |rule: Rule| self.positives.contains(&rule);
        let expects = |what: &str| expected.contains(&what);
        let only_end = expected == ["the end of the statement"];
        let is_word = token.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_');
        if token == "=" && has(Rule::operator) {
            return Some("compare with `==`".to_string());
        }
        if let Some(number) = detached_number(self.text, self.token_start, token) {
            return Some(format!(
                "write the unit right after the number: `{number}{token}`"
            ));
        }
        // A misspelt keyword: the candidates are the keywords expected here.
        let keywords: Vec<&str> = if only_end {
            STATEMENT_KEYWORDS.to_vec()
        } else {
            expected
                .iter()
                .filter_map(|d| d.strip_prefix('`')?.strip_suffix('`'))
                .filter(|k| k.bytes().all(|b| b.is_ascii_lowercase()))
                .collect()
        };
        if is_word && let Some(help) = keyword_help(token, &keywords) {
            return Some(help);
        }
        if expects("an expression") {
            if is_word && !["and", "or", "not"].contains(&token) {
                return Some(
                    "refer to a metric as `PLAN.METRIC`, e.g. `offline.found`".to_string(),
                );
            }
            return Some(
                match trailing_operator(self.text, self.chunk.start, self.token_start) {
                    Some(op) => {
                        format!("complete the expression after `{op}`, e.g. `offline.cost <= 90`")
                    }
                    None => "write a condition, e.g. `offline.found` or `offline.cost <= 90`"
                        .to_string(),
                },
            );
        }
        if token == "," && expects("a value") {
            return Some(
                "values are separated by blanks, commas only separate the elements of \
                 `( )` and `[ ]`: `bounds (0, 0) (10, 10)`"
                    .to_string(),
            );
        }
        if token == "," && expected == ["`)`"] {
            return Some("a point is `(x, y)` and a pose `(x, y, θ)`".to_string());
        }
        if only_end && token == "}" {
            return Some("this `}` has no matching `{`".to_string());
        }
        if only_end {
            let keyword = self.text[self.chunk.start..]
                .split(|c: char| !c.is_ascii_alphabetic())
                .next();
            return Some(format!(
                "the `{}` statement is complete before this: remove it, or begin a new \
                 statement with a keyword",
                keyword.unwrap_or_default()
            ));
        }
        if has(Rule::kw_point) {
            return Some(
                "a robot's shape is `point`, `disk RADIUS`, `rect WIDTH HEIGHT` or \
                 `polygon [(x, y), ...]`"
                    .to_string(),
            );
        }
        if self.chunk.rule == Some(Rule::plan_chunk) && (has(Rule::ident) || has(Rule::plan_kind)) {
            return Some("a plan is written `plan NAME KIND ROBOT { PARAMETERS }`".to_string());
        }
        if has(Rule::kw_origin) && expects("`{`") && is_word {
            return Some(
                "a grid's rows go in a block after it, top row first: \
                 `grid G cell 1 origin (0, 0) { \"..#\" \"...\" }`; or load a map: \
                 `grid G \"maps/x.map\" cell 1 origin (0, 0)`"
                    .to_string(),
            );
        }
        if let Some(closer) = self.open_closer.filter(|c| expects(c)) {
            return Some(format!("add the missing {closer}"));
        }
        if expects("`,`") {
            return Some("separate the elements with commas: `(x, y)`, `[a, b, c]`".to_string());
        }
        if has(Rule::kw_bounds) {
            return Some(
                "write one world item per line, e.g. `rect B1 (0, 0) (10, 1)`".to_string(),
            );
        }
        if expects("a string") {
            return Some("write text in double quotes: `\"...\"`".to_string());
        }
        if expects("a name") {
            return Some(
                "a name is a word: letters, digits and `_`, not starting with a digit".to_string(),
            );
        }
        if expects("a value") {
            return Some(
                "a value is a number (`1.5`, `90deg`, `50%`, `2s`), a string, a point `(x, y)` \
                 or a list `[...]`"
                    .to_string(),
            );
        }
        None
    }
}

/// The keyword among `keywords` that `word` most likely misspells: a longer
/// form of it (`robots`, `rectangle`, `degrees`), or at most a third of its
/// letters changed (in any case).
fn closest_keyword<'k>(word: &str, keywords: &[&'k str]) -> Option<&'k str> {
    if word.len() > 32 || keywords.contains(&word) {
        return None;
    }
    let lower = word.to_ascii_lowercase();
    keywords
        .iter()
        .map(|&k| {
            let distance = if k.len() >= 3 && lower.starts_with(k) {
                0
            } else {
                edit_distance(lower.as_bytes(), k.as_bytes())
            };
            (distance, k)
        })
        .filter(|&(distance, k)| distance <= (k.len() / 3).max(1))
        .min()
        .map(|(_, k)| k)
}

/// The operator that `text[from..at]` ends with, blanks ignored.
fn trailing_operator(text: &str, from: usize, at: usize) -> Option<&'static str> {
    const OPERATORS: [&str; 16] = [
        "<=", ">=", "==", "!=", "+-", "<", ">", "~", "±", "+", "-", "*", "/", "and", "or", "not",
    ];
    let before = text[from..at].trim_end_matches(is_blank);
    OPERATORS.into_iter().find(|op| {
        before.strip_suffix(op).is_some_and(|rest| {
            !op.starts_with(|c: char| c.is_ascii_alphabetic())
                || !rest.ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_')
        })
    })
}

/// The innermost bracket open at `at`, scanning `text[from..at]` with strings
/// and comments skipped.
fn innermost_open_bracket(text: &str, from: usize, at: usize) -> Option<usize> {
    let bytes = &text.as_bytes()[..at];
    let mut open = Vec::new();
    let mut i = from;
    while i < bytes.len() {
        match bytes[i] {
            b'"' => {
                i = scan_string(bytes, i).0;
                continue;
            }
            b'#' => {
                i = bytes[i..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(bytes.len(), |k| i + k);
                continue;
            }
            b'(' | b'[' | b'{' => open.push(i),
            b')' | b']' | b'}' => {
                open.pop();
            }
            _ => {}
        }
        i += 1;
    }
    open.pop()
}

/// When `token` is a unit written apart from the number before it (`90 deg`),
/// that number.
fn detached_number<'t>(text: &'t str, token_start: usize, token: &str) -> Option<&'t str> {
    if !(UNIT_WORDS.contains(&token) || token == "%") {
        return None;
    }
    let before = &text[..token_start];
    let trimmed = before.trim_end_matches([' ', '\t']);
    if trimmed.len() == before.len() {
        return None;
    }
    let number_start = trimmed
        .rfind(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | 'e' | 'E' | '+')))
        .map_or(0, |k| k + 1);
    let number = &trimmed[number_start..];
    number.bytes().any(|b| b.is_ascii_digit()).then_some(number)
}

/// Splits a number token (grammar rule `number`) into its literal, as Rust's
/// `f64` parser reads it (`-`? digits, `.` digits, exponent), and the rest,
/// which should be a unit.
fn split_number(token: &str) -> (&str, &str) {
    let b = token.as_bytes();
    let digits_from = |mut i: usize| {
        while b.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        i
    };
    let mut end = digits_from(usize::from(b.first() == Some(&b'-')));
    if b.get(end) == Some(&b'.') && b.get(end + 1).is_some_and(u8::is_ascii_digit) {
        end = digits_from(end + 1);
    }
    if matches!(b.get(end), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(b.get(end + 1), Some(b'+' | b'-')));
        let exponent_end = digits_from(end + 1 + sign);
        if exponent_end > end + 1 + sign {
            end = exponent_end;
        }
    }
    token.split_at(end)
}

// ------------------------------------------------------------ pairs → AST

/// Binding powers of `expect` operators, loosest first. `not` binds looser
/// than a comparison (`not a < b` is `not (a < b)`), unary `-` tightest.
const OR_POWER: u8 = 1;
const AND_POWER: u8 = 2;
const NOT_POWER: u8 = 3;
const COMPARE_POWER: u8 = 4;
const ADD_POWER: u8 = 5;
const MUL_POWER: u8 = 6;
const NEG_POWER: u8 = 7;

/// The binding power of an infix `operator` token. `+-` gets a comparison's
/// power so that a stray one stops the operand before it and is reported.
fn infix_power(operator: &str) -> u8 {
    match operator {
        "or" => OR_POWER,
        "and" => AND_POWER,
        "+" | "-" => ADD_POWER,
        "*" | "/" => MUL_POWER,
        _ => COMPARE_POWER,
    }
}

/// An expression under construction.
struct Built {
    expr: Expr,
    /// The height of its tree, bounded by [`MAX_EXPR_HEIGHT`].
    height: usize,
    /// A comparison not in parentheses: another comparison may not follow it.
    comparison: bool,
}

impl Built {
    fn new(expr: Expr, height: usize) -> Self {
        Built {
            expr,
            height,
            comparison: false,
        }
    }
}

/// Turns the pairs of one chunk into AST nodes. Spans are offset by `base`,
/// the chunk's offset in the file.
struct Builder<'t, 'd> {
    text: &'t str,
    file: FileId,
    base: usize,
    diags: &'d mut Vec<Diag>,
    /// Whether this statement's "expression too deep" was reported already.
    expr_too_deep: bool,
}

type P<'i> = Pair<'i, Rule>;

fn is_punctuation(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::lbrace
            | Rule::rbrace
            | Rule::lparen
            | Rule::rparen
            | Rule::lbracket
            | Rule::rbracket
            | Rule::comma
            | Rule::EOI
    )
}

/// Where the text of `pair` ends, in the chunk. A pest rule that ends with
/// an optional or repeated part (`grid ... cell 1`, an expression) also spans
/// the blanks and comments skipped before pest found that part absent.
fn content_end(pair: &P<'_>) -> usize {
    match pair.clone().into_inner().next_back() {
        Some(last) => content_end(&last),
        None => pair.as_span().end(),
    }
}

/// The children of `pair` that carry meaning (punctuation left out).
fn children(pair: P<'_>) -> impl Iterator<Item = P<'_>> {
    pair.into_inner().filter(|p| !is_punctuation(p.as_rule()))
}

impl Builder<'_, '_> {
    fn span(&self, pair: &P<'_>) -> Span {
        let s = pair.as_span();
        Span::new(self.file, self.base + s.start(), self.base + s.end())
    }

    /// The span of a rule that may end with an absent optional part (see
    /// [`content_end`]).
    fn trimmed_span(&self, pair: &P<'_>) -> Span {
        let start = pair.as_span().start();
        Span::new(self.file, self.base + start, self.base + content_end(pair))
    }

    fn ident(&self, pair: &P<'_>) -> Ident {
        Spanned::new(pair.as_str().to_string(), self.span(pair))
    }

    fn statement(&mut self, pair: P<'_>) -> Option<Stmt> {
        let span = self.span(&pair);
        Some(match pair.as_rule() {
            Rule::scenario => {
                let title =
                    self.string(&children(pair).nth(1).expect("grammar guarantees a title"));
                Stmt::Scenario { title, span }
            }
            Rule::include => {
                let path = self.string(&children(pair).nth(1).expect("grammar guarantees a path"));
                Stmt::Include { path, span }
            }
            Rule::world => Stmt::World(self.world(pair)),
            Rule::robot => Stmt::Robot(self.robot(pair)),
            Rule::plan => Stmt::Plan(self.plan(pair)),
            Rule::expect => {
                let expr = children(pair)
                    .nth(1)
                    .expect("grammar guarantees an expression");
                Stmt::Expect(self.expression(expr, 0)?.expr)
            }
            rule => unreachable!("grammar guarantees a statement, got {rule:?}"),
        })
    }

    fn world(&mut self, pair: P<'_>) -> WorldBlock {
        let span = self.span(&pair);
        let mut inner = children(pair);
        let keyword = self.span(&inner.next().expect("grammar guarantees `world`"));
        let items = inner.map(|item| self.world_item(item)).collect();
        WorldBlock {
            items,
            keyword,
            span,
        }
    }

    fn world_item(&mut self, pair: P<'_>) -> WorldItem {
        let span = self.trimmed_span(&pair);
        let rule = pair.as_rule();
        let mut inner = children(pair).peekable();
        let keyword = inner.next().expect("grammar guarantees a keyword");
        if rule == Rule::bounds {
            let min = self.value(inner.next().expect("grammar guarantees a min corner"));
            let max = self.value(inner.next().expect("grammar guarantees a max corner"));
            return WorldItem::Bounds { min, max, span };
        }
        let kind = match rule {
            Rule::rect_obstacle => ObstacleKind::Rect,
            Rule::polygon_obstacle => ObstacleKind::Polygon,
            Rule::segment_obstacle => ObstacleKind::Segment,
            Rule::disk_obstacle => ObstacleKind::Disk,
            Rule::grid_obstacle => ObstacleKind::Grid,
            rule => unreachable!("grammar guarantees a world item, got {rule:?}"),
        };
        let name = inner
            .next_if(|p| p.as_rule() == Rule::ident)
            .map(|p| self.ident(&p));
        let mut next_value = |this: &mut Self| {
            this.value(
                inner
                    .next()
                    .expect("grammar guarantees the obstacle's values"),
            )
        };
        let shape = match kind {
            ObstacleKind::Rect => ObstacleShape::Rect(next_value(self), next_value(self)),
            ObstacleKind::Polygon => ObstacleShape::Polygon(next_value(self)),
            ObstacleKind::Segment => ObstacleShape::Segment(next_value(self), next_value(self)),
            ObstacleKind::Disk => ObstacleShape::Disk(next_value(self), next_value(self)),
            ObstacleKind::Grid => ObstacleShape::Grid(self.grid(inner, span)),
        };
        WorldItem::Obstacle(ObstacleDecl {
            kind: Spanned::new(kind, self.span(&keyword)),
            name,
            shape,
            span,
        })
    }

    /// The rest of a `grid` item after its name. A repeated `cell` or
    /// `origin` is an error; the first one is kept.
    fn grid<'i>(&mut self, options: impl Iterator<Item = P<'i>>, span: Span) -> GridSpec {
        let mut grid = GridSpec {
            file: None,
            cell: None,
            origin: None,
            rows: None,
            span,
        };
        let mut cell_span: Option<Span> = None;
        let mut origin_span: Option<Span> = None;
        for option in options {
            let option_span = self.span(&option);
            match option.as_rule() {
                Rule::string => grid.file = Some(self.string(&option)),
                Rule::grid_rows => {
                    grid.rows = Some(children(option).map(|row| self.string(&row)).collect());
                }
                rule @ (Rule::grid_cell | Rule::grid_origin) => {
                    let (first, slot, key) = if rule == Rule::grid_cell {
                        (&mut cell_span, &mut grid.cell, "cell")
                    } else {
                        (&mut origin_span, &mut grid.origin, "origin")
                    };
                    let value = children(option).nth(1).expect("grammar guarantees a value");
                    let value = self.value(value);
                    match *first {
                        Some(first) => self.diags.push(
                            Diag::error(
                                "scen::syntax::duplicate_option",
                                format!("`{key}` is given twice for this grid"),
                            )
                            .at(option_span, "given again here")
                            .with_related(first, "first given here")
                            .help(format!("keep one `{key}`")),
                        ),
                        None => {
                            *first = Some(option_span);
                            *slot = Some(value);
                        }
                    }
                }
                rule => unreachable!("grammar guarantees a grid option, got {rule:?}"),
            }
        }
        grid
    }

    fn robot(&mut self, pair: P<'_>) -> RobotDecl {
        let span = self.span(&pair);
        let mut inner = children(pair).skip(1);
        let name = self.ident(&inner.next().expect("grammar guarantees a robot name"));
        let shape_pair = inner.next().expect("grammar guarantees a robot shape");
        let shape_rule = shape_pair.as_rule();
        let shape_span = self.span(&shape_pair);
        let mut values = children(shape_pair).skip(1).map(|v| self.value(v));
        let mut next = || {
            values
                .next()
                .expect("grammar guarantees the shape's values")
        };
        let shape = match shape_rule {
            Rule::point_shape => RobotShape::Point(shape_span),
            Rule::disk_shape => RobotShape::Disk(next()),
            Rule::rect_shape => RobotShape::Rect(next(), next()),
            Rule::polygon_shape => RobotShape::Polygon(next()),
            rule => unreachable!("grammar guarantees a robot shape, got {rule:?}"),
        };
        RobotDecl { name, shape, span }
    }

    fn plan(&mut self, pair: P<'_>) -> PlanDecl {
        let span = self.span(&pair);
        let mut inner = children(pair).skip(1);
        let mut next = || {
            inner
                .next()
                .expect("grammar guarantees `plan NAME KIND ROBOT { }`")
        };
        let name = self.ident(&next());
        let kind = self.ident(&next());
        let robot = self.ident(&next());
        let body = self.param_tokens(next());
        PlanDecl {
            name,
            kind,
            robot,
            body,
            span,
        }
    }

    /// The tokens of a `{ ... }` block of plan parameters.
    fn param_tokens(&mut self, block: P<'_>) -> Vec<ParamToken> {
        let mut tokens = Vec::new();
        for pair in children(block) {
            tokens.push(match pair.as_rule() {
                Rule::param_block => {
                    let span = self.span(&pair);
                    ParamToken::Block {
                        tokens: self.param_tokens(pair),
                        span,
                    }
                }
                Rule::word => ParamToken::Word(self.ident(&pair)),
                Rule::number | Rule::string | Rule::tuple | Rule::list => {
                    ParamToken::Value(self.value(pair))
                }
                rule => unreachable!("grammar guarantees a parameter token, got {rule:?}"),
            });
        }
        self.check_detached_units(&tokens);
        tokens
    }

    /// `90 deg` in a plan body parses as a number and a word; say what was meant.
    fn check_detached_units(&mut self, tokens: &[ParamToken]) {
        for pair in tokens.windows(2) {
            let [ParamToken::Value(number), ParamToken::Word(unit)] = pair else {
                continue;
            };
            let between = &self.text[number.span.end..unit.span.start];
            if matches!(number.kind, ValueKind::Number(_))
                && UNIT_WORDS.contains(&unit.value.as_str())
                && between.chars().all(|c| c == ' ' || c == '\t')
            {
                let number_text = &self.text[number.span.start..number.span.end];
                self.diags.push(
                    Diag::error(
                        "scen::syntax::detached_unit",
                        format!("the unit `{}` is separated from its number", unit.value),
                    )
                    .at(number.span.to(unit.span), "a number, then a separate word")
                    .help(format!(
                        "write the unit right after the number: `{number_text}{}`",
                        unit.value
                    )),
                );
            }
        }
    }

    /// A value: a `number`, `string`, `tuple` or `list` pair, or a `word` in a
    /// container.
    fn value(&mut self, pair: P<'_>) -> Value {
        let span = self.span(&pair);
        let kind = match pair.as_rule() {
            Rule::number => self.quantity(pair),
            Rule::string => ValueKind::Str(self.string(&pair).value),
            Rule::word => ValueKind::Word(pair.as_str().to_string()),
            Rule::tuple => ValueKind::Tuple(children(pair).map(|p| self.value(p)).collect()),
            Rule::list => ValueKind::List(children(pair).map(|p| self.value(p)).collect()),
            rule => unreachable!("grammar guarantees a value, got {rule:?}"),
        };
        Value { kind, span }
    }

    /// A `number` or `expr_number` pair: a number and its unit, converted to
    /// radians, seconds or a fraction. Errors leave a `Number` placeholder.
    fn quantity(&mut self, pair: P<'_>) -> ValueKind {
        let span = self.span(&pair);
        let token = pair.as_str();
        let (literal, unit) = split_number(token);
        let unit_span = Span::new(self.file, span.start + literal.len(), span.end);
        let unit_is_word = unit.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
            && unit.bytes().all(is_ident_byte);
        if !(unit.is_empty() || unit == "%" || unit_is_word) {
            let help = if unit.starts_with(['e', 'E']) {
                "an exponent needs digits, as in `1e-3`"
            } else {
                "write numbers as `12`, `-3.5`, `1e-3` or `.5`"
            };
            self.diags.push(
                Diag::error(
                    "scen::syntax::bad_number",
                    format!("malformed number {}", show(token)),
                )
                .at(span, "not a number")
                .help(help),
            );
            return ValueKind::Number(0.0);
        }
        let x = match literal.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            _ => {
                self.diags.push(
                    Diag::error("scen::syntax::bad_number", "number out of range")
                        .at(
                            Span::new(self.file, span.start, span.start + literal.len()),
                            "too large for a 64-bit floating-point number",
                        )
                        .help("numbers must lie within ±1.8e308"),
                );
                return ValueKind::Number(0.0);
            }
        };
        match unit {
            "" => ValueKind::Number(x),
            "deg" => ValueKind::Angle(x.to_radians()),
            "rad" => ValueKind::Angle(x),
            "%" => ValueKind::Percent(x / 100.0),
            "ms" => ValueKind::Duration(x / 1000.0),
            "s" => ValueKind::Duration(x),
            other => {
                let help = if other.eq_ignore_ascii_case("e") {
                    "an exponent needs digits, as in `1e-3`".to_string()
                } else if let Some(unit) = closest_keyword(other, &UNIT_WORDS) {
                    format!("did you mean `{literal}{unit}`?")
                } else {
                    UNITS_HELP.to_string()
                };
                self.diags.push(
                    Diag::error(
                        "scen::syntax::bad_unit",
                        format!("unknown unit {}", show(other)),
                    )
                    .at(unit_span, "not a unit")
                    .help(help),
                );
                ValueKind::Number(x)
            }
        }
    }

    /// A string literal without its quotes, with `\"` and `\\` unescaped.
    fn string(&mut self, pair: &P<'_>) -> Spanned<String> {
        let span = self.span(pair);
        let raw = pair.as_str();
        let body = &raw[1..raw.len() - 1];
        let mut value = String::with_capacity(body.len());
        let mut chars = body.char_indices();
        while let Some((k, c)) = chars.next() {
            if c != '\\' {
                value.push(c);
                continue;
            }
            let Some((_, escaped)) = chars.next() else {
                break;
            };
            match escaped {
                '"' | '\\' => value.push(escaped),
                other => {
                    let start = span.start + 1 + k;
                    let end = start + 1 + other.len_utf8();
                    self.diags.push(
                        Diag::error(
                            "scen::syntax::bad_escape",
                            format!("unknown escape `\\{other}` in a string"),
                        )
                        .at(Span::new(self.file, start, end), "not an escape")
                        .help("the only escapes are `\\\"` and `\\\\`; write paths with `/`"),
                    );
                    value.push('\\');
                    value.push(other);
                }
            }
        }
        Spanned::new(value, span)
    }

    // --------------------------------------------------------- expressions

    /// An `expr` pair: a flat sequence of operands and operators, given its
    /// tree by precedence climbing. `depth` counts the enclosing parentheses
    /// and operators, for [`MAX_EXPR_HEIGHT`].
    fn expression(&mut self, pair: P<'_>, depth: usize) -> Option<Built> {
        let mut tokens = Vec::new();
        for child in pair.into_inner() {
            match child.as_rule() {
                Rule::operand => tokens.extend(child.into_inner()),
                _ => tokens.push(child),
            }
        }
        let mut pos = 0;
        let built = self.climb(&tokens, &mut pos, 0, depth)?;
        debug_assert_eq!(pos, tokens.len(), "every token of the expression is used");
        Some(built)
    }

    /// Parses `tokens[*pos..]` up to the first operator that binds no tighter
    /// than `min_power` (see [`infix_power`]).
    fn climb(
        &mut self,
        tokens: &[P<'_>],
        pos: &mut usize,
        min_power: u8,
        depth: usize,
    ) -> Option<Built> {
        let first = &tokens[*pos];
        *pos += 1;
        let first_span = self.span(first);
        self.check_height(depth, first_span)?;
        let mut lhs = match first.as_rule() {
            Rule::prefix => {
                let (power, negate) = if first.as_str() == "-" {
                    (NEG_POWER, true)
                } else {
                    (NOT_POWER, false)
                };
                let operand = self.climb(tokens, pos, power, depth + 1)?;
                let span = first_span.to(operand.expr.span);
                let inner = Box::new(operand.expr);
                let kind = if negate {
                    ExprKind::Neg(inner)
                } else {
                    ExprKind::Not(inner)
                };
                Built::new(Expr { kind, span }, operand.height + 1)
            }
            Rule::primary => self.primary(first.clone(), depth)?,
            rule => unreachable!("grammar guarantees an operand, got {rule:?}"),
        };
        while let Some(op) = tokens.get(*pos) {
            let op_span = self.span(op);
            let text = op.as_str();
            let power = infix_power(text);
            if power <= min_power {
                break;
            }
            *pos += 1;
            if matches!(text, "+-" | "±") {
                self.diags.push(
                    Diag::error("scen::syntax::expected", format!("`{text}` without `~`"))
                        .at(op_span, "a tolerance needs an approximate comparison")
                        .help("approximate equality is written `A ~ B +- TOL`"),
                );
                return None;
            }
            let comparison = power == COMPARE_POWER;
            if comparison && lhs.comparison {
                self.diags.push(
                    Diag::error(
                        "scen::syntax::chained_comparison",
                        "comparisons cannot be chained",
                    )
                    .at(op_span, "a second comparison")
                    .with_related(lhs.expr.span, "the first comparison")
                    .help("join two comparisons with `and`: `a < b and b < c`"),
                );
                return None;
            }
            let rhs = self.climb(tokens, pos, power, depth + 1)?;
            let (lhs_expr, rhs_expr) = (Box::new(lhs.expr), Box::new(rhs.expr));
            let mut height = lhs.height.max(rhs.height);
            let kind = match text {
                "or" => ExprKind::Or(lhs_expr, rhs_expr),
                "and" => ExprKind::And(lhs_expr, rhs_expr),
                "~" => {
                    let tolerance = tokens
                        .get(*pos)
                        .filter(|t| matches!(t.as_str(), "+-" | "±"));
                    if tolerance.is_none() {
                        self.diags.push(
                            Diag::error(
                                "scen::syntax::expected",
                                "expected `+-` and a tolerance after `A ~ B`",
                            )
                            .at(op_span, "an approximate comparison without a tolerance")
                            .help("approximate equality needs a tolerance: `A ~ B +- TOL`"),
                        );
                        return None;
                    }
                    *pos += 1;
                    let tol = self.climb(tokens, pos, COMPARE_POWER, depth + 1)?;
                    height = height.max(tol.height);
                    ExprKind::Approx {
                        lhs: lhs_expr,
                        rhs: rhs_expr,
                        tol: Box::new(tol.expr),
                    }
                }
                _ if comparison => {
                    let op = match text {
                        "<" => CompareOp::Lt,
                        "<=" => CompareOp::Le,
                        ">" => CompareOp::Gt,
                        ">=" => CompareOp::Ge,
                        "==" => CompareOp::Eq,
                        _ => CompareOp::Ne,
                    };
                    ExprKind::Compare {
                        op,
                        lhs: lhs_expr,
                        rhs: rhs_expr,
                    }
                }
                _ => {
                    let op = match text {
                        "+" => ArithOp::Add,
                        "-" => ArithOp::Sub,
                        "*" => ArithOp::Mul,
                        _ => ArithOp::Div,
                    };
                    ExprKind::Arith {
                        op,
                        lhs: lhs_expr,
                        rhs: rhs_expr,
                    }
                }
            };
            let span = first_span.to(self.span(&tokens[*pos - 1]));
            let height = self.check_height(height + 1, span)?;
            lhs = Built {
                expr: Expr { kind, span },
                height,
                comparison,
            };
        }
        Some(lhs)
    }

    /// A `primary` pair: a number, `true`, `false`, `PLAN.METRIC` or `( expr )`.
    fn primary(&mut self, pair: P<'_>, depth: usize) -> Option<Built> {
        let inner = pair
            .into_inner()
            .next()
            .expect("grammar guarantees a primary");
        let span = self.span(&inner);
        let kind = match inner.as_rule() {
            Rule::paren => {
                let expr = children(inner)
                    .next()
                    .expect("grammar guarantees `( expr )`");
                let built = self.expression(expr, depth + 1)?;
                // The span includes the parentheses, so an enclosing
                // expression's span covers them too.
                return Some(Built::new(
                    Expr {
                        kind: built.expr.kind,
                        span,
                    },
                    built.height,
                ));
            }
            Rule::expr_number => {
                match self.quantity(inner) {
                    ValueKind::Percent(x) => ExprKind::Percent(x),
                    // Angle metrics (`turn`) are in radians.
                    ValueKind::Number(x) | ValueKind::Angle(x) => ExprKind::Number(x),
                    ValueKind::Duration(seconds) => {
                        self.diags.push(
                        Diag::error("scen::syntax::unit_not_allowed", "a duration cannot appear in an expectation")
                            .at(span, "a duration")
                            .help(format!(
                                "metrics are plain numbers (`time_ms` is in milliseconds): write `{}`",
                                seconds * 1000.0
                            )),
                    );
                        ExprKind::Number(seconds)
                    }
                    other => unreachable!("a number token is a quantity, got {other:?}"),
                }
            }
            Rule::kw_true => ExprKind::Bool(true),
            Rule::kw_false => ExprKind::Bool(false),
            Rule::metric => {
                let (plan, metric) = inner
                    .as_str()
                    .split_once('.')
                    .expect("grammar guarantees `PLAN.METRIC`");
                let dot = span.start + plan.len();
                ExprKind::Metric {
                    plan: Spanned::new(plan.to_string(), Span::new(self.file, span.start, dot)),
                    metric: Spanned::new(
                        metric.to_string(),
                        Span::new(self.file, dot + 1, span.end),
                    ),
                }
            }
            rule => unreachable!("grammar guarantees a primary, got {rule:?}"),
        };
        Some(Built::new(Expr { kind, span }, 1))
    }

    fn check_height(&mut self, height: usize, span: Span) -> Option<usize> {
        if height <= MAX_EXPR_HEIGHT {
            return Some(height);
        }
        if !self.expr_too_deep {
            self.expr_too_deep = true;
            self.diags.push(
                Diag::error(
                    "scen::syntax::too_deep",
                    format!("expression nested more than {MAX_EXPR_HEIGHT} operators deep"),
                )
                .at(span, "this expression is too deep")
                .help("split it into several `expect` statements"),
            );
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_ok(text: &str) -> Vec<Stmt> {
        let (file, diags) = parse(text, 0);
        assert!(
            diags.is_empty(),
            "unexpected diagnostics for {text:?}: {diags:#?}"
        );
        file.statements
    }

    fn errors(text: &str) -> Vec<Diag> {
        let (_, diags) = parse(text, 0);
        assert!(!diags.is_empty(), "expected an error for {text:?}");
        diags
    }

    fn line_of(text: &str, span: Span) -> usize {
        text[..span.start].matches('\n').count() + 1
    }

    fn expr(text: &str) -> Expr {
        match parse_ok(&format!("expect {text}")).pop() {
            Some(Stmt::Expect(e)) => e,
            other => panic!("not an expect: {other:?}"),
        }
    }

    /// An expression tree in prefix form, for compact assertions.
    fn sexp(e: &Expr) -> String {
        match &e.kind {
            ExprKind::Number(x) => format!("{x}"),
            ExprKind::Percent(x) => format!("{x}%"),
            ExprKind::Bool(b) => format!("{b}"),
            ExprKind::Metric { plan, metric } => format!("{}.{}", plan.value, metric.value),
            ExprKind::Neg(a) => format!("(neg {})", sexp(a)),
            ExprKind::Not(a) => format!("(not {})", sexp(a)),
            ExprKind::Arith { op, lhs, rhs } => {
                format!("({} {} {})", op.symbol(), sexp(lhs), sexp(rhs))
            }
            ExprKind::Compare { op, lhs, rhs } => {
                format!("({} {} {})", op.symbol(), sexp(lhs), sexp(rhs))
            }
            ExprKind::Approx { lhs, rhs, tol } => {
                format!("(~ {} {} {})", sexp(lhs), sexp(rhs), sexp(tol))
            }
            ExprKind::And(a, b) => format!("(and {} {})", sexp(a), sexp(b)),
            ExprKind::Or(a, b) => format!("(or {} {})", sexp(a), sexp(b)),
        }
    }

    fn snippet(text: &str, span: Span) -> &str {
        &text[span.start..span.end]
    }

    fn number(v: &Value) -> f64 {
        match v.kind {
            ValueKind::Number(x) => x,
            ref other => panic!("not a number: {other:?}"),
        }
    }

    fn world_items(text: &str) -> Vec<WorldItem> {
        match parse_ok(text).pop() {
            Some(Stmt::World(w)) => w.items,
            other => panic!("not a world: {other:?}"),
        }
    }

    fn plan_body(text: &str) -> Vec<ParamToken> {
        match parse_ok(text).pop() {
            Some(Stmt::Plan(p)) => p.body,
            other => panic!("not a plan: {other:?}"),
        }
    }

    const APARTMENT: &str = r#"scenario "Apartment: the 8x1 rod"   # title
include "common.scen"

world {
  bounds (0, 0) (32, 30)                  # min corner, max corner (required)
  rect    B1 (0, 18) (10, 19)             # two opposite corners
  polygon P1 [(1,1), (3,1), (2,4)]        # simple polygon, either orientation
  segment W1 (26, 10) (26, 22)            # zero-thickness wall
  disk    C1 (5, 5) 1.5                   # centre, radius
  grid    G  "maps/arena.map" cell 1 origin (0, 0)      # MovingAI .map file
  grid    F  cell 0.5 origin (0, 0) {                   # inline rows, top row first
    "....##...."
    "..3......."
  }
}

robot rod  polygon [(0,0), (8,0), (8,1), (0,1)]   # convex, in the robot frame
robot box  rect 2 1
robot dot  disk 0.5
robot p    point

plan offline astar rod {
  start (4, 24, 0deg)  goal (28, 4, 90deg)
  cell 1 layers auto
  limit expansions 100000 time 2s
  drive unicycle { dt 0.02 max_speed 1.5 }
}

expect offline.found
expect offline.collision_free
expect offline.cost <= 90
expect offline.expanded < 6000 and offline.nodes >= 10
expect not tight.found
expect live.traveled <= 50 * offline.length
expect vg.length ~ 27.3137 +- 0.001
expect cover.coverage == 100%
"#;

    #[test]
    fn parses_every_construct_of_the_spec() {
        let statements = parse_ok(APARTMENT);
        assert_eq!(statements.len(), 16);
        let Stmt::Scenario { title, span } = &statements[0] else {
            panic!()
        };
        assert_eq!(title.value, "Apartment: the 8x1 rod");
        assert_eq!(
            snippet(APARTMENT, *span),
            r#"scenario "Apartment: the 8x1 rod""#
        );
        let Stmt::Include { path, .. } = &statements[1] else {
            panic!()
        };
        assert_eq!(path.value, "common.scen");
        assert_eq!(snippet(APARTMENT, path.span), r#""common.scen""#);

        let Stmt::World(world) = &statements[2] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, world.keyword), "world");
        assert!(snippet(APARTMENT, world.span).starts_with("world {"));
        assert!(snippet(APARTMENT, world.span).ends_with('}'));
        assert_eq!(world.items.len(), 7);
        let WorldItem::Bounds { min, max, span } = &world.items[0] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, *span), "bounds (0, 0) (32, 30)");
        assert_eq!(snippet(APARTMENT, min.span), "(0, 0)");
        let ValueKind::Tuple(xy) = &max.kind else {
            panic!()
        };
        assert_eq!((number(&xy[0]), number(&xy[1])), (32.0, 30.0));

        let names: Vec<_> = world.items[1..]
            .iter()
            .map(|item| match item {
                WorldItem::Obstacle(o) => (o.kind.value, o.name.as_ref().map(|n| n.value.clone())),
                _ => panic!(),
            })
            .collect();
        use ObstacleKind::*;
        let expected = [
            (Rect, "B1"),
            (Polygon, "P1"),
            (Segment, "W1"),
            (Disk, "C1"),
            (Grid, "G"),
            (Grid, "F"),
        ];
        assert_eq!(names, expected.map(|(k, n)| (k, Some(n.to_string()))));

        let WorldItem::Obstacle(disk) = &world.items[4] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, disk.span), "disk    C1 (5, 5) 1.5");
        assert_eq!(snippet(APARTMENT, disk.kind.span), "disk");
        let ObstacleShape::Disk(_, radius) = &disk.shape else {
            panic!()
        };
        assert_eq!(number(radius), 1.5);
        let WorldItem::Obstacle(polygon) = &world.items[2] else {
            panic!()
        };
        let ObstacleShape::Polygon(Value {
            kind: ValueKind::List(points),
            ..
        }) = &polygon.shape
        else {
            panic!()
        };
        assert_eq!(points.len(), 3);

        let WorldItem::Obstacle(g) = &world.items[5] else {
            panic!()
        };
        assert_eq!(
            snippet(APARTMENT, g.span),
            r#"grid    G  "maps/arena.map" cell 1 origin (0, 0)"#
        );
        let WorldItem::Obstacle(g) = &world.items[5] else {
            panic!()
        };
        let ObstacleShape::Grid(g) = &g.shape else {
            panic!()
        };
        assert_eq!(
            g.file.as_ref().map(|f| f.value.as_str()),
            Some("maps/arena.map")
        );
        assert_eq!(g.cell.as_ref().map(number), Some(1.0));
        assert!(matches!(
            g.origin,
            Some(Value {
                kind: ValueKind::Tuple(_),
                ..
            })
        ));
        assert!(g.rows.is_none());
        let WorldItem::Obstacle(f) = &world.items[6] else {
            panic!()
        };
        let ObstacleShape::Grid(f) = &f.shape else {
            panic!()
        };
        assert!(f.file.is_none());
        assert_eq!(f.cell.as_ref().map(number), Some(0.5));
        let rows: Vec<_> = f
            .rows
            .as_ref()
            .unwrap()
            .iter()
            .map(|r| r.value.as_str())
            .collect();
        assert_eq!(rows, ["....##....", "..3......."]);

        let robots: Vec<_> = statements[3..7]
            .iter()
            .map(|s| match s {
                Stmt::Robot(r) => r,
                _ => panic!(),
            })
            .collect();
        assert_eq!(robots[0].name.value, "rod");
        assert!(matches!(
            robots[0].shape,
            RobotShape::Polygon(Value {
                kind: ValueKind::List(_),
                ..
            })
        ));
        let RobotShape::Rect(w, h) = &robots[1].shape else {
            panic!()
        };
        assert_eq!((number(w), number(h)), (2.0, 1.0));
        let RobotShape::Disk(r) = &robots[2].shape else {
            panic!()
        };
        assert_eq!(number(r), 0.5);
        let RobotShape::Point(span) = robots[3].shape else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, span), "point");
        assert_eq!(snippet(APARTMENT, robots[3].span), "robot p    point");

        let Stmt::Plan(plan) = &statements[7] else {
            panic!()
        };
        assert_eq!(
            (plan.name.value.as_str(), plan.kind.value.as_str()),
            ("offline", "astar")
        );
        assert_eq!(plan.robot.value, "rod");
        assert!(snippet(APARTMENT, plan.span).starts_with("plan offline"));
        assert!(snippet(APARTMENT, plan.span).ends_with('}'));
        let words: Vec<String> = plan
            .body
            .iter()
            .map(|t| match t {
                ParamToken::Word(w) => w.value.clone(),
                ParamToken::Value(v) => format!("<{}>", v.kind.describe()),
                ParamToken::Block { tokens, .. } => format!("{{{}}}", tokens.len()),
            })
            .collect();
        assert_eq!(
            words.join(" "),
            "start <a point> goal <a point> cell <a number> layers auto limit expansions <a number> \
             time <a duration> drive unicycle {4}"
        );

        let checks: Vec<String> = statements[8..]
            .iter()
            .map(|s| match s {
                Stmt::Expect(e) => sexp(e),
                _ => panic!(),
            })
            .collect();
        assert_eq!(
            checks,
            [
                "offline.found",
                "offline.collision_free",
                "(<= offline.cost 90)",
                "(and (< offline.expanded 6000) (>= offline.nodes 10))",
                "(not tight.found)",
                "(<= live.traveled (* 50 offline.length))",
                "(~ vg.length 27.3137 0.001)",
                "(== cover.coverage 1%)",
            ]
        );
        let Stmt::Expect(e) = &statements[14] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, e.span), "vg.length ~ 27.3137 +- 0.001");
    }

    #[test]
    fn empty_and_comment_only_files_have_no_statements_and_no_errors() {
        assert!(parse_ok("").is_empty());
        assert!(parse_ok("  \n\t\r\n").is_empty());
        assert!(parse_ok("# just a comment\n   # another one").is_empty());
    }

    #[test]
    fn unnamed_obstacles_and_grid_names() {
        let items = world_items(
            "world { rect (0,0) (1,1) disk (2, 2) 0.5 polygon [(0,0),(1,0),(0,1)] segment (0,0) (1,1) }",
        );
        for item in &items {
            let WorldItem::Obstacle(o) = item else {
                panic!()
            };
            assert!(o.name.is_none(), "{o:?}");
        }
        let grid = |text: &str| match &world_items(text)[0] {
            WorldItem::Obstacle(ObstacleDecl {
                name,
                shape: ObstacleShape::Grid(g),
                ..
            }) => (name.as_ref().map(|n| n.value.clone()), g.clone()),
            other => panic!("{other:?}"),
        };
        let (name, g) = grid("world { grid cell 1 origin (0, 0) { \"..\" } }");
        assert_eq!(name, None);
        assert_eq!(g.cell.as_ref().map(number), Some(1.0));
        let (name, g) = grid("world { grid cell cell 2 }");
        assert_eq!(name.as_deref(), Some("cell"));
        assert_eq!(g.cell.as_ref().map(number), Some(2.0));
        let (name, g) = grid("world { grid \"a.map\" }");
        assert_eq!(name, None);
        assert_eq!(g.file.unwrap().value, "a.map");
        let (name, g) = grid("world { grid origin (1, 2) cell 0.5 {} }");
        assert_eq!(name, None);
        assert_eq!(g.rows, Some(vec![]));
    }

    #[test]
    fn a_repeated_grid_option_is_an_error_at_the_repetition() {
        let text = "world {\n  grid G cell 1 origin (0,0)\n  cell 2\n}";
        let diags = errors(text);
        assert_eq!(diags.len(), 1);
        assert_eq!(diags[0].code, "scen::syntax::duplicate_option");
        assert_eq!(snippet(text, diags[0].span.unwrap()), "cell 2");
        assert_eq!(snippet(text, diags[0].related[0].0), "cell 1");
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
        assert!(matches!(r.shape, RobotShape::Point(_)));
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
    fn a_grid_name_that_is_a_keyword_is_an_error_in_the_world() {
        // `grid1` is not `grid 1`: it is an unknown world item.
        let diags = errors("world { rect rect1 (0,0) (1,1) grid1 }");
        assert_eq!(diags.len(), 1);
        assert!(
            diags[0].message.contains("found `grid1`"),
            "{}",
            diags[0].message
        );
    }

    #[test]
    fn plan_bodies_are_flat_token_lists() {
        let body = plan_body(
            "plan p astar r {\n  start (0, -1.5, 90deg) goal (1e-3, .5)\n  weights [1, 2, 3,] \
             names [center, corner] empty []\n  file \"a \\\"b\\\" \\\\c\"\n  drive unicycle { dt 20ms gain { x 1 } }\n  coverage 100%\n}",
        );
        let ParamToken::Value(start) = &body[1] else {
            panic!()
        };
        let ValueKind::Tuple(xs) = &start.kind else {
            panic!()
        };
        assert_eq!(number(&xs[0]), 0.0);
        assert_eq!(number(&xs[1]), -1.5);
        assert_eq!(xs[2].kind, ValueKind::Angle(std::f64::consts::FRAC_PI_2));
        let ParamToken::Value(goal) = &body[3] else {
            panic!()
        };
        let ValueKind::Tuple(xs) = &goal.kind else {
            panic!()
        };
        assert_eq!((number(&xs[0]), number(&xs[1])), (1e-3, 0.5));
        let ParamToken::Value(Value {
            kind: ValueKind::List(ws),
            span,
        }) = &body[5]
        else {
            panic!()
        };
        assert_eq!(ws.len(), 3);
        assert_eq!(span.len(), "[1, 2, 3,]".len());
        let ParamToken::Value(Value {
            kind: ValueKind::List(names),
            ..
        }) = &body[7]
        else {
            panic!()
        };
        assert_eq!(names[1].kind, ValueKind::Word("corner".into()));
        let ParamToken::Value(Value {
            kind: ValueKind::List(empty),
            ..
        }) = &body[9]
        else {
            panic!()
        };
        assert!(empty.is_empty());
        let ParamToken::Value(Value {
            kind: ValueKind::Str(s),
            ..
        }) = &body[11]
        else {
            panic!()
        };
        assert_eq!(s, r#"a "b" \c"#);
        let ParamToken::Block { tokens, .. } = &body[14] else {
            panic!()
        };
        assert_eq!(tokens.len(), 4);
        assert!(
            matches!(&tokens[1], ParamToken::Value(Value { kind: ValueKind::Duration(d), .. }) if (*d - 0.02).abs() < 1e-15)
        );
        assert!(matches!(&tokens[3], ParamToken::Block { tokens, .. } if tokens.len() == 2));
        let ParamToken::Value(Value {
            kind: ValueKind::Percent(p),
            ..
        }) = &body[16]
        else {
            panic!()
        };
        assert_eq!(*p, 1.0);
    }

    #[test]
    fn units_are_converted() {
        let value = |text: &str| match &plan_body(&format!("plan p k r {{ {text} }}"))[0] {
            ParamToken::Value(v) => v.kind.clone(),
            other => panic!("{other:?}"),
        };
        assert_eq!(value("180deg"), ValueKind::Angle(std::f64::consts::PI));
        assert_eq!(
            value("-90deg"),
            ValueKind::Angle(-std::f64::consts::FRAC_PI_2)
        );
        assert_eq!(value("1.5rad"), ValueKind::Angle(1.5));
        assert_eq!(value("50%"), ValueKind::Percent(0.5));
        assert_eq!(value("500ms"), ValueKind::Duration(0.5));
        assert_eq!(value("2s"), ValueKind::Duration(2.0));
        assert_eq!(value("12"), ValueKind::Number(12.0));
        assert_eq!(value("-3.5"), ValueKind::Number(-3.5));
        assert_eq!(value("1e-3"), ValueKind::Number(1e-3));
        assert_eq!(value("2E+2"), ValueKind::Number(200.0));
        assert_eq!(value(".5"), ValueKind::Number(0.5));
        assert_eq!(value("\"\""), ValueKind::Str(String::new()));
        assert_eq!(
            sexp(&expr("a.turn < 90deg")),
            format!("(< a.turn {})", std::f64::consts::FRAC_PI_2)
        );
        assert_eq!(sexp(&expr("a.coverage >= 50%")), "(>= a.coverage 0.5%)");
    }

    #[test]
    fn precedence_and_associativity() {
        let cases = [
            ("a.x - b.y - c.z", "(- (- a.x b.y) c.z)"),
            ("a.x / b.y / 2", "(/ (/ a.x b.y) 2)"),
            ("1 + 2 * 3", "(+ 1 (* 2 3))"),
            ("(1 + 2) * 3", "(* (+ 1 2) 3)"),
            ("-a.x * 2", "(* (neg a.x) 2)"),
            ("- -a.x", "(neg (neg a.x))"),
            ("a.x - -3", "(- a.x (neg 3))"),
            ("a.x -3", "(- a.x 3)"),
            ("a.f or b.f and c.f", "(or a.f (and b.f c.f))"),
            ("a.f and b.f or c.f", "(or (and a.f b.f) c.f)"),
            ("a.f or b.f or c.f", "(or (or a.f b.f) c.f)"),
            ("not a.f and b.f", "(and (not a.f) b.f)"),
            ("not a.x < 3", "(not (< a.x 3))"),
            ("not not a.f", "(not (not a.f))"),
            ("a.x + 1 < b.y * 2", "(< (+ a.x 1) (* b.y 2))"),
            ("a.x ~ b.y + 1 +- 0.5 * 2", "(~ a.x (+ b.y 1) (* 0.5 2))"),
            ("a.x~1+-0.1", "(~ a.x 1 0.1)"),
            ("a.x ~ 1 ± 0.1", "(~ a.x 1 0.1)"),
            ("a.x != 1 and a.y == 2", "(and (!= a.x 1) (== a.y 2))"),
            ("a.x > 1 or a.x >= 2", "(or (> a.x 1) (>= a.x 2))"),
            ("(a.f)", "a.f"),
            (
                "((a.x < 1)) and (b.f or c.f)",
                "(and (< a.x 1) (or b.f c.f))",
            ),
        ];
        for (text, tree) in cases {
            assert_eq!(sexp(&expr(text)), tree, "{text}");
        }
    }

    #[test]
    fn expression_spans_cover_their_text() {
        let text = "expect (a.x + 1) * b.y <= -c.z and not d.f";
        let Some(Stmt::Expect(e)) = parse_ok(text).pop() else {
            panic!()
        };
        assert_eq!(snippet(text, e.span), "(a.x + 1) * b.y <= -c.z and not d.f");
        let ExprKind::And(cmp, not) = &e.kind else {
            panic!()
        };
        assert_eq!(snippet(text, cmp.span), "(a.x + 1) * b.y <= -c.z");
        assert_eq!(snippet(text, not.span), "not d.f");
        let ExprKind::Compare { lhs, rhs, .. } = &cmp.kind else {
            panic!()
        };
        assert_eq!(snippet(text, lhs.span), "(a.x + 1) * b.y");
        assert_eq!(snippet(text, rhs.span), "-c.z");
        let ExprKind::Arith { lhs, .. } = &lhs.kind else {
            panic!()
        };
        assert_eq!(snippet(text, lhs.span), "(a.x + 1)");
        let ExprKind::Metric { plan, metric } = &rhs.kind else {
            let ExprKind::Neg(inner) = &rhs.kind else {
                panic!()
            };
            let ExprKind::Metric { plan, metric } = &inner.kind else {
                panic!()
            };
            assert_eq!(
                (snippet(text, plan.span), snippet(text, metric.span)),
                ("c", "z")
            );
            return;
        };
        panic!("{plan:?} {metric:?}");
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
    fn every_broken_statement_is_reported_with_its_line() {
        let text = "world {\n  bounds (0,0) (10,10)\n}\nrobot r\nplan p astar r { start (0,0 }\nexpect p.found\nexpect p.cost <\n";
        let (file, diags) = parse(text, 0);
        let lines: Vec<_> = diags
            .iter()
            .map(|d| line_of(text, d.span.unwrap()))
            .collect();
        assert_eq!(lines, [4, 5, 7], "{diags:#?}");
        assert!(diags.iter().all(|d| d.code == "scen::syntax::expected"));
        assert_eq!(
            diags[0].message,
            "expected `rect`, `polygon`, `disk` or `point`, found `plan`"
        );
        assert_eq!(snippet(text, diags[0].span.unwrap()), "r");
        assert_eq!(diags[1].message, "expected `,` or `)`, found `}`");
        assert_eq!(snippet(text, diags[1].span.unwrap()), "}");
        assert_eq!(
            diags[2].message,
            "expected an expression, found the end of the file"
        );
        assert_eq!(snippet(text, diags[2].span.unwrap()), "<");
        // The statements that parsed are still returned.
        assert_eq!(file.statements.len(), 2);
    }

    #[test]
    fn leading_and_trailing_junk_is_not_a_statement() {
        let text = "hello world {}\nrobot r point extra\nWorld {}";
        let diags = errors(text);
        assert_eq!(diags.len(), 2, "{diags:#?}");
        assert_eq!(diags[0].message, EXPECTED_STATEMENT);
        assert_eq!(snippet(text, diags[0].span.unwrap()), "hello");
        assert_eq!(diags[1].message, EXPECTED_STATEMENT);
        assert_eq!(snippet(text, diags[1].span.unwrap()), "extra");
        let diags = errors("robot r point\nWorld {}");
        assert_eq!(
            diags[0].help.as_deref(),
            Some("keywords are lowercase: `world`")
        );
        let diags = errors("robot r point }");
        assert_eq!(
            diags[0].help.as_deref(),
            Some("this `}` has no matching `{`")
        );
    }

    #[test]
    fn grid_rows_written_as_a_keyword_get_the_block_syntax() {
        let text =
            "world {\n  bounds (0,0) (2,2)\n  grid G cell 1 origin (0, 0) rows [\"..\"]\n}\n";
        let (_, diags) = parse(text, 0);
        assert_eq!(diags.len(), 1, "{diags:#?}");
        assert_eq!(snippet(text, diags[0].span.unwrap()), "rows");
        let help = diags[0].help.as_deref().unwrap_or_default();
        assert!(help.starts_with("a grid's rows go in a block"), "{help}");
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
    fn long_expressions_are_refused_not_overflowed() {
        let long = format!("expect {}", vec!["a.x"; 100_000].join(" + "));
        let diags = errors(&long);
        assert_eq!(diags.len(), 1);
        assert_eq!(diags[0].code, "scen::syntax::too_deep");
        let nots = format!("expect {} a.f", "not ".repeat(100_000));
        assert_eq!(errors(&nots)[0].code, "scen::syntax::too_deep");
        let negs = format!("expect {}1 < 2", "-".repeat(100_000));
        assert_eq!(errors(&negs)[0].code, "scen::syntax::too_deep");
        // A long but reasonable conjunction is fine.
        let fine = format!("expect {}", vec!["a.f"; 200].join(" and "));
        parse_ok(&fine);
    }

    #[test]
    fn literal_errors() {
        let text = "robot r disk 1e999\nplan p k r { x 90degx y 1e }";
        let diags = errors(text);
        let codes: Vec<_> = diags.iter().map(|d| d.code).collect();
        assert_eq!(
            codes,
            [
                "scen::syntax::bad_number",
                "scen::syntax::bad_unit",
                "scen::syntax::bad_unit"
            ]
        );
        assert_eq!(snippet(text, diags[0].span.unwrap()), "1e999");
        assert_eq!(diags[0].message, "number out of range");
        assert_eq!(snippet(text, diags[1].span.unwrap()), "degx");
        assert_eq!(diags[1].message, "unknown unit `degx`");
        assert_eq!(
            diags[2].help.as_deref(),
            Some("an exponent needs digits, as in `1e-3`")
        );

        let text = "include \"maps\\arena.map\"";
        let diags = errors(text);
        assert_eq!(diags[0].code, "scen::syntax::bad_escape");
        assert_eq!(snippet(text, diags[0].span.unwrap()), "\\a");

        let diags = errors("expect a.time_ms < 2s");
        assert_eq!(diags[0].code, "scen::syntax::unit_not_allowed");
        assert!(diags[0].help.as_deref().unwrap().contains("`2000`"));
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
    fn a_unit_apart_from_its_number_gets_a_help() {
        let text = "plan p k r { start (0, 0, 90 deg) }";
        let diags = errors(text);
        assert_eq!(
            diags[0].help.as_deref(),
            Some("write the unit right after the number: `90deg`")
        );
        assert_eq!(snippet(text, diags[0].span.unwrap()), "deg");
        let text = "plan p k r { limit time 2 s }";
        let diags = errors(text);
        assert_eq!(diags[0].code, "scen::syntax::detached_unit");
        assert_eq!(snippet(text, diags[0].span.unwrap()), "2 s");
        assert_eq!(
            diags[0].help.as_deref(),
            Some("write the unit right after the number: `2s`")
        );
        let diags = errors("expect c.coverage == 100 %");
        assert_eq!(
            diags[0].help.as_deref(),
            Some("write the unit right after the number: `100%`")
        );
    }

    #[test]
    fn expression_errors_have_helps() {
        let d = &errors("expect a.x < b.y < 3")[0];
        assert_eq!(d.message, "comparisons cannot be chained");
        assert!(d.help.as_deref().unwrap().contains("and"));
        let d = &errors("expect a.x = 3")[0];
        assert_eq!(d.help.as_deref(), Some("compare with `==`"));
        let d = &errors("expect a.x ~ 3")[0];
        assert_eq!(
            d.help.as_deref(),
            Some("approximate equality needs a tolerance: `A ~ B +- TOL`")
        );
        let d = &errors("expect offline")[0];
        assert!(d.help.as_deref().unwrap().contains("PLAN.METRIC"));
        let d = &errors("expect a.x and")[0];
        assert_eq!(
            d.message,
            "expected an expression, found the end of the file"
        );
        let d = &errors("plan p k r { start (1, 2, 3, 4) }")[0];
        assert_eq!(
            d.help.as_deref(),
            Some("a point is `(x, y)` and a pose `(x, y, θ)`")
        );
    }

    #[test]
    fn binary_garbage_gives_a_normal_syntax_error() {
        let text = "\u{0}\u{1}\u{7f}\u{fffd}ÿ\u{1b}[0m";
        let diags = errors(text);
        assert_eq!(diags.len(), 1);
        assert_eq!(diags[0].code, "scen::syntax::expected");
        assert_eq!(diags[0].label, "unexpected `\\u{0}`");
        let text = "world { \u{0} }";
        assert_eq!(errors(text)[0].label, "unexpected `\\u{0}`");
    }

    #[test]
    fn no_input_derived_from_a_valid_file_panics() {
        // Every prefix, and every byte replaced by a troublesome character.
        for end in (0..=APARTMENT.len()).filter(|&k| APARTMENT.is_char_boundary(k)) {
            let _ = parse(&APARTMENT[..end], 0);
        }
        for k in (0..APARTMENT.len()).filter(|&k| APARTMENT.is_char_boundary(k)) {
            let next = APARTMENT[k..].chars().next().unwrap().len_utf8();
            for c in [
                "", "(", "}", "\"", "#", "-", ".", "é", "\u{0}", "e", "world ", "\n",
            ] {
                let text = format!("{}{c}{}", &APARTMENT[..k], &APARTMENT[k + next..]);
                let (_, diags) = parse(&text, 0);
                for d in diags {
                    let span = d.span.expect("every syntax error has a span");
                    assert!(span.end <= text.len() && text.is_char_boundary(span.start));
                    assert!(!span.is_empty() || text.is_empty(), "{d:?} in {text:?}");
                }
            }
        }
    }

    /// Timings are printed, not asserted:
    /// `cargo test --release --lib ten_megabyte -- --nocapture`.
    #[test]
    fn a_ten_megabyte_file_parses() {
        let block = "# a comment line that is fairly long to fill the file quickly ........\n\
                     plan p astar r { start (0, 0) goal (1, 1, 90deg) limit time 2s }\n\
                     expect p.cost <= 90 and p.found\n";
        let text = block.repeat(10_000_000 / block.len() + 1);
        assert!(text.len() >= 10_000_000);
        let started = std::time::Instant::now();
        let (file, diags) = parse(&text, 0);
        eprintln!(
            "parsed {} bytes of statements in {:?}",
            text.len(),
            started.elapsed()
        );
        assert!(diags.is_empty());
        assert_eq!(file.statements.len(), 2 * (10_000_000 / block.len() + 1));

        let comments = "# nothing but comments here\n".repeat(10_000_000 / 28 + 1);
        let started = std::time::Instant::now();
        assert!(parse_ok(&comments).is_empty());
        eprintln!(
            "parsed {} bytes of comments in {:?}",
            comments.len(),
            started.elapsed()
        );

        // One statement of 10 MB: parsed in pieces.
        let world = format!(
            "world {{\n{}}}",
            "  rect (0, 0) (1.5, 2)\n".repeat(10_000_000 / 23)
        );
        let started = std::time::Instant::now();
        assert_eq!(world_items(&world).len(), 10_000_000 / 23);
        eprintln!(
            "parsed a {}-byte world in {:?}",
            world.len(),
            started.elapsed()
        );
    }

    #[test]
    fn a_missing_value_is_expected_as_a_value() {
        let d = &errors("robot r disk")[0];
        assert_eq!(d.message, "expected a value, found the end of the file");
        let d = &errors("world { rect A (0, 0) }")[0];
        assert_eq!(d.message, "expected a value, found `}`");
        let d = &errors("plan p k r { start (0 0) }")[0];
        assert_eq!(d.message, "expected `,`, found `0`");
        let d = &errors("robot r polygon [(0, 0) (1, 0)]")[0];
        assert_eq!(d.message, "expected `,` or `]`, found `(`");
    }

    #[test]
    fn malformed_numbers_are_one_bad_token() {
        for (text, token) in [
            ("1.2.3", "1.2.3"),
            ("5-3", "5-3"),
            ("1e-", "1e-"),
            ("2.", "2."),
        ] {
            let source = format!("plan p k r {{ x {text} }}");
            let diags = errors(&source);
            assert_eq!(diags.len(), 1, "{text}: {diags:#?}");
            assert_eq!(diags[0].code, "scen::syntax::bad_number", "{text}");
            assert_eq!(snippet(&source, diags[0].span.unwrap()), token);
        }
        // In an expression `-` is an operator, and `e-3` an exponent.
        assert_eq!(sexp(&expr("a.x < 5-3")), "(< a.x (- 5 3))");
        assert_eq!(sexp(&expr("a.x < 2e-3-1")), "(< a.x (- 0.002 1))");
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

    /// The AST and diagnostics of `text`, parsing every chunk whole.
    fn parse_without_cutting(text: &str) -> (ast::File, Vec<Diag>) {
        let mut parser = FileParser::new(text, 0);
        for mut chunk in split_statements(text, 0) {
            if let Some(details) = &mut chunk.details {
                details.splits.clear();
            }
            parser.unit(std::slice::from_ref(&chunk));
        }
        sort_diags(&mut parser.diags);
        (
            ast::File {
                statements: parser.statements,
            },
            parser.diags,
        )
    }

    fn assert_same_as_uncut(text: &str) -> (ast::File, Vec<Diag>) {
        let chunks = split_statements(text, 0);
        assert!(
            chunks.iter().any(|c| !c.splits().is_empty()),
            "the test needs a cut"
        );
        let (file, diags) = parse(text, 0);
        let (whole, whole_diags) = parse_without_cutting(text);
        assert_eq!(
            format!("{:?}", file.statements),
            format!("{:?}", whole.statements)
        );
        assert_eq!(format!("{diags:?}"), format!("{whole_diags:?}"));
        (file, diags)
    }

    #[test]
    fn a_large_world_is_cut_into_pieces_with_the_same_result() {
        let mut text = String::from("scenario \"big\"\nworld {\n  bounds (0, 0) (100, 100)\n");
        for k in 0..6000 {
            text.push_str(&format!(
                "  rect R{k} ({k}, 0) ({k}.5, 1)\n  disk (1, 2) 0.5 # a comment\n  \
                 grid G{k} cell 1 origin (0, 0) {{ \"..#\" }}\n  grid\n    H{k}\n  \
                 polygon [(0, 0), (1, 0), (0, 1),]\n  segment rect (0, 0) (1, 1)\n"
            ));
        }
        text.push_str("}\nexpect p.found\n");
        let (file, diags) = assert_same_as_uncut(&text);
        assert!(diags.is_empty());
        let Stmt::World(world) = &file.statements[1] else {
            panic!()
        };
        assert_eq!(world.items.len(), 1 + 6 * 6000);
        assert_eq!(snippet(&text, world.keyword), "world");
        assert!(
            snippet(&text, world.span).starts_with("world {")
                && snippet(&text, world.span).ends_with('}')
        );
        let WorldItem::Obstacle(last) = world.items.last().unwrap() else {
            panic!()
        };
        assert_eq!(snippet(&text, last.span), "segment rect (0, 0) (1, 1)");

        // An error in a piece: the whole block is parsed for the message.
        let broken = text.replacen("R5000 (5000, 0)", "R5000 (5000 0)", 1);
        let (_, diags) = assert_same_as_uncut(&broken);
        assert_eq!(diags.len(), 1);
        assert_eq!(snippet(&broken, diags[0].span.unwrap()), "0");
        assert_eq!(line_of(&broken, diags[0].span.unwrap()), 3 + 5000 * 7 + 1);
    }

    #[test]
    fn a_large_plan_body_is_cut_into_pieces_with_the_same_result() {
        let mut text = String::from("plan p astar r {\n");
        for k in 0..8000 {
            text.push_str(&format!(
                "  start ({k}, 0, 90deg) goal [1, 2] {}\n  drive unicycle {{ dt 0.02 }} name \"n\" 90 deg\n",
                if k % 2 == 0 { "x" } else { "1e-3" }
            ));
        }
        text.push('}');
        let (file, diags) = assert_same_as_uncut(&text);
        assert_eq!(diags.len(), 8000);
        assert!(
            diags
                .iter()
                .all(|d| d.code == "scen::syntax::detached_unit")
        );
        let Stmt::Plan(plan) = &file.statements[0] else {
            panic!()
        };
        assert_eq!(plan.body.len(), 8000 * 12);
        assert_eq!(plan.span, Span::new(0, 0, text.len()));
    }

    #[test]
    fn statements_and_errors_keep_their_order_in_a_large_file() {
        let mut text = String::new();
        for k in 0..20_000 {
            if k % 5000 == 4999 {
                text.push_str(&format!("robot r{k}\n"));
            } else {
                text.push_str(&format!("expect p{k}.found\n"));
            }
        }
        let (file, diags) = parse(&text, 0);
        assert_eq!(file.statements.len(), 20_000 - 4);
        let Stmt::Expect(Expr {
            kind: ExprKind::Metric { plan, .. },
            ..
        }) = &file.statements[5000]
        else {
            panic!()
        };
        assert_eq!(plan.value, "p5001");
        let lines: Vec<_> = diags
            .iter()
            .map(|d| line_of(&text, d.span.unwrap()))
            .collect();
        assert_eq!(lines, [5000, 10_000, 15_000, 20_000]);
    }

    #[test]
    fn syntax_errors_suggest_a_fix() {
        let help = |text: &str| errors(text)[0].help.clone().unwrap_or_default();
        assert_eq!(help("robots r point"), "did you mean `robot`?");
        assert_eq!(
            help("robot r point\nrobots q point"),
            "did you mean `robot`?"
        );
        assert_eq!(
            help("world { rectangle (0, 0) (1, 1) }"),
            "did you mean `rect`?"
        );
        assert_eq!(help("robot r dsk 1"), "did you mean `disk`?");
        assert_eq!(help("plan p k r { x 90degrees }"), "did you mean `90deg`?");
        assert!(
            help("world { bounds (0, 0), (1, 1) }").starts_with("values are separated by blanks")
        );
        assert_eq!(
            help("expect p.cost <="),
            "complete the expression after `<=`, e.g. `offline.cost <= 90`"
        );
        assert!(help("expect").starts_with("write a condition"));
        assert!(help("robot r disk 0.5 0.5").starts_with("the `robot` statement is complete"));
        assert!(help("%%%").starts_with("a file is a list of statements"));

        let text = "plan p k r {\n  start (1.5, 1.5\n  goal (8.5, 1.5)\n}";
        let d = &errors(text)[0];
        assert_eq!(d.help.as_deref(), Some("add the missing `)`"));
        assert_eq!(snippet(text, d.related[0].0), "(");
        assert_eq!(d.related[0].1, "this `(` is not closed yet");
    }
}
