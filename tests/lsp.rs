//! `scen lsp` tested by speaking the protocol to the real binary over
//! stdio, with exact expected answers on small files.

mod common;

use common::TempDir;
use common::lsp_client::{Client, range, reference_lines, uri};
use scen::planners::registry::PLANNERS;
use serde_json::{Value, json};

const MAIN: &str = "\
include \"_robots.scen\"
world {
  bounds (0, 0) (10, 10)
  grid G cell 1 origin (0, 0) { \"....\" \"....\" }
}
plan p astar dot {
  start (1, 1)
  goal (8, 8)
  sample center
}
plan c coverage dot { start (0.5, 0.5) on G }
expect p.found and p.cost < 20
";

fn setup() -> (TempDir, String, String) {
    let dir = TempDir::new("lsp");
    std::fs::write(dir.path().join("main.scen"), MAIN).unwrap();
    std::fs::write(dir.path().join("_robots.scen"), "robot dot disk 0.25\n").unwrap();
    let main = uri(&dir.path().join("main.scen"));
    let robots = uri(&dir.path().join("_robots.scen"));
    (dir, main, robots)
}

const BENCHES: &str = "\
robot dot disk 0.25
plan p potential dot {
  start (1, 1)
  goal (8, 8)
}
plan q astar dot {
  start (1, 1)
  goal (8, 8)
}
bench b {
  plans [p]
  vary jump [4, 8]
  runs 3
}
expect median(b.p[jump = 4].length) < 20
world {
  bounds (0, 0) (10, 10)
}
";

#[test]
fn benches_are_completed_navigated_and_outlined() {
    let dir = TempDir::new("lsp-bench");
    std::fs::write(dir.path().join("b.scen"), BENCHES).unwrap();
    let file = uri(&dir.path().join("b.scen"));
    let mut c = Client::start();
    c.open(&file, BENCHES);
    assert_eq!(c.diagnostics(&file), json!([]));
    // A bench's keys, the plans of `plans [`, the keys `vary` takes.
    assert_eq!(
        c.labels(&file, 10, 2),
        ["plans", "vary", "runs", "worlds", "limit"]
    );
    assert_eq!(c.labels(&file, 10, 9), ["p", "q"]);
    let vary = c.labels(&file, 11, 7);
    assert!(
        vary.contains(&"jump".to_string()) && vary.contains(&"weight".to_string()),
        "{vary:?}"
    );
    // In `expect`: plans, benches and the aggregates; `b.` → plans;
    // `b.p[jump = 4].` → the plan's metrics.
    let words = c.labels(&file, 14, 7);
    assert_eq!(&words[..4], ["p", "q", "b", "mean"]);
    assert!(words.contains(&"rate".to_string()), "{words:?}");
    assert_eq!(c.labels(&file, 14, 16), ["p", "q"]);
    let metrics = c.labels(&file, 14, 29);
    assert!(metrics.contains(&"minima".to_string()), "{metrics:?}");
    // Hover on the series' metric; definition of its bench and plan.
    let hover = c.at("textDocument/hover", &file, 14, 31);
    assert_eq!(hover["range"], range(14, 28, 14, 34), "{hover}");
    let def = c.at("textDocument/definition", &file, 14, 14);
    assert_eq!(def["range"], range(9, 6, 9, 7), "{def}");
    let def = c.at("textDocument/definition", &file, 14, 16);
    assert_eq!(def["range"], range(1, 5, 1, 6), "{def}");
    // The plan's references: its declaration, `plans [p]` and the series.
    let refs = c.at("textDocument/references", &file, 1, 5);
    let lines = reference_lines(&refs);
    assert_eq!(lines, [1, 10, 14], "{refs}");
    // The outline lists the bench.
    let symbols = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": file } }),
    );
    let names: Vec<&str> = symbols
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["dot", "p", "q", "b", "world"]);
    // Formatting leaves the canonical text as it is.
    let edits = c.request(
        "textDocument/formatting",
        json!({ "textDocument": { "uri": file }, "options": { "tabSize": 2, "insertSpaces": true } }),
    );
    assert!(edits.is_null() || edits == json!([]), "{edits}");
    c.shutdown();
}

