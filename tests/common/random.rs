//! The random scenarios of `tests/random_scenarios.rs` (also formatted by
//! `tests/fmt.rs`): random worlds (rects, disks, segments, convex polygons,
//! grids), robots and plans of every planner kind with random parameters.

use scen::rng::SplitMix64;

/// The crate's SplitMix64, with what the generator needs: the text of
/// one case from one seed.
pub struct Rng(pub SplitMix64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// In [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0.next_f64()
    }

    /// Rounded to hundredths, in [lo, hi].
    pub fn num(&mut self, lo: f64, hi: f64) -> f64 {
        ((lo + (hi - lo) * self.unit()) * 100.0).round() / 100.0
    }

    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    pub fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len() as u64) as usize]
    }
}

/// The world's text, and the grid's size in cells (0 × 0 without one).
fn world(r: &mut Rng, w: u64, h: u64, grid: bool, most: u64) -> (String, u64, u64) {
    let (wf, hf) = (w as f64, h as f64);
    let mut out = format!("world {{\n  bounds (0, 0) ({w}, {h})\n");
    for _ in 0..r.below(most + 1) {
        let (x, y) = (r.num(0.0, wf), r.num(0.0, hf));
        let line = match r.below(5) {
            0 => {
                let (u, v) = (r.num(0.1, 5.0), r.num(0.1, 5.0));
                format!("rect ({x}, {y}) ({}, {})", (x + u).min(wf), (y + v).min(hf))
            }
            1 => format!("disk ({x}, {y}) {}", r.num(0.05, 3.0)),
            2 => {
                let (u, v) = (r.num(0.0, wf), r.num(0.0, hf));
                if (u, v) == (x, y) {
                    continue;
                }
                format!("segment ({x}, {y}) ({u}, {v})")
            }
            3 => {
                // On the grid lines: walls and boxes with whole coordinates.
                let (xi, yi) = (r.below(w), r.below(h));
                let l = 1 + r.below(4);
                if r.below(2) == 0 {
                    format!("segment ({xi}, {yi}) ({xi}, {})", (yi + l).min(h))
                } else {
                    format!(
                        "rect ({xi}, {yi}) ({}, {})",
                        (xi + l).min(w),
                        (yi + 1).min(h)
                    )
                }
            }
            _ => {
                let n = 3 + r.below(5);
                let rad = r.num(0.3, 3.0);
                let pts: Vec<String> = (0..n)
                    .map(|j| {
                        let jitter = r.unit() - 0.5;
                        let a = std::f64::consts::TAU * j as f64 / n as f64 + 0.6 * jitter;
                        let px = ((x + rad * a.cos()) * 100.0).round() / 100.0;
                        let py = ((y + rad * a.sin()) * 100.0).round() / 100.0;
                        format!("({px}, {py})")
                    })
                    .collect();
                format!("polygon [{}]", pts.join(", "))
            }
        };
        out.push_str(&format!("  {line}\n"));
    }
    let (mut gw, mut gh) = (0, 0);
    if grid {
        (gw, gh) = (2 + r.below(w - 1), 2 + r.below(h - 1));
        out.push_str("  grid G cell 1 origin (0, 0) {\n");
        for _ in 0..gh {
            let row: String = (0..gw)
                .map(|_| if r.below(10) == 0 { '#' } else { '.' })
                .collect();
            out.push_str(&format!("    \"{row}\"\n"));
        }
        out.push_str("  }\n");
    }
    out.push_str("}\n");
    (out, gw, gh)
}

/// One scenario: a world, a robot, one plan and a check that always holds.
pub fn scenario(seed: u64) -> String {
    let mut r = Rng(SplitMix64::new(seed));
    let (w, h) = (4 + r.below(20), 4 + r.below(20));
    let kind = r.pick(&["astar", "online", "roadmap", "potential", "coverage"]);
    let grid = kind == "coverage" || r.below(4) == 0;
    // Coverage needs room: a whole free mega-cell around its start.
    let most = if kind == "coverage" { 2 } else { 7 };
    let (text, gw, gh) = world(&mut r, w, h, grid, most);
    let tool = 1 + r.below(2);
    let half = tool as f64 / 2.0;
    let robot = match kind {
        "online" | "potential" => {
            if r.below(2) == 0 {
                "point".to_string()
            } else {
                format!("disk {}", r.num(0.05, 1.0))
            }
        }
        "coverage" => format!("disk {}", r.num(0.05, half)),
        _ => match r.below(4) {
            0 => "point".to_string(),
            1 => format!("disk {}", r.num(0.05, 1.0)),
            2 => format!("rect {} {}", r.num(0.1, 2.0), r.num(0.1, 1.0)),
            _ => "polygon [(0, 0), (1, 0), (0.5, 0.8)]".to_string(),
        },
    };
    let rotating = robot.starts_with("rect") || robot.starts_with("polygon");
    let (wf, hf) = (w as f64, h as f64);
    let mut params = vec![if kind == "coverage" {
        let (i, j) = (r.below((gw / tool).max(1)), r.below((gh / tool).max(1)));
        format!(
            "start ({}, {})",
            (i * tool) as f64 + half,
            (j * tool) as f64 + half
        )
    } else if rotating {
        format!(
            "start ({}, {}, {}deg)",
            r.num(0.0, wf),
            r.num(0.0, hf),
            r.below(360)
        )
    } else {
        format!("start ({}, {})", r.num(0.0, wf), r.num(0.0, hf))
    }];
    if kind != "coverage" {
        params.push(format!("goal ({}, {})", r.num(0.0, wf), r.num(0.0, hf)));
    }
    match kind {
        "astar" => {
            params.push(format!("cell {}", r.pick(&["0.25", "0.5", "1", "2"])));
            if rotating {
                params.push(format!("layers {}", r.pick(&["4", "8", "16", "auto"])));
            }
        }
        "online" => params.push(format!(
            "strategy {}",
            r.pick(&["backtrack", "shortcut", "replan", "dstar_lite"])
        )),
        "roadmap" => params.push(format!("arc_segments {}", r.pick(&["8", "12", "32"]))),
        "potential" => {
            params.push(format!("step {}", r.pick(&["0.02", "0.05", "0.3"])));
            params.push(format!("seed {}", r.below(100)));
            params.push("limit steps 100000".into());
        }
        _ => params.push(format!("on G tool {tool}")),
    }
    params.push("limit time 5s".into());
    format!(
        "scenario \"random {seed}\"\n{text}robot R {robot}\n\
         plan P {kind} R {{ {} }}\nexpect P.found or not P.found\n",
        params.join(" ")
    )
}
