//! A seeded fuzzer for `scen lsp` (the real binary over stdio).
//!
//! One server, one open document. Each round writes a burst of one to four
//! bad or odd messages — random bytes, truncated JSON, JSON that is not a
//! message, garbled headers, a `Content-Length` far past the body bound or
//! one that lies about its body, params of the wrong types, positions that
//! are negative or overflow, edits at random ranges, unknown methods —
//! and, right behind them, a valid request (the probe).
//!
//! Oracles: the probe is answered with a result within 30 s (no hang, the
//! stream is found again after every malformed message), the server never
//! ends and never panics (not even a panic it catches), and at the end
//! `shutdown` and `exit` end it with status 0.
//!
//! The budget: `SCEN_FUZZ_SECONDS` (default 3) and optionally
//! `SCEN_FUZZ_INPUTS`, a number of rounds. Round k's bytes depend only on
//! the seed (`SCEN_FUZZ_SEED`, default 20261122) and k; the server's state
//! on the rounds before it, so a failure is reproduced by running the same
//! seed up to that round (`SCEN_FUZZ_INPUTS=k+1`).

mod common;

use std::time::{Duration, Instant};

use common::TempDir;
use common::lsp_client::{Client, PATIENCE, uri};
use scen::rng::SplitMix64;
use serde_json::{Value, json};

const DEFAULT_SECONDS: f64 = 3.0;
const DEFAULT_SEED: u64 = 20261122;

/// The document the rounds edit; put back every [`RESET_EVERY`] rounds so
/// that random edits do not grow it without end.
const DOC: &str = "\
robot dot disk 0.25
world {
  bounds (0, 0) (10, 10)
  rect R (2, 2) (4, 4)
  polygon P [(6, 6), (8, 6), (7, 8)]
}
plan p astar dot {
  start (1, 1)
  goal (8, 1)
}
expect p.found and p.cost < 20
";
const RESET_EVERY: usize = 50;

/// Methods the rounds call (never `shutdown` or `exit`, which end the
/// session as they should).
const METHODS: &[&str] = &[
    "textDocument/hover",
    "textDocument/completion",
    "textDocument/definition",
    "textDocument/references",
    "textDocument/documentSymbol",
    "textDocument/formatting",
    "textDocument/didChange",
    "textDocument/didOpen",
    "textDocument/didClose",
    "textDocument/didSave",
    "initialize",
    "initialized",
    "$/cancelRequest",
    "workspace/symbol",
    "no/such/method",
    "",
];

/// Numbers where a position, an id or a version is expected.
const ODD_NUMBERS: &[&str] = &[
    "-1",
    "0",
    "3",
    "2147483647",
    "2147483648",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "1e20",
    "-1e308",
    "0.5",
    "null",
    "\"7\"",
    "true",
    "[]",
    "{}",
];

struct Rng(SplitMix64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        (self.0.next_u64() % n as u64) as usize
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }

    fn bytes(&mut self, max: usize) -> Vec<u8> {
        let n = self.below(max + 1);
        (0..n).map(|_| self.0.next_u64() as u8).collect()
    }

    /// Text of odd characters: line ends, multi-byte and astral ones.
    fn text(&mut self, max: usize) -> String {
        const PIECES: &[&str] = &[
            "a", "plan", " ", "\n", "\r\n", "{", "}", "(", ")", "[", "\"", "#", "é", "𝄞", "\t",
            "1e9", ".", ",", "\u{0}", "\u{feff}",
        ];
        let n = self.below(max + 1);
        (0..n).map(|_| self.pick(PIECES)).collect()
    }

    fn position(&mut self) -> String {
        let number = |rng: &mut Rng| {
            if rng.below(3) == 0 {
                rng.pick(ODD_NUMBERS).to_string()
            } else {
                rng.below(14).to_string()
            }
        };
        format!(
            "{{\"line\":{},\"character\":{}}}",
            number(self),
            number(self)
        )
    }
}

fn framed(body: &[u8]) -> Vec<u8> {
    [
        format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes(),
        body.to_vec(),
    ]
    .concat()
}

