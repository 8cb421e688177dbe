//! `scen import roadmap FILE`: a SEEDS §D `input.txt` as a scenario.
//!
//! The input, one record per non-blank line, numbers separated by commas
//! and/or whitespace:
//! ```text
//! N
//! Sx, Sy, Ex, Ey        (N lines: one segment obstacle each)
//! X, Y                  (the start)
//! X, Y                  (the goal)
//! m                     (optional: a convex robot of m vertices)
//! X, Y                  (m lines; the first is the reference vertex)
//! ```
//! The scenario has a `segment` per line, a `point` robot (or a `polygon`
//! robot with the vertices relative to the first one, which becomes the
//! frame origin: the report's `b + (r1 − rj)` is `B ⊕ (−A)` in that frame),
//! bounds around everything (the report had none), and one `roadmap` plan
//! with `found` and `collision_free` checks.

use std::fmt::Write as _;
use std::path::Path;

use crate::diagnostics::{Diag, FileId, SourceMap, Span};
use crate::geometry::Point;
use crate::geometry::polygon::{is_convex, normalize_simple_polygon};

/// The largest input accepted (the scenario written must stay loadable).
pub const MAX_INPUT_BYTES: u64 = 2 << 20;

/// One non-blank line: its numbers with their spans, and the line's span.
struct Record {
    span: Span,
    fields: Vec<(String, Span)>,
}

/// Reads and converts `path`; on failure, the diagnostics and their sources.
pub fn import_roadmap_file(path: &Path) -> Result<String, (Vec<Diag>, SourceMap)> {
    let mut sources = SourceMap::default();
    let fail = |d: Diag, sources: SourceMap| Err((vec![d], sources));
    let bytes = match crate::files::read_regular_file(path, MAX_INPUT_BYTES) {
        Ok(b) => b,
        Err(e) => {
            let id = sources.add(path, "");
            let (code, label) = match e {
                crate::files::ReadError::TooLarge(_) => {
                    ("scen::import::too_large", "file too large")
                }
                _ => ("scen::import::unreadable", "unreadable"),
            };
            return fail(
                Diag::error(code, format!("cannot read `{}`: {e}", path.display()))
                    .at(Span::new(id, 0, 0), label),
                sources,
            );
        }
    };
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let id = sources.add(path, text.clone());
    let title = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    match convert(&text, id, &title) {
        Ok(s) => Ok(s),
        Err(d) => fail(*d, sources),
    }
}

/// Splits the text into records (non-blank lines) of fields.
fn records(text: &str, file: FileId) -> Vec<Record> {
    let mut out = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let body = line.trim_end_matches(['\n', '\r']);
        let mut fields = Vec::new();
        let mut i = 0;
        let b = body.as_bytes();
        while i < b.len() {
            if b[i] == b',' || b[i].is_ascii_whitespace() {
                i += 1;
                continue;
            }
            let s = i;
            while i < b.len() && b[i] != b',' && !b[i].is_ascii_whitespace() {
                i += 1;
            }
            fields.push((
                body[s..i].to_string(),
                Span::new(file, start + s, start + i),
            ));
        }
        if !fields.is_empty() {
            let end = start + body.trim_end().len();
            let lead = body.len() - body.trim_start().len();
            out.push(Record {
                span: Span::new(file, start + lead, end),
                fields,
            });
        }
    }
    out
}

/// A cursor over the records, producing diagnostics that name the line.
struct Reader<'a> {
    records: &'a [Record],
    next: usize,
    /// An empty span at the end of the last line.
    end: Span,
}

