//! Grid files: the cell characters of SPEC 2.3 and the MovingAI `.map`
//! format (https://movingai.com/benchmarks/formats.html): a header
//! (`type`, `height H`, `width W`, `map`) and H rows of W cells; CRLF line
//! ends are accepted.

/// The weight of a grid character: 0 blocked, 1..=9 free (SPEC 2.3).
pub fn grid_char(c: char) -> Option<u8> {
    match c {
        '.' | 'G' | 'S' => Some(1),
        '1'..='9' => Some(c as u8 - b'0'),
        '@' | 'O' | 'T' | 'W' | '#' => Some(0),
        _ => None,
    }
}

/// The largest grid accepted from a map file (cells).
const MAX_MAP_CELLS: usize = 50_000_000;

/// Parses a MovingAI `.map` file: `(width, height, cells)`, or the 1-based
/// line of the first problem and a message.
pub fn parse_movingai(text: &str) -> Result<(usize, usize, Vec<u8>), (usize, String)> {
    let mut lines = text.lines().map(|l| l.trim_end_matches('\r')).enumerate();
    let mut height = None;
    let mut width = None;
    loop {
        let Some((n, line)) = lines.next() else {
            return Err((n_lines(text), "missing `map` line before the rows".into()));
        };
        let mut words = line.split_whitespace();
        match (words.next(), words.next()) {
            (Some("type"), _) => {}
            (Some("height"), Some(h)) => {
                height = Some(
                    h.parse::<usize>()
                        .map_err(|_| (n + 1, "the `height` is not a whole number".to_string()))?,
                )
            }
            (Some("width"), Some(w)) => {
                width = Some(
                    w.parse::<usize>()
                        .map_err(|_| (n + 1, "the `width` is not a whole number".to_string()))?,
                )
            }
            (Some("map"), None) => break,
            (None, _) => {}
            _ => {
                return Err((
                    n + 1,
                    // The line is not quoted: the file may be anything
                    // (SPEC 2.2: no echo of bytes that are not a scenario's).
                    "an unexpected header line (a MovingAI header has `type`, `height`, `width` and `map` lines)".to_string(),
                ));
            }
        }
    }
    let (Some(h), Some(w)) = (height, width) else {
        return Err((1, "the header must give `height` and `width`".into()));
    };
    if h == 0 || w == 0 || h.saturating_mul(w) > MAX_MAP_CELLS {
        return Err((
            1,
            format!("a {w} × {h} map is empty or too large (limit {MAX_MAP_CELLS} cells)"),
        ));
    }
    let mut cells = Vec::with_capacity(w * h);
    for r in 0..h {
        let Some((n, line)) = lines.next() else {
            return Err((
                n_lines(text),
                format!("the map has {r} rows, the header says {h}"),
            ));
        };
        if line.chars().count() != w {
            return Err((
                n + 1,
                format!(
                    "row {} has {} cells, the header says {w}",
                    r + 1,
                    line.chars().count()
                ),
            ));
        }
        for (c, ch) in line.chars().enumerate() {
            match grid_char(ch) {
                Some(x) => cells.push(x),
                None => {
                    return Err((
                        n + 1,
                        format!("`{ch}` in column {} is not a map cell", c + 1),
                    ));
                }
            }
        }
    }
    Ok((w, h, cells))
}

fn n_lines(text: &str) -> usize {
    text.lines().count().max(1)
}

/// One row of a MovingAI scenario file (`.scen`): the map it is for and
/// an agent's start and goal cells (x the column, y the row from the top).
#[derive(Clone, Debug, PartialEq)]
pub struct ScenRow {
    /// The row's bytes in the file (its line, without the line end).
    pub at: std::ops::Range<usize>,
    pub map: String,
    pub width: usize,
    pub height: usize,
    pub start: (usize, usize),
    pub goal: (usize, usize),
}

/// Whether `path` is a MovingAI `.scen` file rather than a scenario: its
/// first words are `version` and a number (no scenario starts so). The
/// commands and the tests that walk a folder of scenarios leave such files
/// alone; teams read them (`team T point from "F.scen" agents N`).
pub fn is_scen_file(path: &std::path::Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 64];
    let n = std::fs::File::open(path)
        .and_then(|mut f| f.read(&mut head))
        .unwrap_or(0);
    let text = String::from_utf8_lossy(&head[..n]);
    let mut words = text.split_whitespace();
    words.next() == Some("version") && words.next().is_some_and(|w| w.parse::<u32>().is_ok())
}

/// The first `n` rows of a MovingAI `.scen` file (`version 1` or a bare
/// first row; tab- or blank-separated columns: bucket, map, width, height,
/// start x, start y, goal x, goal y, optimal length; CRLF accepted). `Err`:
/// the byte range of the line at fault and a message.
pub fn parse_scen(text: &str, n: usize) -> Result<Vec<ScenRow>, (std::ops::Range<usize>, String)> {
    let mut rows = Vec::new();
    let mut offset = 0;
    for (k, raw) in text.split_inclusive('\n').enumerate() {
        let start = offset;
        offset += raw.len();
        if rows.len() == n {
            break;
        }
        let line = raw.trim_end_matches('\n').trim_end_matches('\r');
        let at = start..start + line.len();
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.is_empty() || (k == 0 && words[0] == "version") {
            continue;
        }
        if words.len() != 9 {
            return Err((
                at,
                format!(
                    "a scenario row has 9 columns (bucket, map, width, height, start x, start y, goal x, goal y, optimal length), this one {}",
                    words.len()
                ),
            ));
        }
        let num = |i: usize, what: &str| {
            words[i]
                .parse::<usize>()
                .map_err(|_| (at.clone(), format!("the {what} is not a whole number")))
        };
        rows.push(ScenRow {
            at: at.clone(),
            map: words[1].to_string(),
            width: num(2, "map width")?,
            height: num(3, "map height")?,
            start: (num(4, "start x")?, num(5, "start y")?),
            goal: (num(6, "goal x")?, num(7, "goal y")?),
        });
    }
    Ok(rows)
}

#[cfg(test)]
mod scen_tests {
    use super::*;

    #[test]
    fn rows_are_read_with_their_place() {
        let text = "version 1\r\n3\tr.map\t32\t32\t11\t6\t7\t18\t13.6\r\n7 maps/r.map 32 32 29 9 1 16 30.9\n";
        let rows = parse_scen(text, 5).unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0].start, rows[0].goal), ((11, 6), (7, 18)));
        assert_eq!(
            &text[rows[1].at.clone()],
            "7 maps/r.map 32 32 29 9 1 16 30.9"
        );
        assert_eq!(parse_scen(text, 1).unwrap().len(), 1);
        let (at, msg) = parse_scen("version 1\n1 m 3 3 0 0 x 1 2\n", 5).unwrap_err();
        assert_eq!(at, 10..27);
        assert!(msg.contains("goal x"), "{msg}");
        assert!(parse_scen("version 1\n1 m 3 3\n", 5).is_err());
    }
}
