//! `scen run --gif OUT.gif` (SPEC 2.9): the world animated in plan time —
//! the moving obstacles, and the robot of every plan with a trajectory
//! (a time-aware planner's) or a drive — at 25 frames per second, each
//! frame the picture of `--svg` at that instant ([`super::svg::frame_at`])
//! rasterised; `--gif-speed K` plays it K times faster (a frame every K/25
//! s of plan time). An animation longer than [`MAX_FRAMES`] frames plays
//! faster still so that it fits (each frame's title says its time).
//!
//! Colours: one fixed palette (a 6 × 6 × 6 cube and 40 greys), each pixel
//! its nearest entry, so frames need no quantiser and the same run gives
//! the same bytes.

use std::path::Path;

use super::sink::{Command, Product, Sink, Tuning, the_file, write_file};
use crate::run::RunReport;

/// Frames per second of plan time.
pub const FPS: f64 = 25.0;

/// The most frames of one animation.
pub const MAX_FRAMES: usize = 1_000;

/// Pixels per SVG unit of a frame (the PNG's are 2).
const FRAME_SCALE: f32 = 0.75;

/// `--gif OUT.gif`.
pub static SINK: Sink = Sink {
    option: "--gif",
    value_name: "OUT.gif",
    help: &[(
        Command::Run,
        "Animate the moving obstacles and the robots of plans with a trajectory or a drive (GIF, 25 frames per second of plan time)",
    )],
    draws: false,
    folder: false,
    check: |path| super::sink::needs_extension(path, "--gif", "gif", "a GIF animation", ""),
    files: the_file,
    tuning: Some(&SPEED),
    write: |product, path, speed| match product {
        Product::Run(report) => write_file(
            path,
            animation(report, path, speed.unwrap_or(SPEED.default))?,
        ),
        Product::Bench(..) => Err(vec!["`--gif` animates a run, not a bench".into()]),
    },
};

/// The most `--gif-speed` accepts (a 1,000-frame animation of a day of
/// plan time at 100 is still 30 s long).
const MAX_SPEED: f64 = 1e6;

/// `--gif-speed K`.
static SPEED: Tuning = Tuning {
    option: "--gif-speed",
    value_name: "K",
    help: "Play the `--gif` animation K times faster than plan time (default 1; 0.5 is slow motion)",
    default: 1.0,
    check: |k| {
        if k.is_finite() && k > 0.0 && k <= MAX_SPEED {
            Ok(())
        } else {
            Err(format!(
                "`--gif-speed {k}`: the speed is a number above 0 and at most {MAX_SPEED:e} (2 plays twice as fast, 0.5 in slow motion)"
            ))
        }
    },
};

/// How long the run moves: until the last moving obstacle settles and the
/// last trajectory, drive or team ends; `None` when nothing moves.
pub fn duration(report: &RunReport) -> Option<f64> {
    let scenario = &report.scenario;
    let mut end: Option<f64> = None;
    let mut take = |t: f64| end = Some(end.map_or(t, |e: f64| e.max(t)));
    for o in &scenario.moving {
        take(o.settles());
    }
    for run in &report.plans {
        if let (Some(_), Some(times)) = (&run.outcome.path, &run.outcome.times) {
            take(times.last().copied().unwrap_or(0.0));
        }
        if let Some(drive) = &run.drive {
            take(drive.samples.last().map_or(0.0, |s| s.0));
        }
        // A team under grid semantics moves a step a second (SPEC 2.10).
        if let Some(paths) = &run.outcome.agents {
            take(super::svg::team_end(
                paths,
                run.outcome.agent_times.as_deref(),
            ));
        }
    }
    end
}

/// The plan time an animation at `speed` spans: from 0 to one second of
/// the animation (`speed` s of plan time) after `end`.
fn span(end: f64, speed: f64) -> f64 {
    end.max(0.0) + speed
}

