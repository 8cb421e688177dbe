//! Syntax errors: a pest error in a chunk, or leading text that is not a
//! statement → a located diagnostic with a readable message ("expected `,`
//! or `)`, found `}`") and, where the likely fix is known, a help line.

use pest::error::{ErrorVariant, InputLocation};

use super::builder::UNIT_WORDS;
use super::parser::Rule;
use super::scanner::{Chunk, STATEMENT_KEYWORDS, is_blank, is_ident_byte, scan_string};
use crate::diagnostics::{Diag, FileId, Span, edit_distance};

const EXPECTED_STATEMENT: &str =
    "expected a statement: `world`, `robot`, `plan`, `expect`, `bench`, `include` or `scenario`";

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
pub(super) fn show(token: &str) -> String {
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

/// Words that users of other tools (test frameworks, other planners'
/// configuration files, drawing programs) write for a keyword, with it;
/// offered only where that keyword is expected.
const KEYWORD_SYNONYMS: [(&str, &str); 18] = [
    ("check", "expect"),
    ("assert", "expect"),
    ("verify", "expect"),
    ("test", "expect"),
    ("obstacle", "world"),
    ("obstacles", "world"),
    ("map", "world"),
    ("environment", "world"),
    ("planner", "plan"),
    ("problem", "plan"),
    ("import", "include"),
    ("title", "scenario"),
    ("circle", "disk"),
    ("sphere", "disk"),
    ("box", "rect"),
    ("square", "rect"),
    ("line", "segment"),
    ("poly", "polygon"),
];

/// A help line for a word that looks like one of `keywords` misspelt, or
/// that another tool uses for one of them.
fn keyword_help(word: &str, keywords: &[&str]) -> Option<String> {
    let lower = word.to_ascii_lowercase();
    if lower != word && keywords.contains(&lower.as_str()) {
        return Some(format!("keywords are lowercase: `{lower}`"));
    }
    if let Some(keyword) = closest_keyword(word, keywords) {
        return Some(format!("did you mean `{keyword}`?"));
    }
    KEYWORD_SYNONYMS
        .iter()
        .find(|(synonym, keyword)| *synonym == lower && keywords.contains(keyword))
        .map(|(_, keyword)| match *keyword {
            "expect" => "a check is written `expect CONDITION`, e.g. `expect p.found`".to_string(),
            "world" => {
                "obstacles go in `world { ... }`, e.g. `world { rect A (0, 0) (1, 1) }`".to_string()
            }
            keyword => format!("did you mean `{keyword}`?"),
        })
}

/// Leading text that is not a statement.
pub(super) fn not_a_statement(text: &str, file: FileId, start: usize) -> Diag {
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
        Rule::number | Rule::plain_number | Rule::expr_number => "a number",
        // Silent and atomic helper rules never reach an error message.
        Rule::WHITESPACE
        | Rule::COMMENT_TEXT
        | Rule::STRING_TEXT
        | Rule::scenario_chunk
        | Rule::include_chunk
        | Rule::world_chunk
        | Rule::robot_chunk
        | Rule::team_chunk
        | Rule::plan_chunk
        | Rule::expect_chunk
        | Rule::bench_chunk
        | Rule::param_chunk
        | Rule::require_chunk
        | Rule::statement_chunks
        // Expressions in number positions are extensions of a value: a
        // missing value is still "expected a value".
        | Rule::calc
        | Rule::body_calc
        | Rule::calc_neg
        | Rule::calc_term
        | Rule::calc_function
        | Rule::calc_name
        | Rule::calc_unit
        | Rule::name_ref
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
        Rule::kw_bench | Rule::bench => "`bench`",
        Rule::kw_param | Rule::param => "`param`",
        Rule::kw_require | Rule::require => "`require`",
        Rule::kw_scatter | Rule::scatter => "`scatter`",
        Rule::kw_in => "`in`",
        Rule::kw_gap | Rule::scatter_gap => "`gap`",
        Rule::kw_choice | Rule::param_choice => "`choice`",
        Rule::scatter_disk => "`disk`",
        Rule::scatter_rect => "`rect`",
        Rule::calc_paren => "`(`",
        Rule::calc_call => "a call such as `min(a, b)`",
        // After a number, an operator is always possible: not worth saying.
        Rule::calc_op => return None,
        Rule::kw_bounds | Rule::bounds => "`bounds`",
        Rule::kw_rect | Rule::rect_obstacle | Rule::rect_shape => "`rect`",
        Rule::kw_polygon | Rule::polygon_obstacle | Rule::polygon_shape => "`polygon`",
        Rule::kw_segment | Rule::segment_obstacle => "`segment`",
        Rule::kw_disk | Rule::disk_obstacle | Rule::disk_shape => "`disk`",
        Rule::kw_grid | Rule::grid_obstacle => "`grid`",
        Rule::kw_cell | Rule::grid_cell => "`cell`",
        Rule::kw_origin | Rule::grid_origin => "`origin`",
        Rule::kw_point | Rule::point_shape => "`point`",
        Rule::other_shape | Rule::robot_kind => "a robot kind",
        Rule::kw_steer | Rule::steer_clause => "`steer`",
        Rule::kw_speed | Rule::speed_clause => "`speed`",
        Rule::kw_moving | Rule::moving => "`moving`",
        Rule::kw_team | Rule::team => "`team`",
        Rule::kw_from | Rule::team_from => "`from`",
        Rule::kw_agents => "`agents`",
        Rule::team_agents | Rule::team_open => "`{` or `from`",
        Rule::team_close => "`}`",
        Rule::team_agent => "an agent `NAME (x, y) -> (x, y)`",
        Rule::arrow => "`->`",
        Rule::moving_open => "`{`",
        Rule::moving_close => "`}`",
        Rule::kw_at | Rule::moving_at => "`at`",
        Rule::kw_then | Rule::moving_then => "`then`",
        Rule::kw_stay => "`stay`",
        Rule::kw_vanish => "`vanish`",
        Rule::steer_model => "a steering model (`dubins` or `reeds_shepp`)",
        Rule::kw_true => "`true`",
        Rule::kw_false => "`false`",
        Rule::tuple => "a point `(x, y)`",
        Rule::list => "a list `[...]`",
        Rule::expr | Rule::operand | Rule::primary => "an expression",
        Rule::metric | Rule::name_part => "a metric `PLAN.METRIC`",
        Rule::selector => "a selection `[KEY = VALUE, ...]`",
        Rule::selection => "`KEY = VALUE`",
        Rule::equals => "`=`",
        Rule::call | Rule::function => "an aggregate such as `median(...)`",
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
pub(super) fn syntax_error(
    text: &str,
    file: FileId,
    chunk: &Chunk,
    error: &pest::error::Error<Rule>,
) -> Diag {
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
    // Any word may name a robot kind (the registry decides): the kinds
    // with rules of their own are among them.
    if expected.contains(&"a robot kind") {
        expected.retain(|d| !["`point`", "`disk`", "`rect`", "`polygon`"].contains(d));
    }
    // A robot may end with `steer MODEL RADIUS`; after a robot's shape pest
    // expects it, but a word that is nothing like it is the start of junk
    // or of the next statement, and reads best as such.
    for clause in ["steer", "speed"] {
        let shown = format!("`{clause}`");
        if expected.contains(&shown.as_str()) && closest_keyword(token, &[clause]).is_none() {
            expected.retain(|d| *d != shown);
        }
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
        if has(Rule::steer_model) {
            return Some(
                "name the steering model before the turning radius: `steer dubins RADIUS` (forward only) or `steer reeds_shepp RADIUS` (forward and reverse)"
                    .to_string(),
            );
        }
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
            let kinds: Vec<String> = crate::geometry::robots::ROBOTS
                .iter()
                .map(|m| format!("`{}`", m.example))
                .collect();
            return Some(format!("a robot is one of: {}", kinds.join(", ")));
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
pub(super) fn closest_keyword<'k>(word: &str, keywords: &[&'k str]) -> Option<&'k str> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::parse;
    use crate::syntax::testing::{errors, line_of, snippet};

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
    fn every_broken_statement_is_reported_with_its_line() {
        let text = "world {\n  bounds (0,0) (10,10)\n}\nrobot r\nplan p astar r { start (0,0 }\nexpect p.found\nexpect p.cost <\n";
        let (file, diags) = parse(text, 0);
        let lines: Vec<_> = diags
            .iter()
            .map(|d| line_of(text, d.span.unwrap()))
            .collect();
        assert_eq!(lines, [4, 5, 7], "{diags:#?}");
        assert!(diags.iter().all(|d| d.code == "scen::syntax::expected"));
        assert_eq!(diags[0].message, "expected a robot kind, found `plan`");
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
    fn a_missing_value_is_expected_as_a_value() {
        let d = &errors("world { disk A (0, 0) }")[0];
        assert_eq!(d.message, "expected a value, found `}`");
        let d = &errors("world { rect A (0, 0) }")[0];
        assert_eq!(d.message, "expected a value, found `}`");
        // `(0 0)` could also be a parenthesised expression `(0)`.
        let d = &errors("plan p k r { start (0 0) }")[0];
        assert_eq!(d.message, "expected `,` or `)`, found `0`");
        let d = &errors("robot r polygon [(0, 0) (1, 0)]")[0];
        assert_eq!(d.message, "expected `,` or `]`, found `(`");
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
        // (`robot r dsk 1` parses: any word may be a robot kind, and the
        // analyzer suggests `disk`.)
        // Other tools' words for a statement, first or after a statement.
        let expect_help = "a check is written `expect CONDITION`, e.g. `expect p.found`";
        assert_eq!(help("check p.found"), expect_help);
        assert_eq!(help("robot r point\nassert p.found"), expect_help);
        assert!(help("obstacles { rect A (0, 0) (1, 1) }").starts_with("obstacles go in `world"));
        assert_eq!(
            help("robot r point\nimport \"x.scen\""),
            "did you mean `include`?"
        );
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
