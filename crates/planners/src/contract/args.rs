//! What a planner's `check` sees of a plan: its validated parameters with
//! the schema's defaults, the world and the robot, and a place to report
//! problems with spans ([`crate::contract::Planner::check`]).

use crate::contract::Planner;
use crate::diagnostics::{Diag, Span};
use crate::geometry::World;

use super::{ParamValue, Params, Robot};
use crate::contract::schema::{DefaultValue, ParamSpec, ValueSpec, Word};

/// A plan's parameters on their way into the planner's typed settings.
///
/// Values the user gave come with their spans; keys not given read as the
/// schema's [`DefaultValue`], so a default is written once, in the schema.
/// Asking for a key the planner does not declare, or for the default of a
/// key whose default is derived, is a bug in the planner (it panics with
/// the key's name; the contract test runs every planner's `check`).
pub struct PlanArgs<'a> {
    /// The plan's name.
    pub plan: &'a str,
    /// The plan's head `NAME KIND ROBOT`, for problems with no better place.
    pub head: Span,
    pub world: &'a World,
    pub robot: &'a Robot,
    pub params: &'a Params,
    /// The start is inside the bounds and clear of obstacles (otherwise
    /// the analyzer has said so: checks about the start would only repeat
    /// it).
    pub start_valid: bool,
    planner: &'static Planner,
    diags: Vec<Diag>,
}

impl<'a> PlanArgs<'a> {
    pub fn new(
        planner: &'static Planner,
        plan: &'a str,
        head: Span,
        world: &'a World,
        robot: &'a Robot,
        params: &'a Params,
    ) -> Self {
        PlanArgs {
            plan,
            head,
            world,
            robot,
            params,
            start_valid: true,
            planner,
            diags: Vec::new(),
        }
    }

    /// The planner whose plan this is.
    pub fn planner(&self) -> &'static Planner {
        self.planner
    }

    /// The schema of `key`.
    pub fn spec(&self, key: &str) -> &'static ParamSpec {
        match self.planner.param(key) {
            Some(spec) => spec,
            None => panic!("planner `{}` declares no `{key}`", self.planner.kind),
        }
    }

    /// Whether the user gave `key`.
    pub fn given(&self, key: &str) -> bool {
        self.params.values.contains_key(key)
    }

    /// The span of the value of `key` as given, or the plan's head.
    pub fn span(&self, key: &str) -> Span {
        self.params.values.get(key).map_or(self.head, |p| p.span)
    }

    /// A number (durations in seconds, angles in radians): as given, or
    /// the schema's default.
    pub fn num(&self, key: &str) -> f64 {
        if let Some(x) = self.opt_num(key) {
            return x;
        }
        match self.spec(key).default {
            DefaultValue::Num(x, _) => x,
            other => panic!(
                "`{key}` of `{}` has no numeric default ({other:?})",
                self.planner.kind
            ),
        }
    }

    /// A number as given (`None` when not given, or given as a word such as
    /// `layers auto`).
    pub fn opt_num(&self, key: &str) -> Option<f64> {
        self.spec(key);
        match self.params.get(key) {
            Some(ParamValue::Num(x)) => Some(*x),
            _ => None,
        }
    }

    /// A word value as the planner's enum: as given, or the default.
    pub fn word<W: Word>(&self, key: &str) -> W {
        if let Some(w) = self.opt_word(key) {
            return w;
        }
        match self.spec(key).default {
            DefaultValue::Word(w) => word_of(key, w),
            other => panic!(
                "`{key}` of `{}` has no word default ({other:?})",
                self.planner.kind
            ),
        }
    }

    /// A word value as given, as the planner's enum.
    pub fn opt_word<W: Word>(&self, key: &str) -> Option<W> {
        let spec = self.spec(key);
        if let ValueSpec::Word(words) = spec.value {
            assert_eq!(
                words,
                W::WORDS,
                "the schema of `{key}` does not list the words of its enum"
            );
        }
        match self.params.get(key) {
            Some(ParamValue::Word(w)) => Some(word_of(key, w)),
            _ => None,
        }
    }

    /// A name given as a word (`on G`).
    pub fn name(&self, key: &str) -> Option<&'a str> {
        self.spec(key);
        match self.params.get(key) {
            Some(ParamValue::Word(w)) => Some(w.as_str()),
            _ => None,
        }
    }

    /// Reports a problem; the plan will not run.
    pub fn error(&mut self, d: Diag) {
        self.diags.push(d);
    }

    /// Whether nothing was reported so far.
    pub fn ok(&self) -> bool {
        !self.diags.iter().any(Diag::is_error)
    }

    /// The problems reported.
    pub fn into_diags(self) -> Vec<Diag> {
        self.diags
    }
}

fn word_of<W: Word>(key: &str, w: &str) -> W {
    W::WORDS
        .iter()
        .position(|x| *x == w)
        .and_then(W::from_index)
        .unwrap_or_else(|| panic!("`{w}` is not a word of `{key}`'s enum"))
}
