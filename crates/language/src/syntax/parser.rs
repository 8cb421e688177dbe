//! Source text → [`ast::File`], in two passes.
//!
//! 1. The [scanner](super::scanner) splits the file into top-level statement
//!    chunks, and reports what pest must never see: unterminated strings and
//!    brackets nested too deep.
//! 2. pest parses each chunk with the rule for its keyword (grammar/scen.pest),
//!    and the [builder](super::builder) turns the pairs into AST nodes with
//!    file-relative spans; `expect` expressions get their precedence
//!    [there](super::expr), by precedence climbing. A chunk that pest rejects
//!    gets a [syntax error](super::syntax_error) with a readable message.
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
use rayon::prelude::*;

use super::ast::{self, Stmt};
use super::builder::{Builder, P};
use super::scanner::{Chunk, Scan, split_statements};
use super::syntax_error::{not_a_statement, syntax_error};
use crate::diagnostics::{Diag, FileId, Span, sort_diags};

#[derive(pest_derive::Parser)]
#[grammar = "grammar/scen.pest"]
struct ScenParser;

/// Parses one file. Returns the statements that parsed and every error found,
/// sorted by position, and the file's comments.
///
/// When the diagnostics contain errors the file is incomplete: statements
/// that failed to parse are missing, and a statement with a bad literal (an
/// out-of-range number, an unknown unit or escape) is kept with a placeholder
/// in its place. An empty file parses to no statements and no error.
pub fn parse(text: &str, file: FileId) -> (ast::File, Vec<Diag>) {
    let Scan { chunks, comments } = split_statements(text, file);
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
            comments,
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
pub(super) const PIECE_BYTES: usize = BATCH_BYTES;

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
                        let mut builder = Builder::new(self.text, self.file, 0, &mut self.diags);
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
        let mut builder = Builder::new(self.text, self.file, base, &mut self.diags);
        if let Some(statement) = builder.statement(pair) {
            self.statements.push(statement);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::ast::{Expr, ExprKind, WorldItem};
    use crate::syntax::testing::{APARTMENT, line_of, parse_ok, snippet, world_items};

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

    /// The AST and diagnostics of `text`, parsing every chunk whole.
    fn parse_without_cutting(text: &str) -> (ast::File, Vec<Diag>) {
        let mut parser = FileParser::new(text, 0);
        for chunk in split_statements(text, 0).chunks {
            let chunk = chunk.uncut();
            parser.unit(std::slice::from_ref(&chunk));
        }
        sort_diags(&mut parser.diags);
        (
            ast::File {
                statements: parser.statements,
                comments: Vec::new(),
            },
            parser.diags,
        )
    }

    fn assert_same_as_uncut(text: &str) -> (ast::File, Vec<Diag>) {
        let chunks = split_statements(text, 0).chunks;
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
}