const FAMILY: &str = "param gap = uniform(0.5, 2)
param half = gap / 2
world {
  bounds (0, 0) (10, 10)
  rect (0, 4) (5 - half, 5)
}
robot r disk 0.2
plan p astar r { start (1, 1) goal (5, 9) weight 1 + gap }
expect p.length < 20 + gap
";

#[test]
fn params_are_hovered_navigated_and_referenced() {
    let dir = TempDir::new("lsp-family");
    std::fs::write(dir.path().join("f.scen"), FAMILY).unwrap();
    let file = uri(&dir.path().join("f.scen"));
    let mut c = Client::start();
    c.open(&file, FAMILY);
    assert_eq!(c.diagnostics(&file), json!([]));
    // Hover on `half` in the world shows its declaration.
    let hover = c.at("textDocument/hover", &file, 4, 20);
    assert!(
        hover["contents"]["value"]
            .as_str()
            .is_some_and(|t| t.contains("param half = gap / 2")),
        "{hover}"
    );
    // `gap` in a plan body and in an expectation goes to its declaration.
    for (line, col) in [(7, 54), (8, 24)] {
        let def = c.at("textDocument/definition", &file, line, col);
        assert_eq!(def["range"], range(0, 6, 0, 9), "{line}:{col}: {def}");
    }
    // Its references: the declaration, `half`'s value, the plan, the check.
    let refs = c.at("textDocument/references", &file, 0, 7);
    let lines = reference_lines(&refs);
    assert_eq!(lines, [0, 1, 7, 8], "{refs}");
}

const MOVING: &str = "world {
  bounds (0, 0) (20, 10)
  moving cart disk 0.5 {
    at 0s (2, 5)
    at 4s (10, 5)
    then vanish
  }
}
robot dot disk 0.3 speed 1.5
";

#[test]
fn a_moving_obstacle_is_hovered_with_its_route() {
    let dir = TempDir::new("lsp-moving");
    std::fs::write(dir.path().join("m.scen"), MOVING).unwrap();
    let file = uri(&dir.path().join("m.scen"));
    let mut c = Client::start();
    c.open(&file, MOVING);
    let hover = c.at("textDocument/hover", &file, 2, 10);
    let text = hover["contents"]["value"].as_str().unwrap_or_default();
    assert!(
        text.contains("at 4s (10, 5)") && text.contains("then vanish"),
        "{hover}"
    );
}

