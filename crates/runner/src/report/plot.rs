//! `scen bench --svg OUT.svg` (SPEC §4; `--png` rasterises it): per bench
//! and metric, box plots of the runs of each configuration and plan, and —
//! when the bench varies a numeric key — a line per plan of the metric's
//! median against that key inside the band of its interquartile range. A
//! legend column right of the plots names the plans' colours and how to
//! read the marks, off the data. Drawn with `plotters` (its SVG backend).
//!
//! A box spans the quartiles (linear interpolation, as `quantile` in
//! `expect`), a line marks the median, the whiskers reach the most extreme
//! runs within 1.5 IQR of the box (Tukey's), and the runs beyond them are
//! dots. Values that are not finite (the +∞ length of a run without a path)
//! have no place on an axis: they are left out, and a box that leaves runs
//! out says how many it shows (`(18/20)`).

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::checks::{format_num, quantile};
use crate::palette::plan_colour;
use crate::run::BenchRun;
use crate::run::RunReport;
use crate::scenario::Scenario;
use crate::syntax::ast::ValueKind;

/// Pixels of one panel (taller when its box labels are turned).
const PANEL: (u32, u32) = (620, 300);
/// Width of the legend column right of the panels.
const LEGEND: u32 = 220;
/// Height of the x axis's label area with labels across.
const X_LABELS: u32 = 40;
/// The longest box label, in characters, before it is cut with `…`.
const MAX_LABEL: usize = 40;
/// Font sizes as plotters takes them (its SVG writes 1/1.24 of them, in
/// pixels): captions, axis names and box labels, tick labels.
const CAPTION_FONT: f64 = 20.0;
const LABEL_FONT: f64 = 15.0;
const TICK_FONT: f64 = 14.0;
/// Pixels of text per font size above.
const PX: f64 = 1.0 / 1.24;

/// The SVG document, or why plotters could not draw it.
pub fn to_svg(report: &RunReport, metrics: &[&str]) -> Result<String, String> {
    let metrics: Vec<&str> = if metrics.is_empty() {
        crate::bench::default_metrics(&report.scenario).to_vec()
    } else {
        metrics.to_vec()
    };
    let sc = &report.scenario;
    let benches: Vec<usize> = (0..sc.benches.len())
        .filter(|b| report.bench_runs.iter().any(|r| r.bench == *b))
        .collect();
    let rows = (benches.len() * metrics.len()).max(1) as u32;
    let numeric = |b: usize| numeric_key(sc, b);
    let lined = metrics.iter().any(|m| *m != "found");
    let columns = if lined && benches.iter().any(|&b| numeric(b).is_some()) {
        2
    } else {
        1
    };
    // One label area for every box panel, as deep as the longest turned
    // label needs.
    let label_area = benches
        .iter()
        .map(|&b| box_label_area(&configs(sc, b, &report.bench_runs)))
        .max()
        .unwrap_or(X_LABELS);
    let panel_height = PANEL.1 + label_area - X_LABELS;
    let data_width = PANEL.0 * columns;
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (data_width + LEGEND, panel_height * rows))
            .into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (data, legend) = root.split_horizontally(data_width);
        let panels = data.split_evenly((rows as usize, columns as usize));
        let legends = legend.split_evenly((rows as usize, 1));
        let mut k = 0;
        for &b in &benches {
            for metric in &metrics {
                let row = &panels[k * columns as usize..(k + 1) * columns as usize];
                boxes(&row[0], sc, b, &report.bench_runs, metric, label_area)
                    .map_err(|e| e.to_string())?;
                // A success rate has no median to draw against a key.
                let key = numeric(b).filter(|_| *metric != "found");
                if let (Some(key), Some(area)) = (key, row.get(1)) {
                    lines(area, sc, b, key, &report.bench_runs, metric)
                        .map_err(|e| e.to_string())?;
                }
                draw_legend(&legends[k], sc, b, key.is_some(), *metric == "found")
                    .map_err(|e| e.to_string())?;
                k += 1;
            }
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;
type Failure = Box<dyn std::error::Error>;

/// The first varied key whose values are all plain numbers, if any.
fn numeric_key(sc: &Scenario, b: usize) -> Option<usize> {
    sc.benches[b].vary.iter().position(|v| {
        v.values
            .iter()
            .all(|x| matches!(x.value.kind, ValueKind::Number(_) | ValueKind::Percent(_)))
    })
}

/// The finite values of `metric` over the runs of one plan and
/// configuration.
fn values(
    runs: &[BenchRun],
    b: usize,
    plan: usize,
    config: Option<usize>,
    metric: &str,
) -> Vec<f64> {
    runs.iter()
        .filter(|r| r.bench == b && r.plan == plan && config.is_none_or(|c| r.config == c))
        .filter_map(|r| r.metrics.get(metric).map(|v| v.as_f64()))
        .filter(|x| x.is_finite())
        .collect()
}

/// The range of an axis around `xs`, a little wider than the data.
fn axis(xs: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.08).max(hi.abs().max(1.0) * 1e-3);
    (lo - pad, hi + pad)
}

