//! Streams a run to the Rerun viewer (SPEC 6), or saves it as an `.rrd`.
//!
//! One recording per scenario: application id `scen`, recording name the
//! scenario's title (its file stem when it has none). Entities:
//!
//! | entity | archetype | timeline |
//! |---|---|---|
//! | `world/bounds` | LineStrips2D, closed | static |
//! | `world/obstacles/NAME` | LineStrips2D (closed; disks as 64-gons), Boxes2D for a grid's blocked cells | static |
//! | `world/weights/NAME` | Points2D: a grid's weighted cells | static |
//! | `plans/NAME/path` | LineStrips2D: the path in (x, y) | static |
//! | `plans/NAME/unfinished` | LineStrips2D, faint: the motion of a plan that stopped short of the goal | static |
//! | `plans/NAME/cspace/path` | LineStrips3D: the path in (x, y, θ), θ in radians as z (rotating robots) | static |
//! | `plans/NAME/trail/B` | LineStrips2D: piece B of the path, drawn from the step where it starts (at most 100 pieces), so the path grows with the robot | `step` |
//! | `plans/NAME/robot` | LineStrips2D: the body at path configuration `i` (a point robot as a cross; at most 10 000 poses, evenly spread) | `step` = i |
//! | `plans/NAME/drive/path`, `plans/NAME/drive/robot` | LineStrips2D: a driven trajectory and the body along it | static, `time` (s) |
//! | `plans/NAME/LAYER` | the planner's drawable layers ([`crate::contract::layers`]): `search`, `grown`, `cspace/layer_K`, `roadmap`, `tree`, ... as each planner documents them | static or its timeline |
//! | `world/moving/NAME` | LineStrips2D: a moving obstacle's outline where it is (cleared when it vanishes) | `time` (s) |
//! | `world/moving/NAME/route` | LineStrips2D: its route through its waypoints | static |
//! | `plans/NAME/trajectory/robot` | LineStrips2D: a time-aware plan's robot where its trajectory has it | `time` (s) |
//! | `plans/NAME/agents/AGENT/path` | LineStrips2D: a team agent's path, in the agent's colour | static |
//! | `plans/NAME/agents/AGENT` | Points2D: where the agent is at each step (at most 50 000 positions in all, evenly spread steps) | `step` |
//! | `checks` | TextLog: `PASS`/`FAIL line N: expr  (values)` | `check` = index |
//!
//! Colours: obstacles grey, each plan its [`plan_colour`], failed checks red.
//! The automatic `log_time` timeline is switched off, so a recording only
//! has the timelines above.

use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;

use rerun::external::re_uri::RedapUri;
use rerun::{
    Arrows2D, Boxes2D, Color, EntityPath, EntityPathPart, LineStrips2D, LineStrips3D, Points2D,
    Radius, RecordingStream, RecordingStreamBuilder, RecordingStreamResult, SpawnError,
    SpawnOptions, TextLog, TextLogLevel,
};

use super::{
    FAIL_RED, MAX_WEIGHT_CELLS, OBSTACLE_GREY, ViewerError, ViewerTarget, blocked_boxes, closed,
    obstacle_outline, plan_colour, robot_outline, role_colour, weight_colour,
};
use crate::contract::MetricValue;
use crate::contract::layers::{Drawing, Layer};
use crate::geometry::{Config, Point, RobotShape, Shape};
use crate::run::{PlanRun, RunReport};
use crate::scenario::{Plan, Scenario};
use scen_runner::drive::DriveOutcome;

/// The most poses of a driven robot sent on timeline `time`.
pub(crate) const DRIVE_POSES: usize = 2_000;

/// The most pieces the progressively drawn path (`plans/NAME/trail/B`) is
/// sent in.
pub(crate) const TRAIL_BATCHES: usize = 100;

/// The most poses of the robot's body sent on timeline `step`.
pub(crate) const ROBOT_POSES: usize = 10_000;

/// How long a TCP connection to the viewer may take before it counts as
/// unreachable.
const PROBE_TIMEOUT: Duration = Duration::from_secs(1);

/// How long the final flush may wait for a connected viewer to take the data.
const FLUSH_TIMEOUT: Duration = Duration::from_secs(30);

