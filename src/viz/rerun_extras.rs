//! The planner-specific parts of a plan in the Rerun stream (SPEC 6): the
//! roadmap, the online robot's knowledge, the potential field, the coverage
//! tree, and a driven robot. Each reads one field of the plan's
//! [`Trace`](crate::planners::Trace) or its [`DriveOutcome`].
//!
//! | entity | archetype | timeline |
//! |---|---|---|
//! | `plans/NAME/roadmap` | LineStrips2D: visibility edges | static |
//! | `plans/NAME/known/free/B`, `plans/NAME/known/blocked/B` | Boxes2D: cells first sensed in batch B | `step` |
//! | `plans/NAME/plan` | LineStrips2D: the plan the online robot holds | `step` |
//! | `plans/NAME/field/{attract,repulse,total}` | Arrows2D: directions of the forces at sampled steps (all 3% of the world's size long) | `step` |
//! | `plans/NAME/field/minima` | Points2D: local minima | static |
//! | `plans/NAME/field/escapes` | LineStrips2D + Points2D: escape jumps and where they land | static |
//! | `plans/NAME/mega_cells`, `plans/NAME/uncovered` | Boxes2D: tree mega-cells, D-cells STC cannot cover | static |
//! | `plans/NAME/tree` | LineStrips2D: the coverage spanning tree | static |
//! | `plans/NAME/drive/path`, `plans/NAME/drive/robot` | LineStrips2D: the driven trajectory, the body | static, `time` (s) |
//!
//! Sensed cells are sent in at most [`SENSE_BATCHES`] batches, each to an
//! entity of its own: an entity keeps showing its value once logged, so
//! at step `k` the viewer shows everything sensed up to `k` without the
//! cells being sent again.

use rerun::{
    Arrows2D, Boxes2D, Color, LineStrips2D, Points2D, Radius, RecordingStream,
    RecordingStreamResult,
};

use super::rerun_sink::{entity, rgb, strip};
use super::{OBSTACLE_GREY, robot_outline};
use crate::drive::DriveOutcome;
use crate::geometry::{Aabb, Point, RobotShape, Vector};
use crate::planners::{CoverageTrace, FieldTrace, OnlineTrace};

/// The most batches sensed cells are sent in.
pub(crate) const SENSE_BATCHES: usize = 100;

/// The most poses of a driven robot sent on timeline `time`.
pub(crate) const DRIVE_POSES: usize = 2_000;

const FREE_GREEN: [u8; 3] = [170, 215, 170];
const BLOCKED_DARK: [u8; 3] = [90, 90, 90];

/// The visibility edges of a roadmap.
pub(super) fn log_roadmap(
    rec: &RecordingStream,
    name: &str,
    edges: &[(Point, Point)],
    faint: Color,
) -> RecordingStreamResult<()> {
    if edges.is_empty() {
        return Ok(());
    }
    rec.log_static(
        entity(&["plans", name, "roadmap"]),
        &LineStrips2D::new(edges.iter().map(|(a, b)| strip(&[*a, *b])))
            .with_colors([faint])
            .with_radii([Radius::new_ui_points(0.5)])
            .with_draw_order(16.0),
    )
}

/// What the online robot sensed (cumulative, by batches) and the plan it
/// held, on timeline `step`.
pub(super) fn log_online(
    rec: &RecordingStream,
    name: &str,
    online: &OnlineTrace,
    colour: Color,
) -> RecordingStreamResult<()> {
    let steps = online.sensed.len();
    let batch = steps.div_ceil(SENSE_BATCHES).max(1);
    let half = (online.cell / 2.0) as f32;
    for (b, chunk) in online.sensed.chunks(batch).enumerate() {
        let first = b * batch;
        rec.set_time_sequence("step", first as i64);
        for (blocked, label, colour) in
            [(false, "free", FREE_GREEN), (true, "blocked", BLOCKED_DARK)]
        {
            let centres: Vec<[f32; 2]> = chunk
                .iter()
                .flatten()
                .filter(|(_, is_blocked)| *is_blocked == blocked)
                .map(|(p, _)| [p.x as f32, p.y as f32])
                .collect();
            if centres.is_empty() {
                continue;
            }
            let n = centres.len();
            rec.log(
                entity(&["plans", name, "known", label, &format!("{b:04}")]),
                &Boxes2D::from_centers_and_half_sizes(
                    centres,
                    std::iter::repeat_n([half, half], n),
                )
                .with_colors([rgb(colour)])
                .with_draw_order(if blocked { 12.0 } else { 2.0 }),
            )?;
        }
    }
    let mut previous: Option<&Vec<Point>> = None;
    for (step, plan) in online.plans.iter().enumerate() {
        if previous == Some(plan) {
            continue;
        }
        previous = Some(plan);
        rec.set_time_sequence("step", step as i64);
        rec.log(
            entity(&["plans", name, "plan"]),
            &LineStrips2D::new([strip(plan)])
                .with_colors([colour])
                .with_radii([Radius::new_ui_points(1.0)])
                .with_draw_order(25.0),
        )?;
    }
    rec.reset_time();
    Ok(())
}