/// The instants of the frames at `speed`: every `speed`/25 s of plan time
/// from 0 to a second of the animation after `end` (fewer, evenly spread,
/// beyond [`MAX_FRAMES`]).
pub fn instants(end: f64, speed: f64) -> Vec<f64> {
    let span = span(end, speed);
    let frames = ((span * FPS / speed).ceil() as usize + 1).clamp(2, MAX_FRAMES);
    (0..frames)
        .map(|k| span * k as f64 / (frames - 1) as f64)
        .collect()
}

fn animation(report: &RunReport, path: &Path, speed: f64) -> Result<Vec<u8>, Vec<String>> {
    let Some(end) = duration(report) else {
        return Err(vec![format!(
            "`--gif {}`: nothing moves (no moving obstacle, and no plan with a trajectory or a drive); nothing was written",
            path.display()
        )]);
    };
    let times = instants(end, speed);
    // The frame's delay in hundredths of a second: 4 at 25 frames per
    // second; the plan time between frames, shown `speed` times faster
    // (longer when a long animation was spread thinner).
    let step = span(end, speed) / (times.len() - 1) as f64 / speed;
    let delay = (step * 100.0).round().clamp(2.0, 65_535.0) as u16;
    let palette = palette();
    let fail = |e: String| vec![format!("cannot animate `{}`: {e}", path.display())];
    let frame = |t: f64| -> Result<(u16, u16, Vec<u8>), Vec<String>> {
        let pixmap = super::png::rasterise(&super::svg::frame_at(report, t), Some(FRAME_SCALE))
            .map_err(fail)?;
        let (w, h) = (pixmap.width(), pixmap.height());
        let (Ok(w16), Ok(h16)) = (u16::try_from(w), u16::try_from(h)) else {
            return Err(fail(format!("a frame of {w}×{h} pixels is too large")));
        };
        Ok((
            w16,
            h16,
            pixmap.data().chunks_exact(4).map(nearest).collect(),
        ))
    };
    let (w, h, first) = frame(times[0])?;
    let mut bytes = Vec::new();
    {
        let mut encoder =
            gif::Encoder::new(&mut bytes, w, h, &palette).map_err(|e| fail(e.to_string()))?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(|e| fail(e.to_string()))?;
        let mut f = gif::Frame::from_indexed_pixels(w, h, first.clone(), None);
        f.delay = delay;
        encoder.write_frame(&f).map_err(|e| fail(e.to_string()))?;
        // Each later frame only the rectangle where it differs from the one
        // before (the rest is kept on screen).
        let mut shown = first;
        for &t in &times[1..] {
            let (fw, fh, next) = frame(t)?;
            if (fw, fh) != (w, h) {
                return Err(fail("the frames differ in size".into()));
            }
            let (w_, h_) = (usize::from(w), usize::from(h));
            let changed = |i: usize| next[i] != shown[i];
            let rows: Vec<usize> = (0..h_)
                .filter(|&y| (0..w_).any(|x| changed(y * w_ + x)))
                .collect();
            let (top, bottom, left, right) = match (rows.first(), rows.last()) {
                (Some(&top), Some(&bottom)) => {
                    let cols = |x: usize| (top..=bottom).any(|y| changed(y * w_ + x));
                    let left = (0..w_).find(|&x| cols(x)).unwrap_or(0);
                    let right = (0..w_).rev().find(|&x| cols(x)).unwrap_or(0);
                    (top, bottom, left, right)
                }
                // Nothing changed: one pixel, so the frame still takes its time.
                _ => (0, 0, 0, 0),
            };
            let part: Vec<u8> = (top..=bottom)
                .flat_map(|y| next[y * w_ + left..=y * w_ + right].iter().copied())
                .collect();
            let mut f = gif::Frame::from_indexed_pixels(
                (right - left + 1) as u16,
                (bottom - top + 1) as u16,
                part,
                None,
            );
            f.left = left as u16;
            f.top = top as u16;
            f.delay = delay;
            f.dispose = gif::DisposalMethod::Keep;
            encoder.write_frame(&f).map_err(|e| fail(e.to_string()))?;
            shown = next;
        }
    }
    Ok(bytes)
}