/// Streams the run to `target` and waits until the data has left (written
/// to the file, or received by the viewer's server).
///
/// Errors are returned, never panics, so the caller can warn once and
/// continue. An unreachable viewer is detected with a TCP probe before any
/// data is produced (the SDK itself would silently buffer and retry), so
/// `Connect` fails within about a second; `Spawn` may wait a few seconds
/// for a starting viewer to listen.
pub fn stream(report: &RunReport, target: &ViewerTarget) -> Result<(), ViewerError> {
    let builder = RecordingStreamBuilder::new("scen")
        .recording_name(recording_name(&report.scenario))
        // The user asked for the stream: the `RERUN` variable does not veto it.
        .enabled(true);
    let stream_error = |e: rerun::RecordingStreamError| ViewerError::Stream(e.to_string());
    let rec = match target {
        ViewerTarget::Save(path) => builder.save(path).map_err(|e| ViewerError::Save {
            path: path.clone(),
            message: e.to_string(),
        })?,
        ViewerTarget::Spawn => {
            let url = spawn_viewer()?;
            builder.connect_grpc_opts(url).map_err(stream_error)?
        }
        ViewerTarget::Connect(addr) => {
            let url = proxy_url(addr.as_deref())?;
            if !listening(&url) {
                return Err(ViewerError::Unreachable { url });
            }
            builder.connect_grpc_opts(url).map_err(stream_error)?
        }
    };
    rec.set_log_time_enabled(false);
    log_report(&rec, report).map_err(stream_error)?;
    rec.flush_with_timeout(FLUSH_TIMEOUT)
        .map_err(|e| ViewerError::Stream(e.to_string()))?;
    if let ViewerTarget::Save(_) = target {
        // Writes the file's footer now rather than when `rec` is dropped.
        rec.finalize_deferred_sinks();
    }
    Ok(())
}

/// The scenario's title, or its file's stem.
fn recording_name(scenario: &Scenario) -> String {
    scenario.title.clone().unwrap_or_else(|| {
        scenario.file.file_stem().map_or_else(
            || scenario.file.display().to_string(),
            |s| s.to_string_lossy().into(),
        )
    })
}

/// Starts the viewer (or finds one on the default port) and returns its
/// URL once it listens.
fn spawn_viewer() -> Result<String, ViewerError> {
    let opts = SpawnOptions {
        wait_for_bind: true,
        hide_welcome_screen: true,
        ..SpawnOptions::default()
    };
    let spawned = rerun::spawn(&opts).map_err(|e| match e {
        SpawnError::ExecutableNotFoundInPath { .. } | SpawnError::ExecutableNotFound { .. } => {
            ViewerError::ViewerMissing
        }
        SpawnError::Io(e) => ViewerError::Spawn(e.to_string()),
    })?;
    let url = format!("rerun+http://127.0.0.1:{}/proxy", spawned.port);
    if listening(&url) {
        Ok(url)
    } else {
        Err(ViewerError::Spawn(format!(
            "`rerun` was started but is not listening on port {} \
             (it may have failed to open a window)",
            spawned.port
        )))
    }
}

/// The proxy URL for a `--connect` address (see [`ViewerTarget::Connect`]).
fn proxy_url(addr: Option<&str>) -> Result<String, ViewerError> {
    let Some(addr) = addr.map(str::trim).filter(|a| !a.is_empty()) else {
        return Ok(rerun::DEFAULT_CONNECT_URL.to_string());
    };
    let mut url = if addr.contains("://") {
        addr.to_string()
    } else {
        format!("rerun+http://{addr}")
    };
    if !url.ends_with("/proxy") {
        url = format!("{}/proxy", url.trim_end_matches('/'));
    }
    match url.parse::<RedapUri>() {
        Ok(RedapUri::Proxy(_)) => Ok(url),
        _ => Err(ViewerError::BadAddress(addr.to_string())),
    }
}

/// Whether something accepts TCP connections at the URL's host and port.
fn listening(url: &str) -> bool {
    let Ok(RedapUri::Proxy(proxy)) = url.parse::<RedapUri>() else {
        return false;
    };
    let host = proxy.origin.format_host();
    let Ok(addrs) = format!("{host}:{}", proxy.origin.port).to_socket_addrs() else {
        return false;
    };
    addrs
        .into_iter()
        .any(|a| TcpStream::connect_timeout(&a, PROBE_TIMEOUT).is_ok())
}

fn log_report(rec: &RecordingStream, report: &RunReport) -> RecordingStreamResult<()> {
    let scenario = &report.scenario;
    log_world(rec, scenario)?;
    let mut runs: Vec<(&Plan, &PlanRun)> = report
        .plans
        .iter()
        .filter_map(|run| Some((scenario.plans.get(run.plan)?, run)))
        .collect();
    runs.sort_by_key(|(_, run)| run.plan);
    for &(plan, run) in &runs {
        log_plan(rec, scenario, plan, run)?;
    }
    log_time(rec, scenario, &runs)?;
    log_checks(rec, report)
}

