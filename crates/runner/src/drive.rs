//! Driving a path (SPEC 3.6, 3.8): a simulated robot follows any planner's
//! path. Two models ([`Model`]): `unicycle`, a differential-drive robot
//! with a go-to-orientation and a go-to-cell loop (SEEDS.md §F), and
//! `pure_pursuit` ([`pure_pursuit`]), which follows the path continuously
//! (a car's with its curvature bound and its cusps). Independent of the
//! planner that made the path: they see only its configurations (and a
//! car's segments).
//!
//! `unicycle`: for each path point after the first, the robot first turns in place
//! (ω = turn_gain · heading error, at most `max_turn_rate`) until its
//! heading points at the target within `align`; then it drives with
//! v = min(gain · distance, max_speed) · max(cos(heading error), 0) while
//! steering with the same turn law, until it is within `reach` of the
//! target. The state (x, y, θ) is integrated with forward Euler at a fixed
//! `dt`.

pub mod pure_pursuit;

use std::collections::BTreeMap;

use crate::contract::schema::{DefaultValue, ParamSpec, UNICYCLE_PARAMS};
use crate::contract::{Param, ParamValue};
use crate::geometry::car::CarPath;
use crate::geometry::polygon::distance_point_segment;
use crate::geometry::{Config, angle_diff};

pub use pure_pursuit::PurePursuit;

/// The most simulated steps of one drive; a drive that needs more stops
/// there, unfinished.
pub const MAX_DRIVE_STEPS: usize = 2_000_000;

/// A validated block's numeric value of `key`: as given, or its default in
/// `specs` (the model's schema); `None` for a key without a numeric
/// default that was not given.
pub(crate) fn block_value(
    specs: &[ParamSpec],
    block: &BTreeMap<&'static str, Param>,
    key: &str,
) -> Option<f64> {
    match block.get(key).map(|p| &p.value) {
        Some(ParamValue::Num(x)) => Some(*x),
        _ => match specs.iter().find(|p| p.key == key).map(|p| p.default) {
            Some(DefaultValue::Num(x, _)) => Some(x),
            _ => None,
        },
    }
}

/// The model of a validated `drive MODEL { ... }` and its settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Model {
    Unicycle(Unicycle),
    PurePursuit(PurePursuit),
}

impl Model {
    /// The settings of `drive model { block }` (the analyzer checked the
    /// model and the keys).
    pub fn from_block(model: &str, block: &BTreeMap<&'static str, Param>) -> Self {
        match model {
            "pure_pursuit" => Model::PurePursuit(PurePursuit::from_block(block)),
            _ => Model::Unicycle(Unicycle::from_block(block)),
        }
    }

    /// Drives `path` (a car's given by its segments too, `car`) from its
    /// first configuration.
    pub fn drive(&self, path: &[Config], car: Option<&CarPath>) -> DriveOutcome {
        match self {
            Model::Unicycle(u) => drive(path, u),
            Model::PurePursuit(p) => pure_pursuit::drive(path, car, p),
        }
    }
}

/// Settings of the simulated robot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unicycle {
    pub dt: f64,
    pub max_speed: f64,
    pub max_turn_rate: f64,
    pub gain: f64,
    pub turn_gain: f64,
    pub reach: f64,
    pub align: f64,
}

impl Unicycle {
    /// The settings of a validated `drive unicycle { ... }` block: each key
    /// as given, or its default in [`UNICYCLE_PARAMS`].
    pub fn from_block(block: &BTreeMap<&'static str, Param>) -> Self {
        let get = |key: &str| {
            block_value(UNICYCLE_PARAMS, block, key)
                .unwrap_or_else(|| panic!("drive key `{key}` has no numeric default"))
        };
        Unicycle {
            dt: get("dt"),
            max_speed: get("max_speed"),
            max_turn_rate: get("max_turn_rate"),
            gain: get("gain"),
            turn_gain: get("turn_gain"),
            reach: get("reach"),
            align: get("align"),
        }
    }
}

impl Default for Unicycle {
    /// Every key at its default.
    fn default() -> Self {
        Unicycle::from_block(&BTreeMap::new())
    }
}

/// A driven trajectory.
#[derive(Clone, Debug, Default)]
pub struct DriveOutcome {
    /// The simulated poses with their times in seconds, from the path's
    /// start; consecutive samples are `dt` apart.
    pub samples: Vec<(f64, Config)>,
    /// Time to reach the path's last point, in seconds (+∞ when the drive
    /// stopped at [`MAX_DRIVE_STEPS`] first).
    pub time: f64,
    /// Largest distance of the driven reference point from the path
    /// segment it was following.
    pub max_deviation: f64,
    /// The robot reached the path's last point.
    pub completed: bool,
}