#[test]
fn the_server_answers_every_request_exactly() {
    let (_dir, main, robots) = setup();
    let mut c = Client::start();
    c.open(&main, MAIN);
    assert_eq!(c.diagnostics(&main), json!([]));

    // Completion: statement keywords at the start of a line, planner kinds,
    // robot names, a planner's keys with their docs, a key's words, the
    // plan names and a plan's metrics.
    assert_eq!(
        c.labels(&main, 12, 0),
        [
            "scenario", "include", "world", "robot", "team", "plan", "expect", "bench", "param",
            "require"
        ]
    );
    let kinds: Vec<&str> = PLANNERS.iter().map(|p| p.kind).collect();
    assert_eq!(c.labels(&main, 5, 7), kinds);
    assert_eq!(c.labels(&main, 5, 13), ["dot"]);
    let keys = c.at("textDocument/completion", &main, 8, 2);
    let cell = keys
        .as_array()
        .unwrap()
        .iter()
        .find(|i| i["label"] == "cell")
        .unwrap();
    assert_eq!(cell["detail"], "a number > 0 and <= 1e9");
    assert_eq!(cell["kind"], 5);
    assert!(
        cell["documentation"]["value"]
            .as_str()
            .unwrap()
            .contains("Default: `1`."),
        "{cell}"
    );
    assert_eq!(c.labels(&main, 8, 9), ["center", "corner"]);
    assert_eq!(c.labels(&main, 10, 42), ["G"]);
    assert_eq!(
        c.labels(&main, 11, 7),
        ["p", "c", "and", "or", "not", "true", "false"]
    );
    let metrics = c.labels(&main, 11, 9);
    assert_eq!(&metrics[..3], ["found", "gave_up", "cost"]);
    assert!(metrics.contains(&"free_cells".to_string()), "{metrics:?}");

    // Hover: a key, a metric, a robot declared in the include, a planner.
    let hover = c.at("textDocument/hover", &main, 8, 3);
    assert_eq!(hover["range"], range(8, 2, 8, 8));
    assert!(
        hover["contents"]["value"]
            .as_str()
            .unwrap()
            .starts_with("`sample` (astar)\n\n"),
        "{hover}"
    );
    let hover = c.at("textDocument/hover", &main, 11, 25);
    assert_eq!(hover["range"], range(11, 21, 11, 25));
    assert!(
        hover["contents"]["value"]
            .as_str()
            .unwrap()
            .starts_with("`p.cost` (metric of `astar`)"),
        "{hover}"
    );
    let hover = c.at("textDocument/hover", &main, 5, 14);
    let value = hover["contents"]["value"].as_str().unwrap();
    assert!(
        value.starts_with("```scen\nrobot dot disk 0.25\n```\n\nDeclared in `"),
        "{value}"
    );
    assert!(value.ends_with("_robots.scen:1:7`."), "{value}");
    let hover = c.at("textDocument/hover", &main, 5, 9);
    assert!(
        hover["contents"]["value"]
            .as_str()
            .unwrap()
            .starts_with("`astar` — "),
        "{hover}"
    );
    assert_eq!(c.at("textDocument/hover", &main, 2, 0), Value::Null);

    // Definition and references, through the include.
    assert_eq!(
        c.at("textDocument/definition", &main, 5, 14),
        json!({ "uri": robots, "range": range(0, 6, 0, 9) })
    );
    assert_eq!(
        c.at("textDocument/definition", &main, 11, 8),
        json!({ "uri": main, "range": range(5, 5, 5, 6) })
    );
    assert_eq!(
        c.at("textDocument/definition", &main, 0, 12),
        json!({ "uri": robots, "range": range(0, 0, 0, 0) })
    );
    assert_eq!(
        c.at("textDocument/references", &main, 5, 5),
        json!([
            { "uri": main, "range": range(5, 5, 5, 6) },
            { "uri": main, "range": range(11, 7, 11, 8) },
            { "uri": main, "range": range(11, 19, 11, 20) },
        ])
    );
    assert_eq!(
        c.at("textDocument/references", &main, 10, 42),
        json!([
            { "uri": main, "range": range(3, 7, 3, 8) },
            { "uri": main, "range": range(10, 42, 10, 43) },
        ])
    );
    let refs = c.at("textDocument/references", &main, 5, 14);
    assert_eq!(refs.as_array().unwrap().len(), 3, "{refs}");
    assert_eq!(
        refs[0],
        json!({ "uri": robots, "range": range(0, 6, 0, 9) })
    );

    // The outline.
    let symbols = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": main } }),
    );
    let names: Vec<(&str, i64)> = symbols
        .as_array()
        .unwrap()
        .iter()
        .map(|s| (s["name"].as_str().unwrap(), s["kind"].as_i64().unwrap()))
        .collect();
    assert_eq!(names, [("world", 3), ("p", 12), ("c", 12)]);
    assert_eq!(symbols[0]["children"][0]["name"], "G");
    assert_eq!(symbols[0]["children"][0]["range"], range(3, 2, 3, 47));
    assert_eq!(symbols[1]["selectionRange"], range(5, 5, 5, 6));

    // Formatting: the same as `scen fmt`.
    let edits = c.request(
        "textDocument/formatting",
        json!({ "textDocument": { "uri": main }, "options": { "tabSize": 2, "insertSpaces": true } }),
    );
    let formatted = scen::format::format_text(MAIN).unwrap();
    assert_eq!(
        edits,
        json!([{ "range": range(0, 0, 12, 0), "newText": formatted }])
    );

    c.shutdown();
}