fn log_world(rec: &RecordingStream, scenario: &Scenario) -> RecordingStreamResult<()> {
    let grey = rgb(OBSTACLE_GREY);
    rec.log_static(
        "world/bounds",
        &LineStrips2D::new([strip(&closed(scenario.world.bounds.corners().to_vec()))])
            .with_colors([rgb(OBSTACLE_GREY.map(|c| c / 2))])
            .with_draw_order(5.0),
    )?;
    for obstacle in &scenario.world.obstacles {
        let path = entity(&["world", "obstacles", &obstacle.name]);
        if let Shape::Grid(grid) = &obstacle.shape {
            let boxes = blocked_boxes(grid);
            let centres = boxes.iter().map(|b| {
                [
                    ((b.min.x + b.max.x) / 2.0) as f32,
                    ((b.min.y + b.max.y) / 2.0) as f32,
                ]
            });
            let halves = boxes
                .iter()
                .map(|b| [(b.width() / 2.0) as f32, (b.height() / 2.0) as f32]);
            rec.log_static(
                path,
                &Boxes2D::from_centers_and_half_sizes(centres, halves)
                    .with_colors([grey])
                    .with_draw_order(10.0),
            )?;
            // Weights as coloured discs, one per cell (Boxes2D has no fill).
            let weighted: Vec<([f32; 2], u8)> = if grid.cells.len() <= MAX_WEIGHT_CELLS {
                (0..grid.height)
                    .flat_map(|row| (0..grid.width).map(move |col| (col, row)))
                    .filter(|&(col, row)| grid.weight(col, row) >= 2)
                    .map(|(col, row)| {
                        let b = grid.cell_box(col, row);
                        let c = [
                            ((b.min.x + b.max.x) / 2.0) as f32,
                            ((b.min.y + b.max.y) / 2.0) as f32,
                        ];
                        (c, grid.weight(col, row))
                    })
                    .collect()
            } else {
                Vec::new()
            };
            if !weighted.is_empty() {
                rec.log_static(
                    entity(&["world", "weights", &obstacle.name]),
                    &Points2D::new(weighted.iter().map(|(c, _)| *c))
                        .with_colors(weighted.iter().map(|(_, w)| {
                            let [r, g, b, a] = weight_colour(*w);
                            Color::from_unmultiplied_rgba(r, g, b, a)
                        }))
                        .with_radii([Radius::new_scene_units((grid.cell / 2.0) as f32)])
                        .with_draw_order(1.0),
                )?;
            }
        } else {
            let strips = obstacle_outline(&obstacle.shape);
            rec.log_static(
                path,
                &LineStrips2D::new(strips.iter().map(|s| strip(s)))
                    .with_colors([grey])
                    .with_radii([Radius::new_ui_points(1.5)])
                    .with_draw_order(10.0),
            )?;
        }
    }
    Ok(())
}

fn log_plan(
    rec: &RecordingStream,
    scenario: &Scenario,
    plan: &Plan,
    run: &PlanRun,
) -> RecordingStreamResult<()> {
    let [r, g, b] = plan_colour(run.plan);
    let colour = rgb([r, g, b]);
    let faint = Color::from_unmultiplied_rgba(r, g, b, 110);
    let name = plan.name.as_str();
    for layer in &run.outcome.layers {
        log_layer(rec, name, layer, run.plan)?;
    }
    rec.reset_time();
    let bounds = scenario.world.bounds;
    // A point robot is drawn as a cross 1% of the world's size.
    let mark = 0.01 * bounds.width().max(bounds.height());
    if let (Some(drive), Some(robot)) = (&run.drive, scenario.robots.get(plan.robot)) {
        log_drive(rec, name, drive, &robot.shape, mark, colour)?;
    }

    if let (Some(team), Some(paths)) = (plan.team(scenario), &run.outcome.agents) {
        return log_team(rec, name, team, paths, run.outcome.agent_times.as_deref());
    }
    let trajectory = &run.outcome.trajectory;
    if trajectory.len() > 1 {
        let xy: Vec<Point> = trajectory.iter().map(Config::xy).collect();
        rec.log_static(
            entity(&["plans", name, "unfinished"]),
            &LineStrips2D::new([strip(&xy)])
                .with_colors([faint])
                .with_radii([Radius::new_ui_points(1.5)])
                .with_draw_order(30.0),
        )?;
    }
    let Some(path) = run.outcome.path.as_deref().filter(|p| !p.is_empty()) else {
        return Ok(());
    };
    let xy: Vec<Point> = path.iter().map(Config::xy).collect();
    rec.log_static(
        entity(&["plans", name, "path"]),
        &LineStrips2D::new([strip(&xy)])
            .with_colors([colour])
            .with_radii([Radius::new_ui_points(2.5)])
            .with_draw_order(30.0),
    )?;

    let Some(robot) = scenario.robots.get(plan.robot) else {
        return Ok(());
    };
    if robot.shape.rotates() {
        rec.log_static(
            entity(&["plans", name, "cspace", "path"]),
            &LineStrips3D::new(cspace_strips(path)).with_colors([colour]),
        )?;
    }
    // The path drawn progressively: batch B is its own entity, logged at
    // the step where it starts, so at step k everything up to k shows.
    let batch = path.len().div_ceil(TRAIL_BATCHES).max(1);
    for start in (0..path.len().saturating_sub(1)).step_by(batch) {
        let end = (start + batch).min(path.len() - 1);
        rec.set_time_sequence("step", start as i64);
        rec.log(
            entity(&["plans", name, "trail", &format!("{:04}", start / batch)]),
            &LineStrips2D::new([strip(&xy[start..=end])])
                .with_colors([colour])
                .with_radii([Radius::new_ui_points(2.0)])
                .with_draw_order(29.0),
        )?;
    }
    let body = entity(&["plans", name, "robot"]);
    // Every step of the path, or evenly spread ones (the last included)
    // when it has more than ROBOT_POSES.
    let every = path.len().div_ceil(ROBOT_POSES).max(1);
    let last = path.len() - 1;
    let steps = (0..path.len())
        .step_by(every)
        .chain((!last.is_multiple_of(every)).then_some(last));
    for step in steps {
        let c = path[step];
        rec.set_time_sequence("step", step as i64);
        let strips = robot_outline(&robot.shape, c, mark);
        rec.log(
            body.clone(),
            &LineStrips2D::new(strips.iter().map(|s| strip(s)))
                .with_colors([colour])
                .with_radii([Radius::new_ui_points(1.5)])
                .with_draw_order(40.0),
        )?;
    }
    rec.reset_time();
    Ok(())
}