/// A request or notification of `method` on the document, with params
/// that may be of the wrong types.
fn odd_message(rng: &mut Rng, doc: &str) -> String {
    let method = rng.pick(METHODS);
    let params = match rng.below(6) {
        0 => rng.pick(ODD_NUMBERS).to_string(),
        1 => format!("{{\"textDocument\":{{\"uri\":\"{doc}\"}}}}"),
        2 => format!(
            "{{\"textDocument\":{{\"uri\":{}}},\"position\":{}}}",
            rng.pick(&["null", "5", "\"not a uri\"", "\"file:///no/such.scen\""]),
            rng.position()
        ),
        3 => format!(
            "{{\"textDocument\":{{\"uri\":\"{doc}\",\"version\":{}}},\"contentChanges\":{}}}",
            rng.pick(ODD_NUMBERS),
            rng.pick(&["null", "5", "[{}]", "[{\"text\":5}]", "{}"])
        ),
        _ => format!(
            "{{\"textDocument\":{{\"uri\":\"{doc}\"}},\"position\":{},\"context\":{{\"includeDeclaration\":{}}}}}",
            rng.position(),
            rng.pick(&["true", "1", "null"])
        ),
    };
    let id = match rng.below(4) {
        0 => String::new(),
        _ => format!(",\"id\":{}", rng.pick(ODD_NUMBERS)),
    };
    format!("{{\"jsonrpc\":\"2.0\"{id},\"method\":\"{method}\",\"params\":{params}}}")
}

/// A valid edit at a random range (possibly past the end, or reversed) of
/// random text.
fn random_edit(rng: &mut Rng, doc: &str) -> String {
    let at = |rng: &mut Rng| json!({ "line": rng.below(16), "character": rng.below(40) });
    let change = if rng.below(8) == 0 {
        json!({ "text": rng.text(60) })
    } else {
        json!({ "range": { "start": at(rng), "end": at(rng) }, "text": rng.text(12) })
    };
    json!({ "jsonrpc": "2.0", "method": "textDocument/didChange",
            "params": { "textDocument": { "uri": doc, "version": rng.below(1000) },
                        "contentChanges": [change] } })
    .to_string()
}

/// One bad or odd message, as bytes.
fn mutation(rng: &mut Rng, doc: &str) -> Vec<u8> {
    match rng.below(10) {
        // Random bytes, unframed.
        0 => rng.bytes(300),
        // Truncated JSON, framed.
        1 => {
            let message = odd_message(rng, doc);
            let cut = rng.below(message.len());
            framed(&message.as_bytes()[..cut])
        }
        // Params of the wrong types, odd ids, unknown methods.
        2 | 3 => framed(odd_message(rng, doc).as_bytes()),
        // A length past the body bound (or past any integer), and a body.
        4 => {
            let length = rng.pick(&[
                "67108865",
                "1000000000000",
                "18446744073709551615",
                "184467440737095516160",
            ]);
            let body = rng.bytes(40);
            [
                format!("Content-Length: {length}\r\n\r\n").into_bytes(),
                body,
            ]
            .concat()
        }
        // A length that lies: shorter than the body (its rest is stray
        // bytes) or longer (padded with spaces to what it says, as a
        // client that sent it would go on).
        5 => {
            let body = odd_message(rng, doc).into_bytes();
            let declared = if rng.below(2) == 0 {
                rng.below(body.len())
            } else {
                body.len() + 1 + rng.below(100)
            };
            let mut bytes = format!("Content-Length: {declared}\r\n\r\n").into_bytes();
            bytes.extend_from_slice(&body);
            bytes.resize(bytes.len() + declared.saturating_sub(body.len()), b' ');
            bytes
        }
        // JSON that is not a message.
        6 => framed(
            rng.pick(&[
                "[]",
                "[{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"textDocument/hover\"}]",
                "null",
                "-0.0",
                "\"text\"",
                "{}",
                "{\"jsonrpc\":\"2.0\"}",
                "{\"jsonrpc\":2,\"id\":1,\"method\":\"x\"}",
                "{\"jsonrpc\":\"2.0\",\"id\":{},\"method\":\"x\"}",
                "{\"jsonrpc\":\"2.0\",\"id\":3,\"result\":1,\"error\":2}",
                "{\"jsonrpc\":\"2.0\",\"id\":3,\"result\":null}",
            ])
            .as_bytes(),
        ),
        // Garbled headers.
        7 => {
            let body = odd_message(rng, doc);
            let header = match rng.below(6) {
                0 => format!("content-length: {}\n\n", body.len()),
                1 => format!(
                    "Content-Length: {0}\r\nContent-Length: {0}\r\n\r\n",
                    body.len()
                ),
                2 => format!(
                    "Content-Length:   {}  \r\nX-Odd: \u{e9}\r\n\r\n",
                    body.len()
                ),
                3 => "Content-Length: -5\r\n\r\n".to_string(),
                4 => "Content-Length 12\r\n\r\n".to_string(),
                _ => format!(
                    "Content-Type: x\r\n{}\r\n\r\n",
                    "y".repeat(rng.below(20000))
                ),
            };
            [header.into_bytes(), body.into_bytes()].concat()
        }
        // Valid edits at random ranges.
        _ => framed(random_edit(rng, doc).as_bytes()),
    }
}

