//! The server's side of the stdio transport: `Content-Length` framing read
//! by our own reader, which answers a malformed message with a JSON-RPC
//! error and goes on to the next one (lsp-server's reader thread stops at
//! the first one), and writing.
//!
//! Nothing the client sends can make the reader hold more than
//! [`MAX_HEADER_BYTES`] of header or [`MAX_BODY_BYTES`] of body: a longer
//! header is refused as it is read, a larger body before it is read.

use std::io::{self, Read, Write};

use lsp_server::{ErrorCode, Message};
use serde_json::{Value, json};

/// The largest header block (all its lines) taken.
pub(crate) const MAX_HEADER_BYTES: usize = 8 << 10;
/// The largest body taken: above the loader's bound on a scenario's text,
/// so that an oversized document still arrives and is diagnosed.
pub(crate) const MAX_BODY_BYTES: usize = 64 << 20;
const _: () = assert!(MAX_BODY_BYTES as u64 > crate::scenario::loader::MAX_SCENARIO_BYTES);
/// How much is read from the input at once.
const CHUNK: usize = 64 << 10;
const CONTENT_LENGTH: &[u8] = b"content-length:";

/// A message that was not taken: the error response it gets (with `id`
/// null when none could be read from it).
#[derive(Debug)]
pub(crate) struct Rejected {
    pub id: Value,
    pub code: ErrorCode,
    pub message: String,
}

impl Rejected {
    fn parse_error(message: String) -> Rejected {
        Rejected {
            id: Value::Null,
            code: ErrorCode::ParseError,
            message,
        }
    }

    pub(crate) fn response(&self) -> Value {
        json!({
            "jsonrpc": "2.0",
            "id": self.id,
            "error": { "code": self.code as i32, "message": self.message },
        })
    }
}

/// One framed message from the client, or why it was refused.
pub(crate) type Incoming = Result<Message, Rejected>;

/// Reads framed messages from a byte stream.
pub(crate) struct Reader<R> {
    input: R,
    /// Bytes read and not yet taken: `buf[start..]`.
    buf: Vec<u8>,
    start: usize,
    /// After a refused header the stream is out of step: the next message
    /// is looked for at the next `Content-Length:` after the refused
    /// header's first byte (so that stray bytes run into the next header's
    /// line do not hide it; the body, if any, that the refused header
    /// announced is skipped over that way).
    lost: bool,
}

impl<R: Read> Reader<R> {
    pub(crate) fn new(input: R) -> Self {
        Reader {
            input,
            buf: Vec::new(),
            start: 0,
            lost: false,
        }
    }

    /// The next message, or `None` at the end of the input (or when it
    /// ends inside a message).
    pub(crate) fn next_message(&mut self) -> io::Result<Option<Incoming>> {
        if self.lost && !self.find_header()? {
            return Ok(None);
        }
        self.lost = false;
        self.compact();
        let header_start = self.start;
        let length = match self.header()? {
            None => return Ok(None),
            Some(Ok(length)) => length,
            Some(Err(why)) => {
                self.start = header_start + 1;
                self.lost = true;
                return Ok(Some(Err(Rejected::parse_error(why))));
            }
        };
        if length > MAX_BODY_BYTES {
            // Refused before its body is read: the client may never send
            // that many bytes, and the next message must still be found.
            self.lost = true;
            return Ok(Some(Err(Rejected::parse_error(format!(
                "a message of {length} bytes is larger than the limit of {} MiB",
                MAX_BODY_BYTES >> 20
            )))));
        }
        while self.buf.len() - self.start < length {
            if !self.fill()? {
                return Ok(None);
            }
        }
        let body = &self.buf[self.start..self.start + length];
        self.start += length;
        Ok(Some(classify(body)))
    }

    /// Drops the bytes taken.
    fn compact(&mut self) {
        self.buf.drain(..self.start);
        self.start = 0;
    }

    /// Reads more input into the buffer (keeping what was taken: a refused
    /// header is searched again from its start); `false` at the end of the
    /// input.
    fn fill(&mut self) -> io::Result<bool> {
        let old = self.buf.len();
        self.buf.resize(old + CHUNK, 0);
        let read = loop {
            match self.input.read(&mut self.buf[old..]) {
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                other => break other,
            }
        };
        self.buf.truncate(old + *read.as_ref().unwrap_or(&0));
        Ok(read? > 0)
    }

    /// Skips to the next `Content-Length:` (any case); `false` when the
    /// input ends first.
    fn find_header(&mut self) -> io::Result<bool> {
        loop {
            let pending = &self.buf[self.start..];
            if let Some(k) = pending
                .windows(CONTENT_LENGTH.len())
                .position(|w| w.eq_ignore_ascii_case(CONTENT_LENGTH))
            {
                self.start += k;
                return Ok(true);
            }
            // Keep what could be the start of a `Content-Length:` cut in two.
            let keep = (CONTENT_LENGTH.len() - 1).min(pending.len());
            self.start = self.buf.len() - keep;
            self.compact();
            if !self.fill()? {
                return Ok(false);
            }
        }
    }