#[test]
fn diagnostics_follow_the_text_as_it_is_typed() {
    let (_dir, main, robots) = setup();
    let mut c = Client::start();
    c.open(&main, MAIN);
    assert_eq!(c.diagnostics(&main), json!([]));
    // `sample center` → `sample centre`: an analysis error, with its code,
    // span and help, as `scen check` gives it.
    c.change(
        &main,
        2,
        json!([{ "range": range(8, 13, 8, 15), "text": "re" }]),
    );
    let d = c.diagnostics(&main);
    assert_eq!(d.as_array().unwrap().len(), 1, "{d}");
    assert_eq!(d[0]["code"], "scen::analyze::out_of_range");
    assert_eq!(d[0]["range"], range(8, 9, 8, 15));
    assert_eq!(d[0]["severity"], 1);
    assert_eq!(d[0]["source"], "scen");
    let message = d[0]["message"].as_str().unwrap();
    assert!(message.contains("\nhelp: "), "{message}");
    // An error in the included document, open and edited, is shown at the include.
    c.open(&robots, "robot dot disk -1\n");
    let d = c.diagnostics(&main);
    let codes: Vec<&str> = d
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["code"].as_str().unwrap())
        .collect();
    assert!(codes.contains(&"scen::analyze::out_of_range"), "{d}");
    let at_include = d
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["range"] == range(0, 8, 0, 22))
        .expect("at the include");
    assert!(
        at_include["message"].as_str().unwrap().starts_with("in `"),
        "{at_include}"
    );
    assert_eq!(
        at_include["relatedInformation"][0]["location"]["uri"],
        robots
    );
    // Fixed: no diagnostics.
    c.change(&robots, 2, json!([{ "text": "robot dot disk 0.25\n" }]));
    c.change(
        &main,
        3,
        json!([{ "range": range(8, 13, 8, 15), "text": "er" }]),
    );
    let mut last = c.diagnostics(&main);
    while last != json!([]) {
        last = c.diagnostics(&main);
    }
    c.shutdown();
}

#[test]
fn half_typed_and_broken_text_never_stops_the_server() {
    let (dir, main, _) = setup();
    std::fs::write(dir.path().join("_a.scen"), "include \"_b.scen\"\n").unwrap();
    std::fs::write(dir.path().join("_b.scen"), "include \"_a.scen\"\n").unwrap();
    let mut c = Client::start();
    c.open(&main, MAIN);
    c.diagnostics(&main);
    let broken = [
        ("", None),
        (
            "world {\n  bounds (0, 0) (1, 1)\nplan p",
            Some("scen::syntax::expected"),
        ),
        (
            "world { bounds (0, 0) (1, 1) }\nplan p { start (0, 0) }",
            Some("scen::syntax::expected"),
        ),
        ("include \"_a.scen\"\n", Some("scen::load::include_cycle")),
        (
            "\u{0}\u{1}\u{7f}\u{fffd}PK\u{3}\u{4}\n\u{feff}(((((",
            Some("scen::syntax::expected"),
        ),
        ("expect p.", Some("scen::syntax::expected")),
        (
            "plan p astar dot {\n  start (1, 1) goal (2, 2) drive unicycle {",
            Some("scen::syntax::expected"),
        ),
    ];
    for (version, (text, code)) in broken.iter().enumerate() {
        c.change(&main, version as i32 + 2, json!([{ "text": text }]));
        let d = c.diagnostics(&main);
        if let Some(code) = code {
            let codes: Vec<&str> = d
                .as_array()
                .unwrap()
                .iter()
                .map(|d| d["code"].as_str().unwrap())
                .collect();
            assert!(codes.contains(code), "{text:?}: {d}");
        }
        // Every request is still answered, at every line.
        let lines = text.lines().count() as u32 + 1;
        for line in 0..lines {
            for method in [
                "textDocument/completion",
                "textDocument/hover",
                "textDocument/definition",
                "textDocument/references",
            ] {
                c.at(method, &main, line, 3);
            }
        }
        c.request(
            "textDocument/documentSymbol",
            json!({ "textDocument": { "uri": main } }),
        );
        c.request(
            "textDocument/formatting",
            json!({ "textDocument": { "uri": main }, "options": { "tabSize": 2, "insertSpaces": true } }),
        );
    }
    // Completion in half-typed statements.
    c.change(
        &main,
        20,
        json!([{ "text": "robot r point\nplan q astar r {\n  start (1, 1)\n  limit \n" }]),
    );
    c.diagnostics(&main);
    assert_eq!(c.labels(&main, 3, 8), ["expansions", "time", "cells"]);
    assert_eq!(c.labels(&main, 1, 13), ["r"]);
    // Recovered as soon as the text is fixed.
    c.change(&main, 21, json!([{ "text": MAIN }]));
    assert_eq!(c.diagnostics(&main), json!([]));
    assert_eq!(c.labels(&main, 8, 9), ["center", "corner"]);
    c.shutdown();
}