/// Each plan and configuration of bench `b` that has runs: the plan's
/// index in the bench, the configuration and the box's label (the plan,
/// unless it is the bench's only one, and the varied values).
fn configs(sc: &Scenario, b: usize, runs: &[BenchRun]) -> Vec<(usize, usize, String)> {
    let bench = &sc.benches[b];
    let mut out = Vec::new();
    for (p, plan) in bench.plans.iter().enumerate() {
        for config in 0..plan.configs.len() {
            if !runs
                .iter()
                .any(|r| r.bench == b && r.plan == p && r.config == config)
            {
                continue;
            }
            let picks = bench.config_values(config);
            // The legend names a bench's only plan.
            let mut parts = Vec::new();
            if bench.plans.len() > 1 || bench.vary.is_empty() {
                parts.push(sc.plans[plan.plan].name.clone());
            }
            for (v, &i) in bench.vary.iter().zip(&picks) {
                parts.push(format!("{}={}", v.key, v.values[i].text));
            }
            out.push((p, config, parts.join(" ")));
        }
    }
    out
}

/// About the width of `text` in pixels at plotters' font size `size`
/// (DejaVu Sans, which `--png` draws with, averages a little over half an
/// em).
fn text_width(text: &str, size: f64) -> f64 {
    text.chars().count() as f64 * size * PX * 0.6
}

/// Whether box labels side by side would run into each other: then they
/// are turned to run down from the axis.
fn turned(labels: &[(usize, usize, String)]) -> bool {
    // The plot's width, less the y labels and the margins.
    let room = f64::from(PANEL.0 - 70 - 16) / labels.len().max(1) as f64;
    labels.iter().any(|(_, _, l)| {
        text_width(l, LABEL_FONT) + text_width(" (20/20)", LABEL_FONT) > room - 6.0
    })
}

/// The height of a box panel's x label area: across, or as deep as the
/// longest turned label.
fn box_label_area(labels: &[(usize, usize, String)]) -> u32 {
    if !turned(labels) {
        return X_LABELS;
    }
    let longest = labels
        .iter()
        .map(|(_, _, l)| l.chars().count() + " (20/20)".len())
        .max()
        .unwrap_or(0)
        .min(MAX_LABEL);
    (longest as f64 * LABEL_FONT * PX * 0.6 + 16.0).ceil() as u32
}

/// `label` cut to [`MAX_LABEL`] characters.
fn cut(label: String) -> String {
    if label.chars().count() <= MAX_LABEL {
        label
    } else {
        let mut short: String = label.chars().take(MAX_LABEL - 1).collect();
        short.push('…');
        short
    }
}