/// The most agent positions a team plan sends on timeline `step`.
pub(crate) const TEAM_POSITIONS: usize = 50_000;

/// A team plan (SPEC 2.10): each agent's path, static, and the agent at
/// each step (every `stride`-th step and the last when the team would send
/// more than [`TEAM_POSITIONS`] positions); a continuous team's agents at
/// their points' times on timeline `time`.
fn log_team(
    rec: &RecordingStream,
    name: &str,
    team: &[crate::contract::Agent],
    paths: &[Vec<Point>],
    times: Option<&[Vec<f64>]>,
) -> RecordingStreamResult<()> {
    let steps = paths.iter().map(Vec::len).max().unwrap_or(0);
    let stride = (team.len() * steps).div_ceil(TEAM_POSITIONS).max(1);
    for (k, (agent, path)) in team.iter().zip(paths).enumerate() {
        let colour = rgb(super::agent_colour(k));
        let at = entity(&["plans", name, "agents", &agent.name]);
        rec.log_static(
            entity(&["plans", name, "agents", &agent.name, "path"]),
            &LineStrips2D::new([strip(path)])
                .with_colors([colour])
                .with_radii([Radius::new_ui_points(1.5)])
                .with_draw_order(30.0),
        )?;
        let last = steps.saturating_sub(1);
        let shown = (0..steps)
            .step_by(stride)
            .chain((!last.is_multiple_of(stride)).then_some(last));
        for step in shown {
            let k_at = step.min(path.len().saturating_sub(1));
            let Some(&p) = path.get(k_at) else {
                continue;
            };
            match times.and_then(|t| t.get(k)) {
                Some(t) if step < path.len() => rec.set_duration_secs("time", t[k_at]),
                Some(_) => continue,
                None => rec.set_time_sequence("step", step as i64),
            }
            rec.log(
                at.clone(),
                &Points2D::new([[p.x as f32, p.y as f32]])
                    .with_colors([colour])
                    .with_radii([Radius::new_ui_points(5.0)])
                    .with_draw_order(40.0),
            )?;
        }
    }
    rec.reset_time();
    Ok(())
}

/// The largest turn of one edge of a [`Drawing::Rounded`] region's arcs in
/// the viewer, as its circles ([`super::CIRCLE_VERTICES`]).
const ROUNDED_TURN: f64 = std::f64::consts::TAU / super::CIRCLE_VERTICES as f64;

/// One layer of a plan (see [`crate::contract::layers`]): its drawing
/// as the matching archetype, at its timeline index or static.
fn log_layer(
    rec: &RecordingStream,
    plan: &str,
    layer: &Layer,
    plan_index: usize,
) -> RecordingStreamResult<()> {
    if layer.drawing.is_empty() {
        return Ok(());
    }
    let mut parts = vec!["plans", plan];
    parts.extend(layer.entity.split('/'));
    let path = entity(&parts);
    let style = layer.style;
    let [r, g, b, a] = role_colour(style.colour, plan_index);
    let colour = Color::from_unmultiplied_rgba(r, g, b, a);
    let radius = (style.width > 0.0).then(|| Radius::new_ui_points(style.width));
    let log = |archetype: &dyn rerun::AsComponents| match layer.time {
        Some((timeline, at)) => {
            rec.set_time_sequence(timeline.name(), at);
            rec.log(path.clone(), archetype)
        }
        None => rec.log_static(path.clone(), archetype),
    };
    let strips2 = |strips: Vec<Vec<[f32; 2]>>| {
        let mut a = LineStrips2D::new(strips)
            .with_colors([colour])
            .with_draw_order(style.order);
        if let Some(r) = radius {
            a = a.with_radii([r]);
        }
        a
    };
    match &layer.drawing {
        Drawing::Segments(segments) => log(&strips2(
            segments.iter().map(|(a, b)| strip(&[*a, *b])).collect(),
        )),
        Drawing::Polylines(lines) => log(&strips2(lines.iter().map(|l| strip(l)).collect())),
        Drawing::Polygons(outlines) => log(&strips2(
            outlines.iter().map(|o| strip(&closed(o.clone()))).collect(),
        )),
        // The viewer has no arcs: fine polygons around the exact regions.
        Drawing::Rounded(regions) => log(&strips2(
            regions
                .iter()
                .map(|r| strip(&closed(r.outline(ROUNDED_TURN))))
                .collect(),
        )),
        Drawing::Boxes(boxes) => {
            let centres = boxes.iter().map(|b| {
                [
                    ((b.min.x + b.max.x) / 2.0) as f32,
                    ((b.min.y + b.max.y) / 2.0) as f32,
                ]
            });
            let halves = boxes
                .iter()
                .map(|b| [(b.width() / 2.0) as f32, (b.height() / 2.0) as f32]);
            log(&Boxes2D::from_centers_and_half_sizes(centres, halves)
                .with_colors([colour])
                .with_draw_order(style.order))
        }
        Drawing::Points(points) => {
            let mut a = Points2D::new(points.iter().map(|p| [p.x as f32, p.y as f32]))
                .with_colors([colour])
                .with_draw_order(style.order);
            if let Some(r) = radius {
                a = a.with_radii([r]);
            }
            log(&a)
        }
        Drawing::Arrows(arrows) => log(&Arrows2D::from_vectors(
            arrows.iter().map(|(_, v)| [v.x as f32, v.y as f32]),
        )
        .with_origins(arrows.iter().map(|(p, _)| [p.x as f32, p.y as f32]))
        .with_colors([colour])
        .with_draw_order(style.order)),
        Drawing::Text(text) => log(&TextLog::new(text.as_str()).with_level(TextLogLevel::INFO)),
        Drawing::Polylines3D(strips) => log(&LineStrips3D::new(strips.iter().map(|s| {
            s.iter()
                .map(|p| [p[0] as f32, p[1] as f32, p[2] as f32])
                .collect::<Vec<_>>()
        }))
        .with_colors([colour])),
    }
}