impl Reader<'_> {
    fn line(&mut self, what: &str) -> Result<&Record, Box<Diag>> {
        let r = self.records.get(self.next).ok_or_else(|| {
            Box::new(
                Diag::error(
                    "scen::import::missing_line",
                    format!("the file ends before {what}"),
                )
                .at(self.end, format!("{what} expected here"))
                .help(FORMAT_HELP),
            )
        })?;
        self.next += 1;
        Ok(r)
    }

    /// A line of exactly `n` numbers.
    fn numbers(
        &mut self,
        n: usize,
        what: &str,
        shape: &str,
    ) -> Result<(Vec<f64>, Span), Box<Diag>> {
        let r = self.line(what)?;
        if r.fields.len() != n {
            return Err(Box::new(
                Diag::error(
                    "scen::import::wrong_count",
                    format!(
                        "{what}: expected {n} number(s) `{shape}`, found {}",
                        r.fields.len()
                    ),
                )
                .at(r.span, format!("{} field(s) here", r.fields.len()))
                .help(FORMAT_HELP),
            ));
        }
        let mut out = Vec::with_capacity(n);
        for (s, span) in &r.fields {
            match s.parse::<f64>() {
                Ok(x) if x.is_finite() && x.abs() <= 1e12 => out.push(x),
                _ => {
                    return Err(Box::new(
                        Diag::error(
                            "scen::import::bad_number",
                            format!("{what}: `{s}` is not a number"),
                        )
                        .at(*span, "not a finite number (up to 1e12 in size)")
                        .help(FORMAT_HELP),
                    ));
                }
            }
        }
        Ok((out, r.span))
    }

    /// A line with one count in `lo..=hi`.
    fn count(&mut self, what: &str, lo: usize, hi: usize) -> Result<usize, Box<Diag>> {
        let (v, span) = self.numbers(1, what, "N")?;
        let x = v[0];
        if x.fract() != 0.0 || x < lo as f64 || x > hi as f64 {
            return Err(Box::new(
                Diag::error(
                    "scen::import::bad_count",
                    format!("{what} must be a whole number from {lo} to {hi}"),
                )
                .at(span, "not accepted")
                .help(FORMAT_HELP),
            ));
        }
        Ok(x as usize)
    }
}

const FORMAT_HELP: &str = "the format (SEEDS §D): N; N lines `Sx, Sy, Ex, Ey`; the start `X, Y`; \
the goal `X, Y`; optionally m and m robot vertices `X, Y`";

/// Formats a number as the scenario language reads it.
fn num(x: f64) -> String {
    format!("{}", x + 0.0)
}

fn pt(p: Point) -> String {
    format!("({}, {})", num(p.x), num(p.y))
}