/// Box plots of `metric`, one per plan and configuration.
fn boxes(
    area: &Area<'_>,
    sc: &Scenario,
    b: usize,
    runs: &[BenchRun],
    metric: &str,
    label_area: u32,
) -> Result<(), Failure> {
    let bench = &sc.benches[b];
    let configs = configs(sc, b, runs);
    let turn = turned(&configs);
    let mut labels: Vec<String> = Vec::new();
    let mut data: Vec<(Vec<f64>, usize)> = Vec::new();
    for (p, config, label) in &configs {
        let xs = values(runs, b, *p, Some(*config), metric);
        let total = runs
            .iter()
            .filter(|r| r.bench == b && r.plan == *p && r.config == *config)
            .count();
        let mut label = label.clone();
        if xs.len() < total {
            label.push_str(&format!(" ({}/{total})", xs.len()));
        }
        labels.push(cut(label));
        data.push((xs, bench.plans[*p].plan));
    }
    // `found` is drawn as the success rate: a bar per configuration, in
    // percent on a fixed 0–100 axis, with its 95 % Wilson interval.
    let rates = metric == "found";
    let (lo, hi) = if rates {
        (0.0, 100.0)
    } else {
        axis(data.iter().flat_map(|(xs, _)| xs.iter().copied()))
    };
    let (caption, y_desc) = if rates {
        (
            format!("{} — success rate", bench.name),
            "runs that found a path (%)",
        )
    } else {
        (format!("{} — {metric}", bench.name), metric)
    };
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", CAPTION_FONT))
        .margin(8)
        .x_label_area_size(label_area)
        .y_label_area_size(70)
        .build_cartesian_2d(labels[..].into_segmented(), lo as f32..hi as f32)?;
    let percent = |v: &f32| format!("{v:.0}");
    let mut mesh = chart.configure_mesh();
    mesh.y_desc(y_desc)
        .label_style(("sans-serif", TICK_FONT))
        .axis_desc_style(("sans-serif", LABEL_FONT))
        .x_labels(labels.len().max(1))
        // The boxes' labels are drawn below, turned when crowded: plotters
        // centres a turned tick label on its tick, across the axis.
        .x_label_formatter(&|_| String::new())
        .light_line_style(WHITE);
    if rates {
        // Whole percents: `40`, not `40.0`.
        mesh.y_label_formatter(&percent);
    }
    mesh.draw()?;
    let (bx, by) = area.get_base_pixel();
    let label_style = if turn {
        ("sans-serif", LABEL_FONT)
            .into_font()
            .transform(FontTransform::Rotate270)
            .color(&BLACK)
            .pos(Pos::new(HPos::Right, VPos::Center))
    } else {
        ("sans-serif", LABEL_FONT)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Top))
    };
    for label in &labels {
        let (x, y) = chart.backend_coord(&(SegmentValue::CenterOf(label), lo as f32));
        area.draw(&Text::new(
            label.clone(),
            (x - bx, y - by + 8),
            label_style.clone(),
        ))?;
    }
    if rates {
        for (label, (xs, plan)) in labels.iter().zip(&data) {
            let successes = xs.iter().filter(|&&x| x == 1.0).count();
            let (ci_lo, ci_hi) = crate::stats::wilson(successes, xs.len());
            if ci_lo.is_nan() {
                continue;
            }
            let rate = 100.0 * successes as f64 / xs.len() as f64;
            let [r, g, bl] = plan_colour(*plan);
            let at = |y: f64| (SegmentValue::CenterOf(label), y as f32);
            let px = |y: f64| chart.backend_coord(&at(y)).1;
            let ink = ShapeStyle::from(BLACK).stroke_width(2);
            chart.draw_series([EmptyElement::at(at(rate))
                + Rectangle::new(
                    [(-16, 0), (16, px(0.0) - px(rate))],
                    RGBColor(r, g, bl).mix(0.85).filled(),
                )])?;
            let (top, bottom) = (100.0 * ci_hi, 100.0 * ci_lo);
            chart.draw_series([PathElement::new([at(bottom), at(top)], ink)])?;
            for end in [bottom, top] {
                chart.draw_series([
                    EmptyElement::at(at(end)) + PathElement::new([(-7, 0), (7, 0)], ink)
                ])?;
            }
        }
        return Ok(());
    }
    for (label, (xs, plan)) in labels.iter().zip(&data) {
        if xs.is_empty() {
            continue;
        }
        let [r, g, bl] = plan_colour(*plan);
        let style = ShapeStyle::from(RGBColor(r, g, bl)).stroke_width(1);
        let t = Tukey::of(xs);
        let at = |y: f64| (SegmentValue::CenterOf(label), y as f32);
        // Pixel heights of the box from its top, for elements drawn in
        // pixels around a data point.
        let px = |y: f64| chart.backend_coord(&at(y)).1;
        let (top, q1, median) = (px(t.q3), px(t.q1), px(t.median));
        chart.draw_series([
            EmptyElement::at(at(t.q3)) + Rectangle::new([(-9, 0), (9, q1 - top)], style)
        ])?;
        chart.draw_series([EmptyElement::at(at(t.q3))
            + PathElement::new(
                [(-9, median - top), (9, median - top)],
                style.stroke_width(2),
            )])?;
        for (from, to) in [(t.q3, t.high), (t.q1, t.low)] {
            chart.draw_series([PathElement::new([at(from), at(to)], style)])?;
            chart.draw_series([
                EmptyElement::at(at(to)) + PathElement::new([(-5, 0), (5, 0)], style)
            ])?;
        }
        chart.draw_series(
            t.outliers
                .iter()
                .map(|&y| EmptyElement::at(at(y)) + Circle::new((0, 0), 2, style)),
        )?;
    }
    Ok(())
}