    /// Reads a header block up to its empty line: the body's length, or why
    /// the header is refused; `None` at the end of the input.
    fn header(&mut self) -> io::Result<Option<Result<usize, String>>> {
        let mut length = None;
        let mut used = 0;
        let mut lines = 0;
        loop {
            let line = match self.line(MAX_HEADER_BYTES.saturating_sub(used))? {
                Line::Text(line) => line,
                Line::TooLong => {
                    return Ok(Some(Err(format!(
                        "a message header longer than {MAX_HEADER_BYTES} bytes"
                    ))));
                }
                Line::End => return Ok(None),
            };
            used += line.len() + 1;
            let text = String::from_utf8_lossy(&line);
            let text = text.trim_end_matches('\r');
            // A line end left after a body is not a header.
            if text.is_empty() && lines == 0 {
                continue;
            }
            lines += 1;
            if text.is_empty() {
                return Ok(Some(length.ok_or_else(|| {
                    "a message header without `Content-Length`".to_string()
                })));
            }
            let Some((name, value)) = text.split_once(':') else {
                return Ok(Some(Err(format!(
                    "a malformed message header line: {:?}",
                    clip(text)
                ))));
            };
            if name.trim().eq_ignore_ascii_case("content-length") {
                match value.trim().parse::<u64>() {
                    Ok(n) => length = Some(usize::try_from(n).unwrap_or(usize::MAX)),
                    Err(_) => {
                        return Ok(Some(Err(format!(
                            "`Content-Length` is not a number of bytes: {:?}",
                            clip(value.trim())
                        ))));
                    }
                }
            }
        }
    }

    /// The next line, without its `\n`, if it has at most `max` bytes.
    fn line(&mut self, max: usize) -> io::Result<Line> {
        let mut searched = 0;
        loop {
            let pending = &self.buf[self.start..];
            if let Some(k) = pending[searched..].iter().position(|&b| b == b'\n') {
                let end = searched + k;
                if end > max {
                    return Ok(Line::TooLong);
                }
                let line = pending[..end].to_vec();
                self.start += end + 1;
                return Ok(Line::Text(line));
            }
            searched = pending.len();
            if searched > max {
                return Ok(Line::TooLong);
            }
            if !self.fill()? {
                return Ok(Line::End);
            }
        }
    }
}

enum Line {
    Text(Vec<u8>),
    TooLong,
    /// The input ended first.
    End,
}

/// At most 80 characters of `text`, for an error message.
fn clip(text: &str) -> String {
    text.chars().take(80).collect()
}

/// A body as a message: −32700 when it is not JSON, −32600 when it is JSON
/// but not a JSON-RPC 2.0 request, notification or response (with its `id`
/// when it has a usable one).
fn classify(body: &[u8]) -> Incoming {
    let value: Value = serde_json::from_slice(body)
        .map_err(|e| Rejected::parse_error(format!("the message is not JSON: {e}")))?;
    let invalid = |id: Value, message: &str| Rejected {
        id,
        code: ErrorCode::InvalidRequest,
        message: message.to_string(),
    };
    let Some(object) = value.as_object() else {
        return Err(invalid(
            Value::Null,
            "a message is a JSON object (batches are not part of the protocol)",
        ));
    };
    let id = match object.get("id") {
        Some(id @ (Value::Number(_) | Value::String(_))) => id.clone(),
        _ => Value::Null,
    };
    if object.get("jsonrpc").and_then(Value::as_str) != Some("2.0") {
        return Err(invalid(id, "a message has `\"jsonrpc\": \"2.0\"`"));
    }
    let has_id = object.contains_key("id");
    match serde_json::from_value(value) {
        // An `id` that lsp-server cannot hold (a float, a number past i32,
        // null) would make a request a notification, left unanswered.
        Ok(Message::Notification(_)) if has_id => Err(invalid(
            id,
            "a request's `id` is an integer (32 bits) or a string",
        )),
        Ok(message) => Ok(message),
        Err(_) => Err(invalid(
            id,
            "not a request (`id`, `method`), a notification (`method`) or a response (`id`, \
             `result` or `error`)",
        )),
    }
}