/// The palette: entries 0–215 the cube of levels 0, 51, ..., 255 (index
/// 36·r + 6·g + b), then 40 greys between the cube's.
fn palette() -> Vec<u8> {
    let mut p = Vec::with_capacity(256 * 3);
    for r in 0..6u8 {
        for g in 0..6u8 {
            for b in 0..6u8 {
                p.extend([r * 51, g * 51, b * 51]);
            }
        }
    }
    for k in 0..40u32 {
        let v = (k * 255 / 39) as u8;
        p.extend([v, v, v]);
    }
    p
}

/// The palette entry of a premultiplied RGBA pixel (over white where it
/// is not opaque): a grey when the pixel is one, else the cube's nearest.
fn nearest(px: &[u8]) -> u8 {
    let a = u32::from(px[3]);
    let over = |c: u8| -> u32 { u32::from(c) + (255 - a) };
    let (r, g, b) = (over(px[0]), over(px[1]), over(px[2]));
    let level = |c: u32| (c * 5 + 127) / 255;
    if r.abs_diff(g) <= 6 && g.abs_diff(b) <= 6 {
        let v = (r + g + b) / 3;
        return 216 + ((v * 39 + 127) / 255) as u8;
    }
    (36 * level(r) + 6 * level(g) + level(b)) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_25_per_second_up_to_the_cap() {
        let t = instants(3.0, 1.0);
        assert_eq!(t.len(), 101);
        assert!((t[1] - 0.04).abs() < 1e-12, "{}", t[1]);
        assert_eq!(t.last().copied(), Some(4.0));
        assert_eq!(instants(1e6, 1.0).len(), MAX_FRAMES);
    }

    #[test]
    fn a_speed_of_k_takes_a_frame_every_k_25ths_of_a_second() {
        // 4 times faster: 4 s of motion and a second of the animation
        // (4 s of plan time) after it, a frame every 0.16 s.
        let t = instants(4.0, 4.0);
        assert_eq!(t.len(), 51);
        assert!((t[1] - 0.16).abs() < 1e-12, "{}", t[1]);
        assert_eq!(t.last().copied(), Some(8.0));
        // Slow motion: twice the frames of the same span.
        let slow = instants(3.0, 0.5);
        assert!((slow[1] - 0.02).abs() < 1e-12, "{}", slow[1]);
        assert_eq!(slow.last().copied(), Some(3.5));
        // Nothing moves for long: still the second after the end; and the
        // cap.
        assert_eq!(instants(0.0, 1e6).len(), 26);
        assert_eq!(instants(1e6, 0.001).len(), MAX_FRAMES);
        for k in [0.0, -1.0, f64::NAN, f64::INFINITY, 2e6] {
            assert!((SPEED.check)(k).is_err(), "{k}");
        }
        assert!((SPEED.check)(0.5).is_ok() && (SPEED.check)(100.0).is_ok());
    }

    #[test]
    fn the_palette_holds_the_cube_and_the_greys() {
        let p = palette();
        assert_eq!(p.len(), 256 * 3);
        let colour = |i: u8| &p[3 * usize::from(i)..3 * usize::from(i) + 3];
        assert_eq!(colour(nearest(&[255, 255, 255, 255])), [255, 255, 255]);
        assert_eq!(colour(nearest(&[0, 0, 0, 255])), [0, 0, 0]);
        // Transparent is the background white; a plan's blue stays blue.
        assert_eq!(colour(nearest(&[0, 0, 0, 0])), [255, 255, 255]);
        let blue = colour(nearest(&[31, 119, 180, 255]));
        assert!(blue[2] > blue[0] && blue[2] > blue[1], "{blue:?}");
    }
}