/// What a box plot shows of some values.
struct Tukey {
    q1: f64,
    median: f64,
    q3: f64,
    /// The whiskers' ends: the extreme values within 1.5 IQR of the box.
    low: f64,
    high: f64,
    /// The values beyond the whiskers.
    outliers: Vec<f64>,
}

impl Tukey {
    /// Of finite values, at least one.
    fn of(xs: &[f64]) -> Tukey {
        let mut sorted = xs.to_vec();
        sorted.sort_by(f64::total_cmp);
        let (q1, median, q3) = (
            quantile(&sorted, 0.25),
            quantile(&sorted, 0.5),
            quantile(&sorted, 0.75),
        );
        let reach = 1.5 * (q3 - q1);
        let inside = |x: &&f64| **x >= q1 - reach && **x <= q3 + reach;
        let low = sorted.iter().find(inside).copied().unwrap_or(q1).min(q1);
        let high = sorted
            .iter()
            .rev()
            .find(inside)
            .copied()
            .unwrap_or(q3)
            .max(q3);
        let outliers = sorted
            .iter()
            .copied()
            .filter(|x| *x < low || *x > high)
            .collect();
        Tukey {
            q1,
            median,
            q3,
            low,
            high,
            outliers,
        }
    }
}

/// The median of `metric` against the numeric varied key `key`, a line per
/// plan (over the runs of every value of the other keys), inside a band
/// from the first to the third quartile.
fn lines(
    area: &Area<'_>,
    sc: &Scenario,
    b: usize,
    key: usize,
    runs: &[BenchRun],
    metric: &str,
) -> Result<(), Failure> {
    let bench = &sc.benches[b];
    let vary = &bench.vary[key];
    let xs: Vec<f64> = vary
        .values
        .iter()
        .map(|v| match v.value.kind {
            ValueKind::Number(x) | ValueKind::Percent(x) => x,
            _ => f64::NAN,
        })
        .collect();
    let series: Vec<(usize, Vec<Spread>)> = bench
        .plans
        .iter()
        .enumerate()
        .map(|(p, plan)| {
            (
                plan.plan,
                spreads(runs, b, p, key, &xs, |c| bench.config_values(c), metric),
            )
        })
        .collect();
    let (x0, x1) = axis(xs.iter().copied());
    let (y0, y1) = axis(
        series
            .iter()
            .flat_map(|(_, s)| s.iter().flat_map(|q| [q.q1, q.q3])),
    );
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("{} — median {metric} by {}", bench.name, vary.key),
            ("sans-serif", CAPTION_FONT),
        )
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(vary.key.as_str())
        .y_desc(metric)
        .label_style(("sans-serif", TICK_FONT))
        .axis_desc_style(("sans-serif", LABEL_FONT))
        .x_label_formatter(&|x| format_num((*x * 1e4).round() / 1e4))
        .light_line_style(WHITE)
        .draw()?;
    // Every band under every line.
    for (plan, spread) in &series {
        let [r, g, bl] = plan_colour(*plan);
        if spread.len() > 1 {
            let band: Vec<(f64, f64)> = spread
                .iter()
                .map(|q| (q.x, q.q3))
                .chain(spread.iter().rev().map(|q| (q.x, q.q1)))
                .collect();
            chart.draw_series([Polygon::new(band, RGBColor(r, g, bl).mix(0.18).filled())])?;
        } else {
            // One value of the key: the band is a bar at it.
            chart.draw_series(spread.iter().map(|q| {
                PathElement::new(
                    [(q.x, q.q1), (q.x, q.q3)],
                    RGBColor(r, g, bl).mix(0.35).stroke_width(6),
                )
            }))?;
        }
    }
    for (plan, spread) in series {
        let [r, g, bl] = plan_colour(plan);
        let colour = RGBColor(r, g, bl);
        let medians: Vec<(f64, f64)> = spread.iter().map(|q| (q.x, q.median)).collect();
        chart.draw_series(LineSeries::new(medians.clone(), colour.stroke_width(2)))?;
        chart.draw_series(
            medians
                .into_iter()
                .map(|p| Circle::new(p, 3, colour.filled())),
        )?;
    }
    Ok(())
}