/// A 2,000-line scenario: a world of 400 obstacles, 150 plans of 10 lines,
/// 200 checks.
fn two_thousand_lines() -> String {
    let mut text = String::from("scenario \"big\"\nworld {\n  bounds (0, 0) (400, 400)\n");
    for k in 0..400 {
        let (x, y) = (k % 20 * 20, k / 20 * 20);
        text.push_str(&format!("  rect R{k} ({x}.5, {y}.5) ({x}.9, {y}.9)\n"));
    }
    text.push_str("}\nrobot dot disk 0.1\n");
    for k in 0..150 {
        text.push_str(&format!(
            "plan p{k} astar dot {{\n  start (0.1, 0.1)\n  goal (1.1, 1.1)\n  cell 1\n  \
             connect 8\n  heuristic metric\n  weight 1\n  limit expansions 1000\n  \
             limit time 1s\n}}\n"
        ));
    }
    for k in 0..200 {
        text.push_str(&format!(
            "expect p{}.found and p{}.cost < 10\n",
            k % 150,
            k % 150
        ));
    }
    text
}

/// Not a test of speed (nothing is asserted about time): prints the
/// server's latencies on a 2,000-line file for BENCHMARKS.md. Run with
/// `cargo test --release --test lsp -- --ignored --nocapture latencies`.
#[test]
#[ignore]
fn latencies_on_a_two_thousand_line_file() {
    use std::time::Instant;
    let dir = TempDir::new("lsp-timing");
    let path = dir.path().join("big.scen");
    let text = two_thousand_lines();
    assert!(text.lines().count() >= 2000, "{}", text.lines().count());
    std::fs::write(&path, &text).unwrap();
    let main = uri(&path);
    let mut c = Client::start();
    let started = Instant::now();
    c.open(&main, &text);
    assert_eq!(c.diagnostics(&main), json!([]));
    eprintln!("open → diagnostics: {:?}", started.elapsed());
    let line = text
        .lines()
        .position(|l| l.starts_with("plan p100"))
        .unwrap() as u32
        + 6;
    let (mut diagnostics, mut completion, mut hover) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..30 {
        // Type one character into `weight 1` (1 → 2 → 1 ...), then ask.
        let digit = if round % 2 == 0 { "2" } else { "1" };
        // Diagnostics published before this edit do not answer it.
        c.notifications.clear();
        let t = Instant::now();
        c.change(
            &main,
            round + 2,
            json!([{ "range": range(line, 9, line, 10), "text": digit }]),
        );
        let d = c.diagnostics(&main);
        diagnostics.push(t.elapsed());
        assert_eq!(d, json!([]));
        let t = Instant::now();
        c.change(
            &main,
            round + 100,
            json!([{ "range": range(line, 9, line, 10), "text": digit }]),
        );
        let items = c.labels(&main, line, 2);
        completion.push(t.elapsed());
        assert!(items.contains(&"weight".to_string()));
        let t = Instant::now();
        c.at("textDocument/hover", &main, line, 3);
        hover.push(t.elapsed());
    }
    let median = |v: &mut Vec<std::time::Duration>| {
        v.sort();
        v[v.len() / 2]
    };
    eprintln!(
        "{} lines, median of 30 edits: edit → diagnostics {:?}, edit → completion {:?}, hover {:?}",
        text.lines().count(),
        median(&mut diagnostics),
        median(&mut completion),
        median(&mut hover)
    );
    c.shutdown();
}