fn env_or<T: std::str::FromStr>(key: &str, default: T) -> T {
    std::env::var(key)
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(default)
}

#[test]
fn the_language_server_survives_malformed_and_random_messages() {
    let seconds: f64 = env_or("SCEN_FUZZ_SECONDS", DEFAULT_SECONDS);
    let max_rounds: usize = env_or("SCEN_FUZZ_INPUTS", usize::MAX);
    let seed: u64 = env_or("SCEN_FUZZ_SEED", DEFAULT_SEED);
    let dir = TempDir::new("fuzz-lsp");
    let path = dir.path().join("doc.scen");
    std::fs::write(&path, DOC).unwrap();
    let doc = uri(&path);
    let mut c = Client::start();
    c.open(&doc, DOC);
    let began = Instant::now();
    let mut rounds = 0;
    while rounds < max_rounds && began.elapsed() < Duration::from_secs_f64(seconds) {
        let k = rounds;
        rounds += 1;
        let mut rng = Rng(SplitMix64::new(
            seed ^ (k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15),
        ));
        let mut bytes = Vec::new();
        if k % RESET_EVERY == 0 {
            let reset = json!({ "jsonrpc": "2.0", "method": "textDocument/didChange",
                                "params": { "textDocument": { "uri": doc, "version": k },
                                            "contentChanges": [{ "text": DOC }] } });
            bytes.extend(framed(reset.to_string().as_bytes()));
        }
        for _ in 0..1 + rng.below(4) {
            bytes.extend(mutation(&mut rng, &doc));
        }
        let probe = json!(format!("probe {k}"));
        let request = json!({ "jsonrpc": "2.0", "id": probe,
                              "method": rng.pick(&["textDocument/documentSymbol", "textDocument/hover"]),
                              "params": { "textDocument": { "uri": doc },
                                          "position": { "line": 6, "character": 6 } } });
        bytes.extend(framed(request.to_string().as_bytes()));

        let failure = |c: &mut Client, what: &str| -> String {
            let shown = String::from_utf8_lossy(&bytes);
            let shown: String = shown.chars().take(3000).collect();
            format!(
                "round {k} (SCEN_FUZZ_SEED={seed} SCEN_FUZZ_INPUTS={}): {what}\n\
                 --- sent\n{shown:?}\n--- exit status: {:?}\n--- stderr\n{}",
                k + 1,
                c.exited(),
                c.stderr()
            )
        };
        if !c.send_bytes(&bytes) {
            panic!(
                "{}",
                failure(&mut c, "the server no longer reads its input")
            );
        }
        let deadline = Instant::now() + PATIENCE;
        let response = loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match c.receive_within(left) {
                Some(m) if m.get("method").is_none() && m["id"] == probe => break m,
                Some(_) => {}
                None => {
                    let what = match c.exited() {
                        Some(_) => "the server ended",
                        None => "the probe was not answered within 30 s",
                    };
                    panic!("{}", failure(&mut c, what));
                }
            }
        };
        if response.get("result").is_none() || response.get("error").is_some() {
            panic!(
                "{}",
                failure(&mut c, &format!("the probe got no result: {response}"))
            );
        }
        if c.stderr().contains("panicked") {
            panic!("{}", failure(&mut c, "the server panicked"));
        }
    }
    eprintln!(
        "fuzz_lsp: {rounds} rounds in {:.1} s (seed {seed})",
        began.elapsed().as_secs_f64()
    );
    assert!(rounds > 0);
    let _: Value = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": doc } }),
    );
    c.shutdown();
}