/// Converts the text of an `input.txt` into a scenario.
pub fn convert(text: &str, file: FileId, title: &str) -> Result<String, Box<Diag>> {
    let recs = records(text, file);
    let mut rd = Reader {
        records: &recs,
        next: 0,
        end: recs.last().map_or(Span::new(file, 0, 0), |r| {
            Span::new(file, r.span.end, r.span.end)
        }),
    };
    let n = rd.count("the number of segments N", 0, 100_000)?;
    let mut segments = Vec::with_capacity(n);
    for i in 0..n {
        let what = format!("segment {} of {n}", i + 1);
        let (v, span) = rd.numbers(4, &what, "Sx, Sy, Ex, Ey")?;
        let (a, b) = (Point::new(v[0], v[1]), Point::new(v[2], v[3]));
        if a == b {
            return Err(Box::new(
                Diag::error(
                    "scen::import::degenerate_segment",
                    format!("{what} has zero length"),
                )
                .at(span, "both ends are the same point"),
            ));
        }
        segments.push((a, b));
    }
    let (s, _) = rd.numbers(2, "the start", "X, Y")?;
    let (g, _) = rd.numbers(2, "the goal", "X, Y")?;
    let (start, goal) = (Point::new(s[0], s[1]), Point::new(g[0], g[1]));
    let mut robot = Vec::new();
    if rd.next < recs.len() {
        let m_span = recs[rd.next].span;
        let m = rd.count("the number of robot vertices m", 3, 1000)?;
        for i in 0..m {
            let (v, _) = rd.numbers(2, &format!("robot vertex {} of {m}", i + 1), "X, Y")?;
            robot.push(Point::new(v[0], v[1]));
        }
        let r1 = robot[0];
        let local: Vec<Point> = robot.iter().map(|p| Point::from(p - r1)).collect();
        let convex = normalize_simple_polygon(&local)
            .is_ok_and(|ccw| ccw.len() == local.len() && is_convex(&ccw));
        if !convex {
            return Err(Box::new(
                Diag::error(
                    "scen::import::robot_not_convex",
                    "the robot's vertices are not those of a convex polygon",
                )
                .at(m_span, "this robot")
                .help("give m ≥ 3 distinct vertices of a convex polygon with area, in order"),
            ));
        }
        robot = local;
    }
    if let Some(r) = recs.get(rd.next) {
        return Err(Box::new(
            Diag::error(
                "scen::import::extra_line",
                "unexpected line after the input",
            )
            .at(r.span, "not part of the format")
            .help(FORMAT_HELP),
        ));
    }

    // Bounds: everything, plus the robot's size and a margin.
    let mut all: Vec<Point> = segments.iter().flat_map(|&(a, b)| [a, b]).collect();
    all.extend([start, goal]);
    let (mut lo, mut hi) = (all[0], all[0]);
    for p in &all {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let reach = robot.iter().map(|v| v.coords.norm()).fold(0.0, f64::max);
    let margin = (0.1 * (hi.x - lo.x).max(hi.y - lo.y)).max(1.0) + reach;
    let (lo, hi) = (
        Point::new((lo.x - margin).floor(), (lo.y - margin).floor()),
        Point::new((hi.x + margin).ceil(), (hi.y + margin).ceil()),
    );

    let mut out = String::new();
    let _ = writeln!(
        out,
        "scenario \"Imported from {}\"",
        title.replace(['"', '\\'], "_")
    );
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "# Converted by `scen import roadmap` from a SEEDS §D input file: {n} segment(s),"
    );
    let _ = writeln!(
        out,
        "# a {}.\n# The bounds (which the input has not) enclose everything with a margin.",
        if robot.is_empty() {
            "point robot".to_string()
        } else {
            format!(
                "convex robot of {} vertices relative to its reference vertex",
                robot.len()
            )
        }
    );
    let _ = writeln!(out, "world {{");
    let _ = writeln!(out, "  bounds {} {}", pt(lo), pt(hi));
    for (i, (a, b)) in segments.iter().enumerate() {
        let _ = writeln!(out, "  segment s{} {} {}", i + 1, pt(*a), pt(*b));
    }
    let _ = writeln!(out, "}}");
    let _ = writeln!(out);
    if robot.is_empty() {
        let _ = writeln!(out, "robot r point");
    } else {
        let vs: Vec<String> = robot.iter().map(|p| pt(*p)).collect();
        let _ = writeln!(out, "robot r polygon [{}]", vs.join(", "));
    }
    let _ = writeln!(out);
    let _ = writeln!(out, "plan vg roadmap r {{");
    let _ = writeln!(out, "  start {}", pt(start));
    let _ = writeln!(out, "  goal  {}", pt(goal));
    let _ = writeln!(out, "}}");
    let _ = writeln!(out);
    let _ = writeln!(out, "expect vg.found");
    let _ = writeln!(out, "expect vg.collision_free");
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn conv(text: &str) -> Result<String, (Box<Diag>, usize)> {
        let mut sm = SourceMap::default();
        let id = sm.add(Path::new("input.txt"), text.to_string());
        convert(text, id, "input.txt").map_err(|d| {
            let line = d.span.map_or(0, |s| sm.line_of(s));
            (d, line)
        })
    }

    #[test]
    fn point_robot() {
        let s = conv("2\n0, 0, 4, 0\n4,0 4,4\n\n1, -1\n5, 5\n").unwrap();
        assert!(s.contains("segment s1 (0, 0) (4, 0)"), "{s}");
        assert!(s.contains("segment s2 (4, 0) (4, 4)"), "{s}");
        assert!(s.contains("robot r point"));
        assert!(s.contains("start (1, -1)") && s.contains("goal  (5, 5)"));
        assert!(s.contains("bounds (-1, -2) (6, 6)"), "{s}");
        assert!(s.contains("plan vg roadmap r"));
    }

    #[test]
    fn convex_robot_relative_to_its_first_vertex() {
        let s = conv("1\r\n0 0 1 1\r\n-3 -3\r\n3 3\r\n3\r\n10 10\r\n11 10\r\n10 11\r\n").unwrap();
        assert!(
            s.contains("robot r polygon [(0, 0), (1, 0), (0, 1)]"),
            "{s}"
        );
    }

    #[test]
    fn errors_point_at_the_line() {
        let cases: &[(&str, &str, usize)] = &[
            ("x\n", "scen::import::bad_number", 1),
            (
                "2\n0 0 1 1\n0 0 1\n0 0\n1 1\n",
                "scen::import::wrong_count",
                3,
            ),
            ("1\n0 0 1 1\n0 0\n", "scen::import::missing_line", 3),
            ("1.5\n", "scen::import::bad_count", 1),
            (
                "1\n0 0 0 0\n1 1\n2 2\n",
                "scen::import::degenerate_segment",
                2,
            ),
            (
                "0\n1 1\n2 2\n4\n0 0\n1 0\n0 1\n1 1\n",
                "scen::import::robot_not_convex",
                4,
            ),
            (
                "0\n1 1\n2 2\n3\n0 0\n1 0\n0 1\n9 9\n",
                "scen::import::extra_line",
                8,
            ),
            ("0\n1 1\nnan 2\n", "scen::import::bad_number", 3),
        ];
        for &(text, code, line) in cases {
            match conv(text) {
                Ok(s) => panic!("{text:?} converted: {s}"),
                Err((d, l)) => {
                    assert_eq!(d.code, code, "{text:?}");
                    assert_eq!(l, line, "{text:?}");
                }
            }
        }
    }
}