/// The most instants of timeline `time` at which one moving obstacle or
/// the robot of one time-aware plan is sent (SPEC 2.9)...
pub(crate) const TIME_SAMPLES: usize = 2_000;

/// ... and the most for all of them together, so that a world of hundreds
/// of carts makes a recording of megabytes, not gigabytes.
pub(crate) const TIME_SAMPLES_IN_ALL: usize = 50_000;

/// Time (SPEC 2.9) on timeline `time`: every moving obstacle, and the robot
/// of every plan with a trajectory, at up to [`TIME_SAMPLES`] instants
/// evenly spread from 0 to a second after the last thing moves, plus each
/// trajectory's own points.
fn log_time(
    rec: &RecordingStream,
    scenario: &Scenario,
    runs: &[(&Plan, &PlanRun)],
) -> RecordingStreamResult<()> {
    use crate::geometry::timed::{MovingShape, Timed, robot_at};
    let timed: Vec<(&Plan, &PlanRun, Vec<Timed>)> = runs
        .iter()
        .filter_map(|&(plan, run)| Some((plan, run, run.outcome.timed()?)))
        .collect();
    if scenario.moving.is_empty() && timed.is_empty() {
        return Ok(());
    }
    let end = scenario
        .moving
        .iter()
        .map(|o| o.settles())
        .chain(timed.iter().filter_map(|(_, _, p)| p.last().map(|p| p.t)))
        .fold(0.0, f64::max)
        + 1.0;
    let movers = scenario.moving.len() + timed.len();
    let samples = (TIME_SAMPLES_IN_ALL / movers.max(1)).clamp(10, TIME_SAMPLES);
    let instants: Vec<f64> = (0..=samples)
        .map(|k| end * k as f64 / samples as f64)
        .collect();
    let grey = rgb(OBSTACLE_GREY);
    for o in &scenario.moving {
        let path = entity(&["world", "moving", &o.name]);
        let route: Vec<Point> = o.route.iter().map(|w| w.at).collect();
        rec.log_static(
            entity(&["world", "moving", &o.name, "route"]),
            &LineStrips2D::new([strip(&route)])
                .with_colors([Color::from_unmultiplied_rgba(90, 90, 90, 140)])
                .with_radii([Radius::new_ui_points(1.0)])
                .with_draw_order(6.0),
        )?;
        // The route's own times too, so each waypoint is met exactly.
        let mut at: Vec<f64> = instants.clone();
        at.extend(o.route.iter().map(|w| w.t).filter(|t| *t < end));
        at.sort_by(f64::total_cmp);
        at.dedup();
        for t in at {
            rec.set_duration_secs("time", t);
            let Some(p) = o.position(t) else {
                rec.log(path.clone(), &rerun::Clear::flat())?;
                break;
            };
            let strips: Vec<Vec<Point>> = match &o.shape {
                MovingShape::Disk(r) => {
                    vec![closed(super::circle_polygon(p, *r, super::CIRCLE_VERTICES))]
                }
                MovingShape::Pieces(pieces) => pieces
                    .iter()
                    .map(|piece| closed(piece.iter().map(|v| p + v.coords).collect()))
                    .collect(),
            };
            rec.log(
                path.clone(),
                &LineStrips2D::new(strips.iter().map(|s| strip(s)))
                    .with_colors([grey])
                    .with_radii([Radius::new_ui_points(1.5)])
                    .with_draw_order(11.0),
            )?;
        }
    }
    let bounds = scenario.world.bounds;
    let mark = 0.01 * bounds.width().max(bounds.height());
    for (plan, run, points) in &timed {
        let Some(robot) = scenario.robots.get(plan.robot) else {
            continue;
        };
        let body = entity(&["plans", &plan.name, "trajectory", "robot"]);
        let mut at: Vec<f64> = instants.clone();
        at.extend(points.iter().map(|p| p.t));
        at.sort_by(f64::total_cmp);
        at.dedup();
        for t in at {
            rec.set_duration_secs("time", t);
            let strips = robot_outline(&robot.shape, robot_at(points, t), mark);
            rec.log(
                body.clone(),
                &LineStrips2D::new(strips.iter().map(|s| strip(s)))
                    .with_colors([rgb(plan_colour(run.plan))])
                    .with_radii([Radius::new_ui_points(1.5)])
                    .with_draw_order(41.0),
            )?;
        }
    }
    rec.reset_time();
    Ok(())
}

