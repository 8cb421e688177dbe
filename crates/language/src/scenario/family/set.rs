//! `scen run --set NAME=VALUE`: a drawn param's value given, refused when
//! it names no family member.

#![allow(clippy::result_large_err)]

use crate::contract::schema;
use crate::diagnostics::{Diag, Span};
use crate::syntax::ast::Expr;

use super::*;

/// A `--set` that names no family member (exit 2).
pub(super) fn bad_set(message: String, span: Span, label: &str, help: impl Into<String>) -> Diag {
    Diag::error("scen::family::bad_set", message)
        .at(span, label.to_string())
        .help(help.into())
}

impl Family {
    /// The drawn params' values given as `NAME=VALUE` (`scen run --set`),
    /// by param index (`None`: drawn as usual). Errors: not `NAME=VALUE`,
    /// an unknown or computed param, not a number, a family that draws
    /// nothing. Whether a value is in its distribution's support is
    /// checked at the draw (bounds may read earlier params).
    pub(crate) fn resolve_set(&self, set: &[String]) -> Result<Vec<Option<f64>>, Vec<Diag>> {
        if set.is_empty() {
            return Ok(Vec::new());
        }
        let anchor = self
            .params
            .first()
            .map_or(Span::new(0, 0, 0), |p| p.name.span);
        let mut out = vec![None; self.params.len()];
        let mut diags = Vec::new();
        for given in set {
            let Some((name, value)) = given.split_once('=') else {
                diags.push(bad_set(
                    format!("`--set {given}` is not `NAME=VALUE`"),
                    anchor,
                    "the family's params are declared from here",
                    "give a param's value as `--set NAME=VALUE`, e.g. `--set gap=1.25`",
                ));
                continue;
            };
            let name = name.trim();
            let Some(&k) = self.index.get(name) else {
                let known: Vec<&str> = self.drawn_names();
                let help = match schema::did_you_mean(name, known.iter().copied()) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None if known.is_empty() => {
                        "this scenario draws no param: run it without `--set`".to_string()
                    }
                    None => format!("the drawn params are {}", schema::backticked(&known)),
                };
                diags.push(bad_set(
                    format!("`--set {given}`: the scenario has no param `{name}`"),
                    anchor,
                    "the family's params are declared from here",
                    help,
                ));
                continue;
            };
            let p = &self.params[k];
            if !p.drawn() {
                diags.push(bad_set(
                    format!(
                        "`--set {given}`: the param `{name}` is computed from others, not drawn"
                    ),
                    p.name.span,
                    "computed here",
                    "set the drawn params it is computed from",
                ));
                continue;
            }
            match value.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => out[k] = Some(x),
                _ => diags.push(bad_set(
                    format!("`--set {given}`: `{}` is not a number", value.trim()),
                    p.name.span,
                    "the param set",
                    "write a finite number, e.g. `--set gap=1.25` (what `scen falsify` prints)",
                )),
            }
        }
        if diags.is_empty() {
            Ok(out)
        } else {
            Err(diags)
        }
    }

    /// Why `x` is not a value param `p` can draw (its support), given the
    /// earlier params' values; `None` when it is one.
    pub(super) fn outside_support(
        &self,
        p: &ParamDef,
        x: f64,
        values: &[f64],
    ) -> Result<Option<String>, Diag> {
        let bound = |e: &Expr| eval(e, values, &self.index).map_err(|e| e.diag(self, values));
        Ok(match &p.source {
            Source::Uniform(a, b) => {
                let (lo, hi) = (bound(a)?, bound(b)?);
                (!(lo <= x && x <= hi))
                    .then(|| format!("`uniform({lo}, {hi})` draws from {lo} to {hi}"))
            }
            Source::Int(a, b) => {
                let (lo, hi) = (bound(a)?.ceil(), bound(b)?.floor());
                (!(lo <= x && x <= hi && x.fract() == 0.0))
                    .then(|| format!("`int` draws the whole numbers from {lo} to {hi}"))
            }
            Source::Choice(items) => {
                let mut all = Vec::new();
                for item in items {
                    all.push(self.number(item, values)?);
                }
                (!all.contains(&x)).then(|| {
                    format!(
                        "`choice` draws one of {}",
                        all.iter()
                            .map(|v| format!("{v}"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                })
            }
            Source::Normal(..) | Source::Value(_) => None,
        })
    }

    /// The drawn params' values (in the order of [`Family::drawn_values`])
    /// as what `--set` gives, by param index.
    pub fn set_of_drawn(&self, drawn: &[f64]) -> Vec<Option<f64>> {
        let mut given = drawn.iter().copied();
        self.params
            .iter()
            .map(|p| if p.drawn() { given.next() } else { None })
            .collect()
    }
}
