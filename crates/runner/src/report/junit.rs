//! `scen test --junit OUT.xml`: a JUnit XML report (the Ant/Jenkins schema
//! that CI systems read), one test suite per file, one test case per check
//! with the file and the line.

use std::fmt::Write as _;

/// One test case: a check (or a file's loading, or an expected error).
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub name: String,
    /// The line of the check in its file.
    pub line: usize,
    /// Why it failed; `None` when it passed.
    pub failure: Option<String>,
}

/// What `scen test` made of one file.
#[derive(Clone, Debug, PartialEq)]
pub struct FileResult {
    pub file: String,
    /// `ok  FILE  (N checks)` or `FAILED ...`.
    pub line: String,
    /// The diagnostics of its failures, rendered.
    pub diagnostics: String,
    pub cases: Vec<Case>,
}

/// The JUnit XML document.
pub fn to_junit(results: &[FileResult]) -> String {
    let tests: usize = results.iter().map(|r| r.cases.len()).sum();
    let failures: usize = results
        .iter()
        .map(|r| r.cases.iter().filter(|c| c.failure.is_some()).count())
        .sum();
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<testsuites name=\"scen test\" tests=\"{tests}\" failures=\"{failures}\" errors=\"0\">"
    );
    for r in results {
        let failed = r.cases.iter().filter(|c| c.failure.is_some()).count();
        let _ = writeln!(
            s,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failed}\" errors=\"0\" skipped=\"0\">",
            escape(&r.file),
            r.cases.len()
        );
        for c in &r.cases {
            let _ = write!(
                s,
                "    <testcase classname=\"{}\" name=\"{}\" file=\"{}\" line=\"{}\"",
                escape(&r.file),
                escape(&c.name),
                escape(&r.file),
                c.line
            );
            match &c.failure {
                None => s.push_str("/>\n"),
                Some(why) => {
                    let first = why.lines().next().unwrap_or("failed");
                    let _ = writeln!(
                        s,
                        ">\n      <failure message=\"{}\">{}</failure>\n    </testcase>",
                        escape(first),
                        escape(why)
                    );
                }
            }
        }
        s.push_str("  </testsuite>\n");
    }
    s.push_str("</testsuites>\n");
    s
}

/// Text for XML attributes and content: the five special characters
/// escaped, and characters XML 1.0 forbids (controls other than tab and
/// newlines, ANSI escapes included) dropped.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => {}
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn junit_escapes_and_counts() {
        let results = vec![FileResult {
            file: "a<b>.scen".into(),
            line: String::new(),
            diagnostics: String::new(),
            cases: vec![
                Case {
                    name: "line 3: p.cost <= 90 & \"x\"".into(),
                    line: 3,
                    failure: None,
                },
                Case {
                    name: "line 4: q".into(),
                    line: 4,
                    failure: Some("FAIL \u{1b}[31mred\u{1b}[0m\nmore".into()),
                },
            ],
        }];
        let xml = to_junit(&results);
        assert!(xml.contains("tests=\"2\" failures=\"1\""));
        assert!(xml.contains("name=\"line 3: p.cost &lt;= 90 &amp; &quot;x&quot;\""));
        assert!(xml.contains("classname=\"a&lt;b&gt;.scen\""));
        assert!(!xml.contains('\u{1b}'));
    }
}