/// The quartiles of a metric's runs at one value `x` of a varied key.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Spread {
    x: f64,
    q1: f64,
    median: f64,
    q3: f64,
}

/// For the plan of bench index `p`, the quartiles of `metric`'s finite
/// values at each value of the varied key `key` (its values `xs`; `picks`
/// gives a configuration's value indices), in increasing `x`; values of
/// `x` without a finite run are left out.
fn spreads(
    runs: &[BenchRun],
    b: usize,
    p: usize,
    key: usize,
    xs: &[f64],
    picks: impl Fn(usize) -> Vec<usize>,
    metric: &str,
) -> Vec<Spread> {
    let mut out: Vec<Spread> = Vec::new();
    for (i, &x) in xs.iter().enumerate() {
        let mut ys: Vec<f64> = runs
            .iter()
            .filter(|r| r.bench == b && r.plan == p && picks(r.config).get(key) == Some(&i))
            .filter_map(|r| r.metrics.get(metric).map(|v| v.as_f64()))
            .filter(|y| y.is_finite())
            .collect();
        if ys.is_empty() || !x.is_finite() {
            continue;
        }
        ys.sort_by(f64::total_cmp);
        out.push(Spread {
            x,
            q1: quantile(&ys, 0.25),
            median: quantile(&ys, 0.5),
            q3: quantile(&ys, 0.75),
        });
    }
    out.sort_by(|a, b| a.x.total_cmp(&b.x));
    out
}

