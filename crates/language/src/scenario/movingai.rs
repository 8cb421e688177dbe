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
