use super::*;

fn fmt(text: &str) -> String {
    let once = match format_text(text) {
        Ok(t) => t,
        Err(e) => panic!("{e:?} for\n{text}"),
    };
    let twice = format_text(&once).expect("the output formats");
    assert_eq!(once, twice, "formatting twice changed the text");
    once
}

#[test]
fn every_construct_in_the_canonical_layout() {
    let text = r#"scenario   "Apartment"
include "common.scen"
world {   bounds (0,0) (32,30)
  rect    B1 (0, 18) (10, 19)
  polygon P1 [(1,1), (3,1), (2,4),]
  segment W1 (26, 10) (26, 22)   disk C1 (5, 5) 1.5
  grid    G  "maps/arena.map" origin (0,0) cell 1
  grid F cell 0.5 origin (0, 0) {
       "....##...."
    "..3......."  }
  rect (0, 0) (.5, 1e-3)
}
robot rod  polygon [(0,0), (8,0), (8,1), (0,1)]
robot p point    robot d disk 0.5 robot b rect 2 1
plan offline astar rod { start (4, 24, 0deg) goal  (4, 8, 0deg) cell 1 limit time 2s
  sample center drive unicycle { dt 0.02 max_speed 1 } }
plan empty roadmap p {}
expect offline.found and not offline.gave_up
expect offline.cost<=90
expect live.traveled <= 50*offline.length
expect vg.length ~ 27.3137 +- 0.001
expect -offline.cost < (1 + 2) * 3
"#;
    assert_eq!(
        fmt(text),
        r#"scenario "Apartment"
include "common.scen"
world {
  bounds (0, 0) (32, 30)
  rect B1 (0, 18) (10, 19)
  polygon P1 [(1, 1), (3, 1), (2, 4)]
  segment W1 (26, 10) (26, 22)
  disk C1 (5, 5) 1.5
  grid G "maps/arena.map" origin (0, 0) cell 1
  grid F cell 0.5 origin (0, 0) {
    "....##...."
    "..3......."
  }
  rect (0, 0) (.5, 1e-3)
}
robot rod polygon [(0, 0), (8, 0), (8, 1), (0, 1)]
robot p point
robot d disk 0.5
robot b rect 2 1
plan offline astar rod {
  start (4, 24, 0deg)
  goal (4, 8, 0deg)
  cell 1
  limit time 2s
  sample center
  drive unicycle {
    dt 0.02
    max_speed 1
  }
}
plan empty roadmap p {}
expect offline.found and not offline.gave_up
expect offline.cost <= 90
expect live.traveled <= 50 * offline.length
expect vg.length ~ 27.3137 +- 0.001
expect -offline.cost < (1 + 2) * 3
"#
    );
}

#[test]
fn comments_stay_where_they_were() {
    let text = "# The header.\n\n# Second paragraph.\nscenario \"x\" # title\n\n\n\
                world { # the world\n\n  bounds (0, 0) (1, 1)   # corners\n  # a disk:\n  \
                disk (0, 0) 1\n\n  # the end of the world\n}\n\
                plan p astar r {\n  start # where\n    (0, 0)\n  goal (1, 1)\n  # last\n}\n\
                robot r polygon [(0, 0), # origin\n (1, 0), (0, 1)]\n\
                expect p.found # one\n  and p.cost < 3 # two\n# at the end\n";
    assert_eq!(
        fmt(text),
        "# The header.\n\n# Second paragraph.\nscenario \"x\" # title\n\n\
         world { # the world\n  bounds (0, 0) (1, 1) # corners\n  # a disk:\n  disk (0, 0) 1\n\n  \
         # the end of the world\n}\n\
         plan p astar r {\n  start # where\n    (0, 0)\n  goal (1, 1)\n  # last\n}\n\
         robot r polygon [\n  (0, 0), # origin\n  (1, 0),\n  (0, 1),\n]\n\
         expect p.found # one\n  and p.cost < 3 # two\n# at the end\n"
    );
}