impl DriveOutcome {
    /// At most `max` (≥ 2) of the samples, evenly spread, the first and the
    /// last included: what the viewer animates and `--json` lists.
    pub fn thinned(&self, max: usize) -> impl Iterator<Item = (f64, Config)> + '_ {
        let n = self.samples.len();
        // Every `every`-th sample and the last: at most max when max ≥ 2.
        let every = n
            .saturating_sub(1)
            .div_ceil(max.saturating_sub(1).max(1))
            .max(1);
        let last = n.checked_sub(1).filter(|l| !l.is_multiple_of(every));
        (0..n).step_by(every).chain(last).map(|i| self.samples[i])
    }
}

impl DriveOutcome {
    /// What the report says of a drive stopped at [`MAX_DRIVE_STEPS`]
    /// before the path's end (a speed so small, or a `dt` so short, that
    /// the path takes more steps): why `drive_time` is +∞.
    pub fn cut_off_note(&self) -> Option<String> {
        if self.completed {
            return None;
        }
        let simulated = self.samples.last().map_or(0.0, |(t, _)| *t);
        Some(format!(
            "the drive was stopped after {MAX_DRIVE_STEPS} steps ({simulated:.3} s simulated) before the path's end, so `drive_time` is inf: at this speed and `dt` the path takes more steps; raise the speed (`max_speed`, `speed`) or `dt`"
        ))
    }
}

/// Drives `path` from its first configuration (heading = its θ).
pub fn drive(path: &[Config], u: &Unicycle) -> DriveOutcome {
    let Some(first) = path.first() else {
        return DriveOutcome {
            completed: true,
            ..DriveOutcome::default()
        };
    };
    let mut state = *first;
    let mut t = 0.0;
    let mut steps = 0usize;
    let mut samples = vec![(0.0, state)];
    let mut max_dev = 0.0f64;
    let turn = |err: f64| (u.turn_gain * err).clamp(-u.max_turn_rate, u.max_turn_rate);
    for w in path.windows(2) {
        let (from, to) = (w[0].xy(), w[1].xy());
        let mut step = |state: &mut Config, v: f64, omega: f64| -> bool {
            if steps >= MAX_DRIVE_STEPS {
                return false;
            }
            state.x += v * state.theta.cos() * u.dt;
            state.y += v * state.theta.sin() * u.dt;
            state.theta += omega * u.dt;
            steps += 1;
            t = steps as f64 * u.dt;
            samples.push((t, *state));
            max_dev = max_dev.max(distance_point_segment(state.xy(), from, to));
            true
        };
        if (to - state.xy()).norm() <= u.reach {
            continue;
        }
        // Go-to-orientation: turn in place.
        loop {
            let d = to - state.xy();
            let err = angle_diff(state.theta, d.y.atan2(d.x));
            if err.abs() < u.align {
                break;
            }
            if !step(&mut state, 0.0, turn(err)) {
                return unfinished(samples, max_dev);
            }
        }
        // Go-to-cell: proportional speed, steering on the way.
        loop {
            let d = to - state.xy();
            let dist = d.norm();
            if dist <= u.reach {
                break;
            }
            let err = angle_diff(state.theta, d.y.atan2(d.x));
            let v = (u.gain * dist).min(u.max_speed) * err.cos().max(0.0);
            if !step(&mut state, v, turn(err)) {
                return unfinished(samples, max_dev);
            }
        }
    }
    DriveOutcome {
        samples,
        time: t,
        max_deviation: max_dev,
        completed: true,
    }
}

