//! `scen bench --svg OUT.svg` (SPEC §4): per bench and metric, box plots of
//! the runs of each configuration and plan, and — when the bench varies a
//! numeric key — a line per plan of the metric's median against that key.
//! Drawn with `plotters` (its SVG backend).
//!
//! A box spans the quartiles (linear interpolation, as `quantile` in
//! `expect`), a line marks the median, the whiskers reach the most extreme
//! runs within 1.5 IQR of the box (Tukey's), and the runs beyond them are
//! dots. Values that are not finite (the +∞ length of a run without a path)
//! have no place on an axis: they are left out, and a box that leaves runs
//! out says how many it shows (`(18/20)`).

use plotters::prelude::*;

use crate::bench::{BenchRun, TABLE_METRICS};
use crate::checks::{format_num, quantile};
use crate::run::RunReport;
use crate::scenario::Scenario;
use crate::syntax::ast::ValueKind;
use crate::viz::plan_colour;

/// Pixels of one panel.
const PANEL: (u32, u32) = (620, 300);

/// The SVG document, or why plotters could not draw it.
pub fn to_svg(report: &RunReport, metrics: &[&str]) -> Result<String, String> {
    let metrics: Vec<&str> = if metrics.is_empty() {
        TABLE_METRICS.to_vec()
    } else {
        metrics.to_vec()
    };
    let sc = &report.scenario;
    let benches: Vec<usize> = (0..sc.benches.len())
        .filter(|b| report.bench_runs.iter().any(|r| r.bench == *b))
        .collect();
    let rows = (benches.len() * metrics.len()).max(1) as u32;
    let numeric = |b: usize| numeric_key(sc, b);
    let columns = if benches.iter().any(|&b| numeric(b).is_some()) {
        2
    } else {
        1
    };
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (PANEL.0 * columns, PANEL.1 * rows))
            .into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let panels = root.split_evenly((rows as usize, columns as usize));
        let mut k = 0;
        for &b in &benches {
            for metric in &metrics {
                let row = &panels[k * columns as usize..(k + 1) * columns as usize];
                boxes(&row[0], sc, b, &report.bench_runs, metric).map_err(|e| e.to_string())?;
                if let (Some(key), Some(area)) = (numeric(b), row.get(1)) {
                    lines(area, sc, b, key, &report.bench_runs, metric)
                        .map_err(|e| e.to_string())?;
                }
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

/// Box plots of `metric`, one per plan and configuration.
fn boxes(
    area: &Area<'_>,
    sc: &Scenario,
    b: usize,
    runs: &[BenchRun],
    metric: &str,
) -> Result<(), Failure> {
    let bench = &sc.benches[b];
    let mut labels: Vec<String> = Vec::new();
    let mut data: Vec<(Vec<f64>, usize)> = Vec::new();
    for (p, plan) in bench.plans.iter().enumerate() {
        for config in 0..plan.configs.len() {
            let xs = values(runs, b, p, Some(config), metric);
            let total = runs
                .iter()
                .filter(|r| r.bench == b && r.plan == p && r.config == config)
                .count();
            if total == 0 {
                continue;
            }
            let picks = bench.config_values(config);
            let mut label = sc.plans[plan.plan].name.clone();
            for (v, &i) in bench.vary.iter().zip(&picks) {
                label.push_str(&format!(" {}={}", v.key, v.values[i].text));
            }
            if xs.len() < total {
                label.push_str(&format!(" ({}/{total})", xs.len()));
            }
            labels.push(label);
            data.push((xs, plan.plan));
        }
    }
    let (lo, hi) = axis(data.iter().flat_map(|(xs, _)| xs.iter().copied()));
    let mut chart = ChartBuilder::on(area)
        .caption(format!("{} — {metric}", bench.name), ("sans-serif", 16))
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(labels[..].into_segmented(), lo as f32..hi as f32)?;
    chart
        .configure_mesh()
        .y_desc(metric)
        .x_labels(labels.len().max(1))
        .x_label_formatter(&|v| match v {
            SegmentValue::CenterOf(s) | SegmentValue::Exact(s) => (*s).clone(),
            SegmentValue::Last => String::new(),
        })
        .light_line_style(WHITE)
        .draw()?;
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
/// plan (over the runs of every value of the other keys).
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
    let mut series: Vec<(usize, Vec<(f64, f64)>)> = Vec::new();
    for (p, plan) in bench.plans.iter().enumerate() {
        let mut points = Vec::new();
        for (i, &x) in xs.iter().enumerate() {
            let mut ys: Vec<f64> = runs
                .iter()
                .filter(|r| r.bench == b && r.plan == p && bench.config_values(r.config)[key] == i)
                .filter_map(|r| r.metrics.get(metric).map(|v| v.as_f64()))
                .filter(|y| y.is_finite())
                .collect();
            if ys.is_empty() {
                continue;
            }
            ys.sort_by(f64::total_cmp);
            let n = ys.len();
            let median = if n % 2 == 1 {
                ys[n / 2]
            } else {
                (ys[n / 2 - 1] + ys[n / 2]) / 2.0
            };
            points.push((x, median));
        }
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push((plan.plan, points));
    }
    let (x0, x1) = axis(xs.iter().copied());
    let (y0, y1) = axis(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)));
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("{} — median {metric} by {}", bench.name, vary.key),
            ("sans-serif", 16),
        )
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(vary.key.as_str())
        .y_desc(metric)
        .x_label_formatter(&|x| format_num((*x * 1e4).round() / 1e4))
        .light_line_style(WHITE)
        .draw()?;
    for (plan, points) in series {
        let [r, g, bl] = plan_colour(plan);
        let colour = RGBColor(r, g, bl);
        chart
            .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))?
            .label(sc.plans[plan].name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], colour));
        chart.draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p, 3, colour.filled())),
        )?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK.mix(0.3))
        .draw()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::Tukey;

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