#[test]
fn long_lists_and_expressions_break_to_fit() {
    let points: Vec<String> = (0..12).map(|k| format!("({k}.25, {k}.75)")).collect();
    let text = format!(
        "world {{ bounds (0, 0) (9, 9) polygon [{}] }}\n\
         expect first_plan.found and second_plan.found and third_plan.collision_free and fourth_plan.reaches_goal\n\
         expect (first_plan.length + second_plan.length + third_plan.length) / 3 <= 1.5 * fourth_plan.length_of_it\n",
        points.join(", ")
    );
    let mut list = String::new();
    for p in &points {
        list.push_str(&format!("    {p},\n"));
    }
    assert_eq!(
        fmt(&text),
        format!(
            "world {{\n  bounds (0, 0) (9, 9)\n  polygon [\n{list}  ]\n}}\n\
             expect first_plan.found\n  and second_plan.found\n  and third_plan.collision_free\n  and fourth_plan.reaches_goal\n\
             expect (first_plan.length + second_plan.length + third_plan.length) / 3\n  <= 1.5 * fourth_plan.length_of_it\n"
        )
    );
}

#[test]
fn parentheses_are_kept_once_and_tokens_as_written() {
    assert_eq!(
        fmt("expect ((a.found))or(b.x+1)*2>=.5 and not(c.found)\nexpect a.c == 100% \n"),
        "expect (a.found) or (b.x + 1) * 2 >= .5 and not (c.found)\nexpect a.c == 100%\n"
    );
    assert_eq!(fmt("expect ((3)) < a.x\n"), "expect (3) < a.x\n");
    assert_eq!(fmt("expect a.x ~ 1 ± 2\n"), "expect a.x ~ 1 +- 2\n");
}

#[test]
fn blank_lines_shrink_to_one_and_edges_lose_theirs() {
    assert_eq!(
        fmt("\n\n\nrobot r point\n\n\n\nrobot q point\n\n\n"),
        "robot r point\n\nrobot q point\n"
    );
    assert_eq!(fmt(""), "");
    assert_eq!(fmt("\n  \n"), "");
    assert_eq!(fmt("# only\n\n\n# comments\r\n"), "# only\n\n# comments\n");
    assert_eq!(
        fmt("world {\n\n  bounds (0, 0) (1, 1)\n\n}\n"),
        "world {\n  bounds (0, 0) (1, 1)\n}\n"
    );
}

#[test]
fn a_number_and_a_unit_word_stay_on_two_lines() {
    // `foo` is unknown: it takes `1 s 2` as its values, and `1 s` on one
    // line would be a unit apart from its number.
    let text = "plan p astar r {\n  foo 1\n  s 2\n}\n";
    assert_eq!(fmt(text), "plan p astar r {\n  foo 1\n    s 2\n}\n");
}

#[test]
fn syntax_errors_are_refused() {
    match format_text("world {\n  bounds (0, 0)\n") {
        Err(FormatError::Syntax(diags)) => assert!(!diags.is_empty()),
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_shape_ignores_spans_only() {
    let (a, _) = crate::syntax::parse("robot r disk 1", 0);
    let (b, _) = crate::syntax::parse("\n\nrobot   r disk 1", 0);
    let (c, _) = crate::syntax::parse("robot r disk 2", 0);
    assert_eq!(shape(&a.statements), shape(&b.statements));
    assert_ne!(shape(&a.statements), shape(&c.statements));
    assert!(!shape(&a.statements).contains("start"));
}

#[test]
fn moving_obstacles_and_speed_in_the_canonical_layout() {
    let text = "world { bounds (0,0) (20,10)\n  moving cart   disk 0.5 { at 0s (2,5)  at 4s (10,5) then   vanish }\n  moving door rect 1 4 {}\n}\nrobot dot disk 0.3   speed 1.5 robot car rect 2 1 speed 2 steer dubins 3\n";
    assert_eq!(
        fmt(text),
        "world {\n  bounds (0, 0) (20, 10)\n  moving cart disk 0.5 {\n    at 0s (2, 5)\n    at 4s (10, 5)\n    then vanish\n  }\n  moving door rect 1 4 {}\n}\nrobot dot disk 0.3 speed 1.5\nrobot car rect 2 1 speed 2 steer dubins 3\n"
    );
}