/// The error response to a message that could not be taken (its `id` is
/// null: none could be read from it), skipping other messages.
fn error_without_id(c: &mut Client) -> Value {
    loop {
        let message = c.receive();
        if message.get("method").is_none() && message["id"].is_null() {
            assert_eq!(message["jsonrpc"], "2.0", "{message}");
            return message["error"].clone();
        }
        c.notifications.push(message);
    }
}

fn framed(body: &str) -> Vec<u8> {
    format!("Content-Length: {}\r\n\r\n{body}", body.len()).into_bytes()
}

#[test]
fn malformed_messages_get_error_responses_and_the_server_goes_on() {
    let (_dir, main, _) = setup();
    let mut c = Client::start();
    c.open(&main, MAIN);
    assert_eq!(c.diagnostics(&main), json!([]));
    let hover = |id: i64, position: Value| {
        json!({ "jsonrpc": "2.0", "id": id, "method": "textDocument/hover",
                "params": { "textDocument": { "uri": main }, "position": position } })
        .to_string()
    };
    // (what is sent, the error code, the id of the response)
    let cases: Vec<(Vec<u8>, i64, Value)> = vec![
        // Framing: −32700 with id null, and the stream is found again.
        (
            b"Content-Length: twelve\r\n\r\n{}".to_vec(),
            -32700,
            Value::Null,
        ),
        (
            b"Content-Type: application/json\r\n\r\n{}".to_vec(),
            -32700,
            Value::Null,
        ),
        (b"this is no header\r\n\r\n".to_vec(), -32700, Value::Null),
        (
            b"Content-Length: 1000000000000\r\n\r\n{\"jsonrpc\":\"2.0\"}".to_vec(),
            -32700,
            Value::Null,
        ),
        (b"stray bytes, no line end".to_vec(), -32700, Value::Null),
        // Bodies that are not JSON.
        (
            framed(r#"{"jsonrpc": "2.0", "id": 5, "method": "textDocu"#),
            -32700,
            Value::Null,
        ),
        (framed("\u{0}\u{1}\u{2}PK"), -32700, Value::Null),
        // JSON that is not a message: −32600, with the id when it has one.
        (framed("[1, 2, 3]"), -32600, Value::Null),
        (framed("17"), -32600, Value::Null),
        (
            framed(r#"{"id": 41, "method": "textDocument/hover"}"#),
            -32600,
            json!(41),
        ),
        (
            framed(r#"{"jsonrpc": "2.0", "id": "x", "method": 12}"#),
            -32600,
            json!("x"),
        ),
        (
            framed(r#"{"jsonrpc": "2.0", "id": 1e40, "method": "shutdown"}"#),
            -32600,
            json!(1e40),
        ),
        // Requests with bad params: −32602; unknown methods: −32601.
        (
            framed(
                &json!({ "jsonrpc": "2.0", "id": 42, "method": "textDocument/hover",
                         "params": { "textDocument": { "uri": main } } })
                .to_string(),
            ),
            -32602,
            json!(42),
        ),
        (
            framed(&hover(43, json!({ "line": -1, "character": 0 }))),
            -32602,
            json!(43),
        ),
        (
            framed(&hover(44, json!({ "line": 4294967296u64, "character": 0 }))),
            -32602,
            json!(44),
        ),
        (
            framed(&hover(45, json!({ "line": "one", "character": 0 }))),
            -32602,
            json!(45),
        ),
        (
            framed(r#"{"jsonrpc": "2.0", "id": 46, "method": "textDocument/hover", "params": 7}"#),
            -32602,
            json!(46),
        ),
        (
            framed(r#"{"jsonrpc": "2.0", "id": 47, "method": "no/such/method"}"#),
            -32601,
            json!(47),
        ),
    ];
    for (k, (bytes, code, id)) in cases.into_iter().enumerate() {
        let sent = String::from_utf8_lossy(&bytes).into_owned();
        // A valid request right behind: the server cannot know where stray
        // bytes end before the next message begins.
        let probe = json!(format!("probe {k}"));
        let hover = json!({ "jsonrpc": "2.0", "id": probe, "method": "textDocument/hover",
                            "params": { "textDocument": { "uri": main },
                                        "position": { "line": 8, "character": 3 } } });
        let bytes = [bytes, framed(&hover.to_string())].concat();
        assert!(c.send_bytes(&bytes), "{sent:?}");
        let error = if id.is_null() {
            error_without_id(&mut c)
        } else {
            let response = c.response(&id);
            assert_eq!(response["jsonrpc"], "2.0", "{response}");
            response["error"].clone()
        };
        assert_eq!(error["code"], code, "{sent:?}: {error}");
        assert!(error["message"].is_string(), "{sent:?}: {error}");
        // The valid request sent afterwards is still answered.
        let hover = c.response(&probe);
        assert_eq!(
            hover["result"]["range"],
            range(8, 2, 8, 8),
            "after {sent:?}"
        );
    }
    // Positions past the end of a line or of the text are the end.
    assert_eq!(
        c.at("textDocument/hover", &main, u32::MAX, u32::MAX),
        Value::Null
    );
    assert_eq!(c.exited(), None, "{}", c.stderr());
    c.shutdown();
}

#[test]
fn the_server_exits_only_on_exit_or_at_the_end_of_its_input() {
    // After `shutdown`, requests are refused until `exit`, which ends the
    // server with status 0.
    let (_dir, main, _) = setup();
    let mut c = Client::start();
    c.open(&main, MAIN);
    assert_eq!(c.request("shutdown", Value::Null), Value::Null);
    c.send_bytes(b"garbage\r\n\r\n");
    assert_eq!(error_without_id(&mut c)["code"], -32700);
    let refused = c.call(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": main } }),
    );
    assert_eq!(refused["error"]["code"], -32600, "{refused}");
    assert_eq!(c.exited(), None);
    c.notify("exit", Value::Null);
    assert_eq!(c.wait().code(), Some(0));

    // `exit` without `shutdown`: status 1, as the LSP specifies.
    let mut c = Client::start();
    c.send_bytes(&framed("{}"));
    assert_eq!(error_without_id(&mut c)["code"], -32600);
    c.notify("exit", Value::Null);
    assert_eq!(c.wait().code(), Some(1));

    // Before `initialize`: requests are refused (−32002), bad messages get
    // their errors, and the server waits for `initialize`.
    let mut c = Client::spawn();
    let early = c.call("textDocument/hover", json!({}));
    assert_eq!(early["error"]["code"], -32002, "{early}");
    c.send_bytes(b"Content-Length: -3\r\n\r\n");
    assert_eq!(error_without_id(&mut c)["code"], -32700);
    let bad_init = c.call("initialize", json!({ "capabilities": 5 }));
    assert_eq!(bad_init["error"]["code"], -32602, "{bad_init}");
    let init = c.request("initialize", json!({ "capabilities": {} }));
    assert_eq!(init["serverInfo"]["name"], "scen");

    // The end of the input ends it too (without `shutdown`: status 1).
    c.close_stdin();
    assert_eq!(c.wait().code(), Some(1));
}

#[test]
fn an_oversized_document_is_diagnosed_once_and_not_analysed_per_edit() {
    use scen::scenario::loader::MAX_SCENARIO_BYTES;
    let (dir, main, _) = setup();
    // `big.scen` sorts before `main.scen`: in one publication of every
    // document's diagnostics, the big one's would come first.
    std::fs::write(dir.path().join("big.scen"), "").unwrap();
    let big = uri(&dir.path().join("big.scen"));
    let filler = MAX_SCENARIO_BYTES as usize + 1 - MAIN.len();
    let text = format!("{MAIN}#{}", "x".repeat(filler - 1));
    assert_eq!(text.len() as u64, MAX_SCENARIO_BYTES + 1);
    let mut c = Client::start();
    c.open(&big, &text);
    let d = c.diagnostics(&big);
    assert_eq!(d.as_array().unwrap().len(), 1, "{d}");
    assert_eq!(d[0]["code"], "scen::load::too_large");
    assert_eq!(d[0]["range"], range(0, 0, 0, 0));
    assert!(
        d[0]["message"].as_str().unwrap().contains("larger than"),
        "{d}"
    );
    // Edits that keep it too large, and requests on it, answered with
    // nothing.
    for version in 2..8 {
        c.change(
            &big,
            version,
            json!([{ "range": range(1, 0, 1, 0), "text": "# one more line\n" }]),
        );
        assert_eq!(c.at("textDocument/completion", &big, 1, 0), Value::Null);
        assert_eq!(c.at("textDocument/hover", &big, 5, 6), Value::Null);
        assert_eq!(c.at("textDocument/definition", &big, 5, 14), Value::Null);
    }
    let symbols = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": big } }),
    );
    assert_eq!(symbols, json!([]));
    // Another document opened: its diagnostics come, the big one's are not
    // published again (not after its edits, not after this change).
    c.open(&main, MAIN);
    let mut published = Vec::new();
    loop {
        let message = c.receive();
        if message["method"] == "textDocument/publishDiagnostics" {
            let uri = message["params"]["uri"].as_str().unwrap().to_string();
            published.push(uri.clone());
            if uri == main {
                assert_eq!(message["params"]["diagnostics"], json!([]));
                break;
            }
        }
    }
    assert_eq!(published, [main.as_str()]);
    assert!(
        c.notifications
            .iter()
            .all(|n| n["params"]["uri"] != big.as_str()),
        "published again"
    );
    // Made small again: analysed again; too large again: diagnosed again.
    c.change(&big, 20, json!([{ "text": MAIN }]));
    assert_eq!(c.diagnostics(&big), json!([]));
    assert_eq!(c.labels(&big, 8, 9), ["center", "corner"]);
    c.change(&big, 21, json!([{ "text": text }]));
    let d = c.diagnostics(&big);
    assert_eq!(d[0]["code"], "scen::load::too_large", "{d}");
    c.shutdown();
}

/// The loader's bounds hold in the server too (issue: a file included
/// twice per level, 24 levels deep, ran past 60 s; a FIFO hung it): the
/// document's diagnostics come at once, and the server answers after.
#[test]
fn includes_that_double_at_every_level_or_are_fifos_are_refused_at_once() {
    let dir = common::TempDir::new("lsp-includes");
    for k in 0..24 {
        let next = format!("include \"_twice_{}.scen\"\n", k + 1);
        std::fs::write(dir.path().join(format!("_twice_{k}.scen")), next.repeat(2)).expect("write");
    }
    std::fs::write(
        dir.path().join("_twice_24.scen"),
        "# the bottom of the chain: forty bytes.\n",
    )
    .expect("write");
    let main = dir.path().join("main.scen");
    let text = format!("include \"_twice_0.scen\"\n{MAIN}");
    std::fs::write(&main, &text).expect("write");
    let main = uri(&main);
    let mut c = Client::start();
    c.open(&main, &text);
    let diags = c.diagnostics(&main);
    assert!(
        diags.to_string().contains("scen::load::too_large"),
        "{diags}"
    );
    #[cfg(unix)]
    {
        let fifo = dir.path().join("pipe.scen");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success());
        assert!(made, "mkfifo");
        let other = dir.path().join("other.scen");
        let text = format!("include \"pipe.scen\"\n{MAIN}");
        std::fs::write(&other, &text).expect("write");
        let other = uri(&other);
        c.open(&other, &text);
        let diags = c.diagnostics(&other);
        assert!(
            diags.to_string().contains("scen::load::not_regular"),
            "{diags}"
        );
    }
    // Still answering.
    let symbols = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": main } }),
    );
    assert!(symbols.is_array(), "{symbols}");
    c.shutdown();
}