pub(crate) fn unfinished(samples: Vec<(f64, Config)>, max_deviation: f64) -> DriveOutcome {
    DriveOutcome {
        samples,
        time: f64::INFINITY,
        max_deviation,
        completed: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<Config> {
        [(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5), (0.5, 0.5)]
            .iter()
            .map(|&(x, y)| Config::new(x, y, 0.0))
            .collect()
    }

    #[test]
    fn reaches_every_point_within_reach() {
        let u = Unicycle::default();
        let path = square();
        let out = drive(&path, &u);
        assert!(out.completed);
        let last = out.samples.last().unwrap().1;
        assert!((last.xy() - path[4].xy()).norm() <= u.reach);
        // Every path point is passed within `reach` by some sample.
        for c in &path {
            let near = out
                .samples
                .iter()
                .any(|(_, s)| (s.xy() - c.xy()).norm() <= u.reach);
            assert!(near, "never reached {c:?}");
        }
        // Samples are dt apart and the time is the last sample's.
        for w in out.samples.windows(2) {
            assert!((w[1].0 - w[0].0 - u.dt).abs() < 1e-9);
        }
        assert_eq!(out.time, out.samples.last().unwrap().0);
        // Turning in place before each move keeps the robot on the path.
        assert!(out.max_deviation < 0.01, "{}", out.max_deviation);
    }

    #[test]
    fn speed_and_turn_rate_are_bounded() {
        let u = Unicycle {
            max_speed: 0.3,
            max_turn_rate: 1.0,
            ..Unicycle::default()
        };
        let out = drive(&square(), &u);
        for w in out.samples.windows(2) {
            let (a, b) = (w[0].1, w[1].1);
            assert!((b.xy() - a.xy()).norm() <= u.max_speed * u.dt + 1e-12);
            assert!((b.theta - a.theta).abs() <= u.max_turn_rate * u.dt + 1e-12);
        }
        // 4 unit moves at ≤ 0.3 per second take more than 4 / 0.3 seconds.
        assert!(out.time > 4.0 / 0.3);
    }

    #[test]
    fn a_step_cap_stops_a_hopeless_drive() {
        // A tiny dt with a slow robot would need far more steps than allowed.
        let u = Unicycle {
            dt: 1e-6,
            max_speed: 1e-3,
            ..Unicycle::default()
        };
        let out = drive(&square(), &u);
        assert!(!out.completed);
        assert!(out.time.is_infinite());
        assert_eq!(out.samples.len(), MAX_DRIVE_STEPS + 1);
    }

    #[test]
    fn an_empty_or_single_point_path_needs_no_driving() {
        let u = Unicycle::default();
        assert!(drive(&[], &u).completed);
        let one = drive(&[Config::new(1.0, 2.0, 0.3)], &u);
        assert!(one.completed);
        assert_eq!(one.time, 0.0);
        assert_eq!(one.samples.len(), 1);
    }

    #[test]
    fn thinning_keeps_the_ends_and_at_most_max_samples() {
        let outcome = |n: usize| DriveOutcome {
            samples: (0..n)
                .map(|i| (i as f64, Config::new(i as f64, 0.0, 0.0)))
                .collect(),
            ..Default::default()
        };
        assert_eq!(outcome(0).thinned(10).count(), 0);
        assert_eq!(
            outcome(1).thinned(10).map(|s| s.0).collect::<Vec<_>>(),
            [0.0]
        );
        assert_eq!(outcome(7).thinned(10).count(), 7);
        for (n, max) in [
            (11, 10),
            (100, 10),
            (101, 10),
            (12_345, 1000),
            (2, 2),
            (3, 2),
        ] {
            let times: Vec<f64> = outcome(n).thinned(max).map(|s| s.0).collect();
            assert!(
                times.len() <= max,
                "{n} samples thinned to {max}: {}",
                times.len()
            );
            assert_eq!(times[0], 0.0);
            assert_eq!(*times.last().unwrap(), (n - 1) as f64);
            // Evenly spread: all steps but the last are equal.
            let steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
            assert!(steps[..steps.len() - 1].iter().all(|&d| d == steps[0]));
            assert!(steps[steps.len() - 1] <= steps[0]);
        }
    }

    #[test]
    fn the_defaults_are_the_ones_the_schema_writes() {
        // A block giving every key its documented default, as written.
        let block: Vec<String> = UNICYCLE_PARAMS
            .iter()
            .map(|p| format!("{} {}", p.key, p.default.text()))
            .collect();
        let text = format!(
            "world {{ bounds (0, 0) (4, 4) }}\nrobot r point\n\
             plan a astar r {{ start (1, 1) goal (3, 3) drive unicycle {{ {} }} }}\n",
            block.join(" ")
        );
        let scenario = crate::scenario::load_text(&text);
        let Some(ParamValue::Block(_, given)) = scenario.plans[0].params.get("drive") else {
            panic!("no drive block");
        };
        assert_eq!(given.len(), UNICYCLE_PARAMS.len());
        assert_eq!(Unicycle::from_block(given), Unicycle::default());
        // The values the simulation documents (DECISIONS.md).
        let d = Unicycle::default();
        assert_eq!((d.dt, d.max_speed, d.max_turn_rate), (0.01, 1.0, 2.0));
        assert_eq!((d.gain, d.turn_gain, d.reach), (2.0, 8.0, 0.0009));
        assert!((d.align - 0.5_f64.to_radians()).abs() < 1e-15);
    }
}
