//! How the flat tokens of a plan body (or a `drive { }` block) group into
//! parameters, as the analyzer reads them (`param_list` in analyze.rs): a
//! known key, then its value (`limit` takes a kind and an amount, `drive` a
//! model and an optional block); an unknown key takes the tokens up to the
//! next known key. The formatter puts one group per line, and the language
//! server finds the key a cursor's value belongs to.

use std::ops::Range;

use crate::planners::registry::{self, PLANNERS};
use crate::syntax::ast::ParamToken;

use crate::contract::schema::{COMMON_PARAMS, ParamSpec, ValueSpec, drive_params};

/// One parameter of a body: the range of its tokens, the first being its
/// key when `spec` is known.
#[derive(Clone, Debug)]
pub struct ParamGroup {
    pub tokens: Range<usize>,
    pub spec: Option<&'static ParamSpec>,
}

/// The parameters a body may give: a plan's of kind `kind`, every
/// planner's when the kind is unknown (so that a typo in the kind does not
/// change the layout), or a `drive` block's (every model's keys: the
/// analyzer says which model takes which).
#[derive(Clone, Copy, Debug)]
pub enum ParamKeys<'a> {
    Plan(&'a str),
    Drive,
}

impl ParamKeys<'_> {
    /// The parameter `key`, if this body accepts it.
    pub fn spec(&self, key: &str) -> Option<&'static ParamSpec> {
        match self {
            ParamKeys::Drive => drive_params().find(|p| p.key == key),
            ParamKeys::Plan(kind) => match registry::planner(kind) {
                Some(planner) => planner.param(key),
                None => COMMON_PARAMS
                    .iter()
                    .chain(PLANNERS.iter().flat_map(|p| p.params.iter()))
                    .find(|p| p.key == key),
            },
        }
    }

    /// The keys of a block nested in a parameter of this body.
    pub fn nested(&self) -> ParamKeys<'static> {
        ParamKeys::Drive
    }
}

/// Groups `tokens` into parameters; see the module docs.
pub fn group_params(tokens: &[ParamToken], keys: ParamKeys<'_>) -> Vec<ParamGroup> {
    let known = |t: Option<&ParamToken>| match t {
        Some(ParamToken::Word(w)) => keys.spec(&w.value).is_some(),
        _ => false,
    };
    let mut groups = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let start = i;
        let spec = match &tokens[i] {
            ParamToken::Word(key) => keys.spec(&key.value),
            _ => None,
        };
        i += 1;
        match spec {
            None if matches!(tokens[start], ParamToken::Word(_)) => {
                while i < tokens.len() && !known(tokens.get(i)) {
                    i += 1;
                }
            }
            None => {}
            Some(spec) => {
                let next = tokens.get(i);
                let missing = next.is_none() || (!spec.value.takes_word() && known(next));
                if !missing {
                    i += 1;
                    let follows = match spec.value {
                        ValueSpec::Limit => matches!(tokens.get(i), Some(ParamToken::Value(_))),
                        ValueSpec::Drive => {
                            matches!(tokens.get(i), Some(ParamToken::Block { .. }))
                        }
                        _ => false,
                    };
                    let takes_more = matches!(next, Some(ParamToken::Word(_)));
                    if follows && takes_more {
                        i += 1;
                    }
                }
            }
        }
        groups.push(ParamGroup {
            tokens: start..i,
            spec,
        });
    }
    groups
}

/// Groups the tokens of a bench's body (SPEC 2.7) as the analyzer reads
/// them: each group starts at a bench key (`plans`, `vary`, `runs`,
/// `limit`) and runs up to the next one; `vary` takes the word after it
/// as the key it varies, whatever that word is. Leading tokens that are not
/// a key form a group of their own.
pub fn group_bench(tokens: &[ParamToken]) -> Vec<Range<usize>> {
    let is_key = |t: &ParamToken| matches!(t, ParamToken::Word(w) if super::analyze::BENCH_KEYS.contains(&w.value.as_str()));
    let mut groups = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let start = i;
        i += 1;
        if matches!(&tokens[start], ParamToken::Word(w) if w.value == "vary")
            && matches!(tokens.get(i), Some(ParamToken::Word(_)))
        {
            i += 1;
        }
        while i < tokens.len() && !is_key(&tokens[i]) {
            i += 1;
        }
        groups.push(start..i);
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::ast::Stmt;

    fn groups(body: &str, kind: &str) -> Vec<String> {
        let text = format!("plan p {kind} r {{ {body} }}");
        let (file, diags) = crate::syntax::parse(&text, 0);
        assert!(diags.is_empty(), "{diags:?}");
        let Some(Stmt::Plan(plan)) = file.statements.first() else {
            panic!("{text}")
        };
        group_params(&plan.body, ParamKeys::Plan(kind))
            .iter()
            .map(|g| {
                let first = plan.body[g.tokens.start].span().start;
                let last = plan.body[g.tokens.end - 1].span().end;
                text[first..last].to_string()
            })
            .collect()
    }

    #[test]
    fn a_bench_groups_into_its_keys() {
        let text =
            "bench b { x plans [p, q] vary limit [1, 2] vary weight [1, 2] runs 5 limit time 1s }";
        let (file, diags) = crate::syntax::parse(text, 0);
        assert!(diags.is_empty(), "{diags:?}");
        let Some(Stmt::Bench(bench)) = file.statements.first() else {
            panic!("{text}")
        };
        let groups: Vec<&str> = group_bench(&bench.body)
            .into_iter()
            .map(|g| {
                let first = bench.body[g.start].span().start;
                let last = bench.body[g.end - 1].span().end;
                &text[first..last]
            })
            .collect();
        assert_eq!(
            groups,
            [
                "x",
                "plans [p, q]",
                "vary limit [1, 2]",
                "vary weight [1, 2]",
                "runs 5",
                "limit time 1s"
            ]
        );
    }

    #[test]
    fn a_body_groups_into_its_parameters() {
        assert_eq!(
            groups(
                "start (0, 0) goal (1, 1) limit time 2s limit expansions 10 \
                 drive unicycle { dt 0.1 } sample center cell",
                "astar"
            ),
            [
                "start (0, 0)",
                "goal (1, 1)",
                "limit time 2s",
                "limit expansions 10",
                "drive unicycle { dt 0.1 }",
                "sample center",
                "cell",
            ]
        );
        // An unknown key takes what follows up to a known key; a key right
        // before a known key has no value; a stray value stands alone.
        assert_eq!(
            groups("cel 1 2 start goal (1, 1) 5", "astar"),
            ["cel 1 2", "start", "goal (1, 1)", "5"]
        );
        // An unknown kind groups by every planner's keys.
        assert_eq!(
            groups("start (0, 0) cell 1 tool 2", "astra"),
            ["start (0, 0)", "cell 1", "tool 2"]
        );
    }
}