/// Forces at the sampled steps, local minima and escape jumps.
pub(super) fn log_field(
    rec: &RecordingStream,
    name: &str,
    field: &FieldTrace,
    length: f64,
    colour: Color,
) -> RecordingStreamResult<()> {
    // Forces span orders of magnitude (repulsion grows as 1/ρ³): arrows
    // show directions, all `length` long; zero forces are left out.
    let arrows = |v: Vector| {
        let n = v.norm();
        if n > 0.0 && n.is_finite() {
            let u = v * (length / n);
            [u.x as f32, u.y as f32]
        } else {
            [0.0, 0.0]
        }
    };
    let kinds: [(&str, [u8; 3]); 3] = [
        ("attract", [44, 160, 44]),
        ("repulse", [214, 39, 40]),
        ("total", [31, 119, 180]),
    ];
    for f in &field.forces {
        rec.set_time_sequence("step", f.step as i64);
        for (kind, c) in kinds {
            let v = match kind {
                "attract" => f.attract,
                "repulse" => f.repulse,
                _ => f.total,
            };
            rec.log(
                entity(&["plans", name, "field", kind]),
                &Arrows2D::from_vectors([arrows(v)])
                    .with_origins([[f.at.x as f32, f.at.y as f32]])
                    .with_colors([rgb(c)])
                    .with_draw_order(35.0),
            )?;
        }
    }
    rec.reset_time();
    if !field.minima.is_empty() {
        rec.log_static(
            entity(&["plans", name, "field", "minima"]),
            &Points2D::new(field.minima.iter().map(|(_, p)| [p.x as f32, p.y as f32]))
                .with_colors([rgb([214, 39, 40])])
                .with_radii([Radius::new_ui_points(5.0)])
                .with_draw_order(36.0),
        )?;
    }
    if !field.escapes.is_empty() {
        let jumps = entity(&["plans", name, "field", "escapes"]);
        rec.log_static(
            jumps.clone(),
            &LineStrips2D::new(field.escapes.iter().map(|(_, a, b)| strip(&[*a, *b])))
                .with_colors([colour])
                .with_radii([Radius::new_ui_points(1.0)])
                .with_draw_order(36.0),
        )?;
        rec.log_static(
            jumps,
            &Points2D::new(
                field
                    .escapes
                    .iter()
                    .map(|(_, _, b)| [b.x as f32, b.y as f32]),
            )
            .with_colors([colour])
            .with_radii([Radius::new_ui_points(4.0)])
            .with_draw_order(36.0),
        )?;
    }
    Ok(())
}

/// The tree's mega-cells, the cells STC cannot cover, and the tree.
pub(super) fn log_coverage(
    rec: &RecordingStream,
    name: &str,
    coverage: &CoverageTrace,
    colour: Color,
    faint: Color,
) -> RecordingStreamResult<()> {
    let boxes = |bs: &[Aabb]| {
        let centres: Vec<[f32; 2]> = bs
            .iter()
            .map(|b| {
                [
                    ((b.min.x + b.max.x) / 2.0) as f32,
                    ((b.min.y + b.max.y) / 2.0) as f32,
                ]
            })
            .collect();
        let halves: Vec<[f32; 2]> = bs
            .iter()
            .map(|b| [(b.width() / 2.0) as f32, (b.height() / 2.0) as f32])
            .collect();
        Boxes2D::from_centers_and_half_sizes(centres, halves)
    };
    if !coverage.mega_cells.is_empty() {
        rec.log_static(
            entity(&["plans", name, "mega_cells"]),
            &boxes(&coverage.mega_cells)
                .with_colors([faint])
                .with_draw_order(3.0),
        )?;
    }
    if !coverage.uncovered.is_empty() {
        rec.log_static(
            entity(&["plans", name, "uncovered"]),
            &boxes(&coverage.uncovered)
                .with_colors([rgb(OBSTACLE_GREY)])
                .with_draw_order(4.0),
        )?;
    }
    if !coverage.tree.is_empty() {
        rec.log_static(
            entity(&["plans", name, "tree"]),
            &LineStrips2D::new(coverage.tree.iter().map(|(a, b)| strip(&[*a, *b])))
                .with_colors([colour])
                .with_radii([Radius::new_ui_points(1.0)])
                .with_draw_order(28.0),
        )?;
    }
    Ok(())
}

/// The driven trajectory and the body along it on timeline `time`, at
/// most [`DRIVE_POSES`] poses evenly spread (the last one included).
pub(super) fn log_drive(
    rec: &RecordingStream,
    name: &str,
    drive: &DriveOutcome,
    shape: &RobotShape,
    mark: f64,
    colour: Color,
) -> RecordingStreamResult<()> {
    if drive.samples.is_empty() {
        return Ok(());
    }
    let xy: Vec<Point> = drive.samples.iter().map(|(_, c)| c.xy()).collect();
    rec.log_static(
        entity(&["plans", name, "drive", "path"]),
        &LineStrips2D::new([strip(&xy)])
            .with_colors([colour])
            .with_radii([Radius::new_ui_points(1.0)])
            .with_draw_order(31.0),
    )?;
    let body = entity(&["plans", name, "drive", "robot"]);
    for (t, c) in drive.thinned(DRIVE_POSES) {
        rec.set_duration_secs("time", t);
        let strips = robot_outline(shape, c, mark);
        rec.log(
            body.clone(),
            &LineStrips2D::new(strips.iter().map(|s| strip(s)))
                .with_colors([colour])
                .with_radii([Radius::new_ui_points(1.5)])
                .with_draw_order(41.0),
        )?;
    }
    rec.reset_time();
    Ok(())
}