/// The legend of one row, in the column right of the plots: each plan's
/// colour and name, then how to read the marks.
fn draw_legend(
    area: &Area<'_>,
    sc: &Scenario,
    b: usize,
    has_lines: bool,
    rates: bool,
) -> Result<(), Failure> {
    let font = ("sans-serif", LABEL_FONT).into_font().color(&BLACK);
    let note = ("sans-serif", TICK_FONT - 1.0)
        .into_font()
        .color(&RGBColor(90, 90, 90));
    // Level with the top of the plots, under their captions.
    let mut y = 40;
    for plan in &sc.benches[b].plans {
        let [r, g, bl] = plan_colour(plan.plan);
        let colour = RGBColor(r, g, bl);
        area.draw(&Rectangle::new([(10, y - 5), (28, y + 5)], colour.filled()))?;
        let name = cut(sc.plans[plan.plan].name.clone());
        area.draw(&Text::new(name, (34, y - 7), font.clone()))?;
        y += 20;
    }
    y += 6;
    let mut notes = if rates {
        vec![
            "bar: the success rate",
            "error bar: its 95 % interval",
            "(Wilson score)",
        ]
    } else {
        vec![
            "box: 25–75 % of runs",
            "bar in a box: the median",
            "whiskers: within 1.5 IQR",
            "dots: runs beyond them",
        ]
    };
    if has_lines {
        notes.push("line: the median by value");
        notes.push("band: 25–75 % of runs");
    }
    for line in notes {
        area.draw(&Text::new(line, (10, y - 6), note.clone()))?;
        y += 16;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::sync::Arc;

    use super::*;
    use crate::contract::MetricValue;

    /// A bench of two plans over a numeric key, with made-up runs: plan
    /// `a`'s length at `weight = w` is w + run, plan `b`'s twice that.
    fn report() -> RunReport {
        let text = "world { bounds (0, 0) (20, 20) }\nrobot p point\n\
            plan a astar p { start (1, 1) goal (19, 19) }\n\
            plan b astar p { start (1, 1) goal (19, 19) cell 2 }\n\
            bench grow { plans [a, b] vary weight [1, 2, 4] runs 5 }\n";
        // An absolute path that does not exist: the overlay's text only.
        let file = std::env::temp_dir().join("scen-plot-test-overlay.scen");
        let overlay = |p: &Path| (p == file).then(|| Arc::<str>::from(text));
        let scenario = crate::scenario::loader::load_with(&file, None, &overlay)
            .unwrap_or_else(|f| panic!("{:?}", f.diags));
        let mut runs = Vec::new();
        for plan in 0..2 {
            for config in 0..3 {
                let weight = [1.0, 2.0, 4.0][config];
                for run in 0..5u32 {
                    let length = (weight + f64::from(run)) * (plan + 1) as f64;
                    runs.push(BenchRun {
                        bench: 0,
                        plan,
                        config,
                        world: 0,
                        run: u64::from(run),
                        seed: u64::from(run),
                        metrics: [("length".to_string(), MetricValue::Num(length))].into(),
                    });
                }
            }
        }
        crate::bench::report(scenario, runs)
    }

    #[test]
    fn lines_carry_the_quartiles_of_each_value_of_the_key() {
        let r = report();
        let bench = &r.scenario.benches[0];
        let s = spreads(
            &r.bench_runs,
            0,
            1,
            0,
            &[1.0, 2.0, 4.0],
            |c| bench.config_values(c),
            "length",
        );
        // Plan b at weight 2: lengths 4, 6, 8, 10, 12.
        assert_eq!(s.len(), 3);
        assert_eq!(
            s[1],
            Spread {
                x: 2.0,
                q1: 6.0,
                median: 8.0,
                q3: 10.0
            }
        );
    }

    /// The `x` of each `<text>` whose content is exactly `content`
    /// (plotters writes it on a line of its own).
    fn text_xs(svg: &str, content: &str) -> Vec<f64> {
        svg.split("<text")
            .skip(1)
            .filter(|t| {
                let inner = t.split_once('>').map_or("", |(_, rest)| rest);
                inner.split("</text>").next().map(str::trim) == Some(content)
            })
            .filter_map(|t| {
                let at = t.find(" x=\"")? + 4;
                t[at..].split('"').next()?.parse().ok()
            })
            .collect()
    }

    #[test]
    fn the_legend_is_right_of_every_plot() {
        let svg = to_svg(&report(), &["length"]).unwrap_or_default();
        let data_width = f64::from(2 * PANEL.0);
        for plan in ["a", "b"] {
            let xs = text_xs(&svg, plan);
            assert_eq!(xs.len(), 1, "{plan}: {xs:?}");
            assert!(xs[0] >= data_width, "{plan}'s legend at x = {}", xs[0]);
        }
        let notes = text_xs(&svg, "band: 25–75 % of runs");
        assert!(notes.len() == 1 && notes[0] >= data_width);
        // The data: the medians' dots and the bands, all left of it.
        let mut marks = 0;
        for circle in svg.split("<circle").skip(1) {
            let at = circle.find("cx=\"").map_or(0, |i| i + 4);
            let cx: f64 = circle[at..]
                .split('"')
                .next()
                .and_then(|v| v.parse().ok())
                .unwrap_or(f64::MAX);
            assert!(cx < data_width, "a dot at {cx}");
            marks += 1;
        }
        assert_eq!(marks, 6, "a dot per plan and value of the key");
        assert_eq!(svg.matches("<polygon").count(), 2, "a band per plan");
    }

    #[test]
    fn long_box_labels_are_turned_and_cut() {
        let short: Vec<(usize, usize, String)> =
            (0..3).map(|k| (0, k, format!("a k={k}"))).collect();
        assert!(!turned(&short));
        assert_eq!(box_label_area(&short), X_LABELS);
        let long: Vec<(usize, usize, String)> = (0..8)
            .map(|k| (0, k, format!("planner_{k} jump={k} weight=0.{k}")))
            .collect();
        assert!(turned(&long));
        assert!(box_label_area(&long) > X_LABELS);
        let cut_label = cut("x".repeat(60));
        assert_eq!(cut_label.chars().count(), MAX_LABEL);
        assert!(cut_label.ends_with('…'));
    }

    #[test]
    fn whiskers_end_at_values_within_one_and_a_half_iqr() {
        // Quartiles 2 and 4 (IQR 2): the whiskers reach 1 and 7, the
        // extreme values within [−1, 7]; 20 is beyond.
        let t = Tukey::of(&[3.0, 1.0, 2.0, 4.0, 20.0, 3.0, 7.0, 2.0, 4.0]);
        assert_eq!((t.q1, t.median, t.q3), (2.0, 3.0, 4.0));
        assert_eq!((t.low, t.high), (1.0, 7.0));
        assert_eq!(t.outliers, [20.0]);
        // One value: a box of no height, no whiskers, no outliers.
        let t = Tukey::of(&[5.0]);
        assert_eq!((t.q1, t.q3, t.low, t.high), (5.0, 5.0, 5.0, 5.0));
        assert!(t.outliers.is_empty());
    }
}