/// The driven trajectory and the body along it on timeline `time`, at
/// most [`DRIVE_POSES`] poses evenly spread (the last one included).
fn log_drive(
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

/// The path in (x, y, θ), cut where θ wraps around (a jump of more than
/// π between neighbours), so the strip does not cross the whole θ range.
fn cspace_strips(path: &[Config]) -> Vec<Vec<[f32; 3]>> {
    let mut strips: Vec<Vec<[f32; 3]>> = Vec::new();
    let mut previous: Option<f64> = None;
    for c in path {
        let wraps = previous.is_some_and(|t| (c.theta - t).abs() > std::f64::consts::PI);
        if wraps || strips.is_empty() {
            strips.push(Vec::new());
        }
        if let Some(current) = strips.last_mut() {
            current.push([c.x as f32, c.y as f32, c.theta as f32]);
        }
        previous = Some(c.theta);
    }
    strips
}

/// One TextLog entry per check, on timeline `check` (the check's index):
/// `PASS line 23: a.cost <= 90  (a.cost = 79.1)`, failures as errors in red.
fn log_checks(rec: &RecordingStream, report: &RunReport) -> RecordingStreamResult<()> {
    for (index, outcome) in report.checks.iter().enumerate() {
        let Some(check) = report.scenario.checks.get(outcome.check) else {
            continue;
        };
        let values: Vec<String> = outcome
            .values
            .iter()
            .map(|(name, value)| match value {
                MetricValue::Bool(b) => format!("{name} = {b}"),
                MetricValue::Num(x) => format!("{name} = {x}"),
            })
            .collect();
        let verdict = if outcome.passed { "PASS" } else { "FAIL" };
        let mut text = format!("{verdict} line {}: {}", check.line, check.text);
        if !values.is_empty() {
            text = format!("{text}  ({})", values.join(", "));
        }
        let entry = if outcome.passed {
            TextLog::new(text).with_level(TextLogLevel::INFO)
        } else {
            TextLog::new(text)
                .with_level(TextLogLevel::ERROR)
                .with_color(rgb(FAIL_RED))
        };
        rec.set_time_sequence("check", index as i64);
        rec.log("checks", &entry)?;
    }
    rec.reset_time();
    Ok(())
}

/// An entity path from parts taken literally (names need no escaping).
pub(super) fn entity(parts: &[&str]) -> EntityPath {
    EntityPath::new(parts.iter().map(|&p| EntityPathPart::new(p)).collect())
}

pub(super) fn strip(points: &[Point]) -> Vec<[f32; 2]> {
    points.iter().map(|p| [p.x as f32, p.y as f32]).collect()
}

pub(super) fn rgb([r, g, b]: [u8; 3]) -> Color {
    Color::from_rgb(r, g, b)
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;
    use std::path::PathBuf;

    use super::*;
    use crate::contract::PlanOutcome;
    use crate::contract::Robot;
    use crate::contract::layers;
    use crate::diagnostics::{SourceMap, Span};
    use crate::geometry::{Aabb, ConvexPolygon, Grid, Obstacle, RobotShape, World};
    use crate::run::CheckOutcome;
    use crate::scenario::Check;
    use crate::syntax::ast::{Expr, ExprKind};

    fn plan(name: &str, robot: usize) -> Plan {
        let planner = crate::planners::registry::PLANNERS[0];
        let (start, goal) = (Config::new(1.0, 1.0, 0.0), Config::new(9.0, 4.0, 0.0));
        Plan::fixture(name, planner, robot, start, Some(goal))
    }

    /// A rod and a point robot among a rectangle, a disk, a wall and a
    /// grid; 250 expansions; one check passed and one failed.
    fn report() -> RunReport {
        let rod = ConvexPolygon {
            vertices: vec![
                Point::new(-1.0, -0.1),
                Point::new(1.0, -0.1),
                Point::new(1.0, 0.1),
                Point::new(-1.0, 0.1),
            ],
        };
        let obstacle = |name: &str, shape| Obstacle {
            name: name.into(),
            shape,
        };
        let scenario = Scenario {
            benches: Vec::new(),
            file: PathBuf::from("scenarios/demo.scen"),
            title: Some("Demo: the rod".into()),
            world: World {
                bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(10.0, 5.0)),
                obstacles: vec![
                    obstacle(
                        "box",
                        Shape::Rect(Aabb::from_corners(
                            Point::new(4.0, 0.0),
                            Point::new(5.0, 2.0),
                        )),
                    ),
                    obstacle(
                        "disk",
                        Shape::Disk {
                            center: Point::new(7.0, 3.0),
                            radius: 0.5,
                        },
                    ),
                    obstacle(
                        "wall",
                        Shape::Segment(Point::new(2.0, 3.0), Point::new(3.0, 5.0)),
                    ),
                    obstacle(
                        "map",
                        Shape::Grid(Grid {
                            cell: 0.5,
                            origin: Point::new(8.0, 0.0),
                            width: 2,
                            height: 2,
                            cells: vec![0, 1, 0, 0],
                        }),
                    ),
                ],
            },
            obstacle_spans: Vec::new(),
            moving: Vec::new(),
            moving_spans: Vec::new(),
            family: None,
            template: None,
            robots: vec![
                Robot {
                    name: "rod".into(),
                    shape: RobotShape::Polygon(rod),
                    steering: None,
                    speed: None,
                    team: None,
                    span: Span::default(),
                },
                Robot {
                    name: "dot".into(),
                    shape: RobotShape::Point,
                    steering: None,
                    speed: None,
                    team: None,
                    span: Span::default(),
                },
            ],
            plans: vec![plan("offline", 0), plan("dot", 1)],
            checks: vec![Check {
                bench: false,
                expr: Expr {
                    kind: ExprKind::Bool(true),
                    span: Span::default(),
                },
                text: "offline.cost <= 90".into(),
                line: 23,
                span: Span::default(),
            }],
            sources: SourceMap::default(),
        };
        let path = vec![
            Config::new(1.0, 1.0, 0.0),
            Config::new(3.0, 2.5, 3.0),
            Config::new(6.0, 2.5, -3.0),
            Config::new(9.0, 4.0, 0.0),
        ];
        let expansions: Vec<Point> = (0..250)
            .map(|i| Point::new(f64::from(i % 10), f64::from(i / 50)))
            .collect();
        let mut layers = layers::search(&expansions);
        layers.extend(layers::grown(vec![vec![
            Point::new(3.5, 0.0),
            Point::new(5.5, 0.0),
            Point::new(5.5, 2.5),
        ]]));
        let run = |plan, path| PlanRun {
            plan,
            outcome: PlanOutcome {
                path,
                layers: layers.clone(),
                ..PlanOutcome::default()
            },
            metrics: BTreeMap::new(),
            validation: None,
            drive: None,
        };
        RunReport {
            bench_runs: Vec::new(),
            skipped: Vec::new(),
            scenario,
            plans: vec![run(1, Some(path.clone())), run(0, Some(path))],
            checks: vec![
                CheckOutcome {
                    series: Default::default(),
                    check: 0,
                    passed: true,
                    values: [("offline.cost".to_string(), MetricValue::Num(79.1))].into(),
                },
                CheckOutcome {
                    series: Default::default(),
                    check: 0,
                    passed: false,
                    values: [("offline.found".to_string(), MetricValue::Bool(false))].into(),
                },
            ],
        }
    }

    fn temp_rrd(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("scen-{}-{name}.rrd", std::process::id()))
    }

    #[test]
    fn saves_a_non_empty_rrd() {
        let path = temp_rrd("save");
        let result = stream(&report(), &ViewerTarget::Save(path.clone()));
        assert!(result.is_ok(), "{result:?}");
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        let _ = std::fs::remove_file(&path);
        assert!(size > 0, "empty recording");
    }

    /// Every kind of drawing, static or on a timeline, and a driven robot
    /// go into the recording under the plan's entities (the entities of
    /// each planner are checked with `rerun rrd print` in tests/outputs.rs
    /// on the real scenarios).
    #[test]
    fn saves_every_kind_of_layer() {
        use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg, Timeline};
        use crate::geometry::Vector;
        use scen_runner::drive::DriveOutcome;
        let mut r = report();
        let p = |x: f64, y: f64| Point::new(x, y);
        let style = Style::new(Colour::Plan, 1.0, 20.0).svg(Svg::line(1.0));
        let drawings = [
            (
                "segments",
                Drawing::Segments(vec![(p(0.0, 0.0), p(1.0, 1.0))]),
            ),
            (
                "lines",
                Drawing::Polylines(vec![vec![p(0.0, 0.0), p(1.0, 1.0), p(2.0, 0.0)]]),
            ),
            (
                "outlines",
                Drawing::Polygons(vec![vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)]]),
            ),
            (
                "boxes",
                Drawing::Boxes(vec![Aabb::from_corners(p(0.0, 0.0), p(2.0, 2.0))]),
            ),
            ("points", Drawing::Points(vec![p(1.0, 1.0)])),
            (
                "arrows",
                Drawing::Arrows(vec![(p(1.0, 1.0), Vector::new(0.5, 0.0))]),
            ),
            ("note", Drawing::Text("a note".into())),
            (
                "deep/in/3d",
                Drawing::Polylines3D(vec![vec![[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]]),
            ),
            (
                "rounded",
                Drawing::Rounded(vec![
                    layers::Rounded::new(&[p(1.0, 1.0)], 0.5),
                    layers::Rounded::new(&[p(3.0, 1.0), p(4.0, 1.0), p(3.5, 2.0)], 0.25),
                ]),
            ),
        ];
        let timelines = [Timeline::Step, Timeline::Expansion, Timeline::Iteration];
        for (k, (entity, drawing)) in drawings.into_iter().enumerate() {
            let layer = Layer::new(entity, drawing, style);
            r.plans[0].outcome.layers.push(match k % 4 {
                3 => layer,
                i => layer.at(timelines[i], k as i64),
            });
        }
        r.plans[0].drive = Some(DriveOutcome {
            samples: (0..5000)
                .map(|i| {
                    (
                        f64::from(i) * 0.01,
                        Config::new(f64::from(i) * 1e-3, 0.5, 0.0),
                    )
                })
                .collect(),
            time: 49.99,
            max_deviation: 0.0,
            completed: true,
        });
        let path = temp_rrd("extras");
        let result = stream(&r, &ViewerTarget::Save(path.clone()));
        assert!(result.is_ok(), "{result:?}");
        // The viewer's own reader lists the entities (when it is installed:
        // scripts/test.sh puts it in target/rerun-venv; CI must have it).
        let rerun = std::env::var_os("SCEN_RERUN")
            .map(PathBuf::from)
            .unwrap_or_else(|| {
                PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/rerun-venv/bin/rerun")
            });
        if !rerun.exists() {
            assert_ne!(
                std::env::var("CI").as_deref(),
                Ok("true"),
                "CI must have rerun"
            );
            let _ = std::fs::remove_file(&path);
            return;
        }
        let print = std::process::Command::new(&rerun)
            .args(["rrd", "print"])
            .arg(&path)
            .output()
            .expect("rerun runs");
        let _ = std::fs::remove_file(&path);
        let text = String::from_utf8_lossy(&print.stdout);
        for e in [
            "/plans/dot/segments ",
            "/plans/dot/lines ",
            "/plans/dot/outlines ",
            "/plans/dot/boxes ",
            "/plans/dot/points ",
            "/plans/dot/arrows ",
            "/plans/dot/note ",
            "/plans/dot/deep/in/3d ",
            "/plans/dot/rounded ",
            "/plans/dot/search ",
            "/plans/dot/grown ",
            "/plans/dot/drive/path ",
            "/plans/dot/drive/robot ",
        ] {
            assert!(text.contains(e), "no {e} in:\n{text}");
        }
    }

    #[test]
    fn unwritable_path_is_an_error() {
        let path = PathBuf::from("/nonexistent-scen-dir/out.rrd");
        let result = stream(&report(), &ViewerTarget::Save(path));
        assert!(
            matches!(result, Err(ViewerError::Save { .. })),
            "{result:?}"
        );
    }

    #[test]
    fn unreachable_viewer_fails_fast() {
        // A port that was free a moment ago: nothing listens there.
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .map(|a| a.port())
            .unwrap_or(1);
        let started = std::time::Instant::now();
        let target = ViewerTarget::Connect(Some(format!("127.0.0.1:{port}")));
        let result = stream(&report(), &target);
        assert!(
            matches!(result, Err(ViewerError::Unreachable { .. })),
            "{result:?}"
        );
        assert!(started.elapsed() < Duration::from_secs(3));
    }

    #[test]
    fn connect_addresses_become_proxy_urls() {
        let url = |a: Option<&str>| proxy_url(a).map_err(|e| e.to_string());
        assert_eq!(
            url(None),
            Ok("rerun+http://127.0.0.1:9876/proxy".to_string())
        );
        assert_eq!(
            url(Some("127.0.0.1:9000")),
            Ok("rerun+http://127.0.0.1:9000/proxy".into())
        );
        assert_eq!(
            url(Some("rerun+http://localhost:9877/proxy")),
            Ok("rerun+http://localhost:9877/proxy".into())
        );
        assert_eq!(
            url(Some("rerun+http://localhost:9877/")),
            Ok("rerun+http://localhost:9877/proxy".into())
        );
        assert_eq!(url(Some(" ")), url(None));
        assert!(url(Some("ftp://x")).is_err());
    }

    #[test]
    fn cspace_path_is_cut_where_theta_wraps() {
        let path = [
            Config::new(0.0, 0.0, 0.0),
            Config::new(1.0, 0.0, 3.0),
            Config::new(2.0, 0.0, -3.0),
            Config::new(3.0, 0.0, -2.5),
        ];
        let strips = cspace_strips(&path);
        assert_eq!(strips.iter().map(Vec::len).collect::<Vec<_>>(), [2, 2]);
    }

    #[test]
    fn recording_name_falls_back_to_the_file_stem() {
        let mut scenario = report().scenario;
        assert_eq!(recording_name(&scenario), "Demo: the rod");
        scenario.title = None;
        assert_eq!(recording_name(&scenario), "demo");
    }
}