/// Writes one message with its `Content-Length` header.
pub(crate) fn write_message(out: &mut impl Write, message: &Value) -> io::Result<()> {
    let body = message.to_string();
    write!(out, "Content-Length: {}\r\n\r\n{body}", body.len())?;
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(body: &str) -> String {
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    }

    /// Every message of `input`: the method of a taken one, or the code and
    /// id of a refused one.
    fn read_all(input: &[u8]) -> Vec<String> {
        let mut reader = Reader::new(input);
        let mut out = Vec::new();
        while let Some(m) = reader.next_message().unwrap() {
            out.push(match m {
                Ok(Message::Request(r)) => format!("request {}", r.method),
                Ok(Message::Notification(n)) => format!("notification {}", n.method),
                Ok(Message::Response(r)) => format!("response {}", r.id),
                Err(r) => format!("error {} {}", r.code as i32, r.id),
            });
        }
        out
    }

    const PING: &str = r#"{"jsonrpc":"2.0","id":7,"method":"ping"}"#;

    #[test]
    fn well_framed_messages_are_taken_in_order() {
        let input = frame(PING)
            + "\r\n"
            + &frame(r#"{"jsonrpc":"2.0","method":"exit"}"#)
            + &format!("content-length: {}\nContent-Type: x\n\n", PING.len())
            + PING;
        assert_eq!(
            read_all(input.as_bytes()),
            ["request ping", "notification exit", "request ping"]
        );
    }

    #[test]
    fn malformed_headers_are_refused_and_the_next_message_is_found() {
        for bad in [
            "Content-Length: abc\r\n\r\n{}".to_string(),
            "Content-Type: text\r\n\r\n{\"jsonrpc\":\"2.0\"}".to_string(),
            "garbage without a colon\r\n\r\n".to_string(),
            "Content-Length: 99999999999999999999999\r\n\r\n{".to_string(),
            format!("Content-Length: {}\r\n\r\n{{", MAX_BODY_BYTES + 1),
            "x".repeat(3 * MAX_HEADER_BYTES),
            format!("X: {}\r\n\r\n", "y".repeat(MAX_HEADER_BYTES)),
            // Stray bytes without a line end run into the next header line.
            "stray bytes".to_string(),
            "x: y".to_string(),
            "two\nlines".to_string(),
        ] {
            let input = bad.clone() + &frame(PING);
            assert_eq!(
                read_all(input.as_bytes()),
                ["error -32700 null", "request ping"],
                "{bad:?}"
            );
        }
    }

    #[test]
    fn bodies_that_are_not_messages_get_their_codes() {
        let cases = [
            ("{\"jsonrpc\":\"2.0\",", "error -32700 null"),
            ("\u{0}\u{1}binary", "error -32700 null"),
            ("[1, 2]", "error -32600 null"),
            ("42", "error -32600 null"),
            (r#"{"id":3,"method":"ping"}"#, "error -32600 3"),
            (
                r#"{"jsonrpc":"1.0","id":"a","method":"ping"}"#,
                "error -32600 \"a\"",
            ),
            (r#"{"jsonrpc":"2.0","id":4,"method":5}"#, "error -32600 4"),
            (r#"{"jsonrpc":"2.0","id":4}"#, "error -32600 4"),
            (
                r#"{"jsonrpc":"2.0","id":9999999999,"method":"ping"}"#,
                "error -32600 9999999999",
            ),
            (
                r#"{"jsonrpc":"2.0","id":null,"method":"ping"}"#,
                "error -32600 null",
            ),
            (
                r#"{"jsonrpc":"2.0","id":1.5,"method":"ping"}"#,
                "error -32600 1.5",
            ),
        ];
        for (body, expected) in cases {
            let input = frame(body) + &frame(PING);
            assert_eq!(
                read_all(input.as_bytes()),
                [expected, "request ping"],
                "{body:?}"
            );
        }
    }

    #[test]
    fn the_input_may_end_anywhere() {
        let whole = frame(PING);
        for cut in 0..whole.len() {
            let got = read_all(&whole.as_bytes()[..cut]);
            assert!(got.is_empty(), "cut at {cut}: {got:?}");
        }
    }

    #[test]
    fn a_body_arriving_in_small_pieces_is_put_together() {
        /// Gives one byte per read.
        struct Trickle<'a>(&'a [u8]);
        impl Read for Trickle<'_> {
            fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
                let Some((&b, rest)) = self.0.split_first() else {
                    return Ok(0);
                };
                out[0] = b;
                self.0 = rest;
                Ok(1)
            }
        }
        let input = "Content-Length: x\r\n\r\n".to_string() + &frame(PING) + &frame(PING);
        let mut reader = Reader::new(Trickle(input.as_bytes()));
        let mut methods = Vec::new();
        while let Some(m) = reader.next_message().unwrap() {
            methods.push(m.map(|m| matches!(m, Message::Request(_))).is_ok());
        }
        assert_eq!(methods, [false, true, true]);
    }
}
