//! The parts of a sharded command (`scen bench` and `scen falsify` with
//! `--shard K/N --out PART.jsonl`): reading one, and checking that a set of
//! them is whole (each K of 1 … N once).

use std::collections::BTreeSet;
use std::path::Path;

use serde_json::Value;

/// The lines of a part: its header line (whose `tag` field is 1), its
/// common fields, and the rest.
pub struct Lines {
    pub header: Value,
    pub common: Header,
    pub rest: Vec<Value>,
}

/// The error for a file that is not a part `command` writes.
pub fn not_a_part(path: &Path, command: &str) -> String {
    format!(
        "`{}` is not a part written by `{command} --shard K/N --out PART.jsonl`",
        path.display()
    )
}

/// Reads a part of at most `max_bytes`: JSON Lines whose first line is a
/// header with `"TAG": 1`.
pub fn read_lines(path: &Path, max_bytes: u64, command: &str, tag: &str) -> Result<Lines, String> {
    let bytes = crate::files::read_regular_file(path, max_bytes)
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    let bad = || not_a_part(path, command);
    let text = String::from_utf8(bytes).map_err(|_| bad())?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let (_, first) = lines.next().ok_or_else(bad)?;
    let header: Value = serde_json::from_str(first).map_err(|_| bad())?;
    if header.get(tag).and_then(Value::as_u64) != Some(1) {
        return Err(bad());
    }
    let common = Header::of(path, &header).ok_or_else(bad)?;
    // A part with a good header whose later line does not parse was cut
    // short (a copy between machines) or edited: say which line, and which
    // shard to run again.
    let shard = match (
        header.get("k").and_then(Value::as_u64),
        header.get("n").and_then(Value::as_u64),
    ) {
        (Some(k), Some(n)) => format!("shard {k}/{n}"),
        _ => "its shard".into(),
    };
    let rest = lines
        .map(|(i, l)| {
            serde_json::from_str::<Value>(l).map_err(|e| {
                // serde's message ends with its own "at line 1 column C".
                let message = e.to_string();
                let why = message.split(" at line ").next().unwrap_or_default();
                format!(
                    "line {} of the part `{}` is not JSON ({why}, column {}): the part was cut short or changed; run {shard} again",
                    i + 1,
                    path.display(),
                    e.column()
                )
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Lines {
        header,
        common,
        rest,
    })
}

/// At most this many missing parts are named in an error.
const MISSING_SHOWN: usize = 10;

/// Whether the parts (their K and file) are each K of 1 … `n` once.
fn check_whole<'a>(parts: impl IntoIterator<Item = (u64, &'a Path)>, n: u64) -> Result<(), String> {
    let mut seen = BTreeSet::new();
    for (k, path) in parts {
        if k == 0 || k > n {
            return Err(format!("`{}` says it is part {k}/{n}", path.display()));
        }
        if !seen.insert(k) {
            return Err(format!(
                "part {k}/{n} is given twice (`{}`)",
                path.display()
            ));
        }
    }
    if seen.len() as u64 != n {
        let missing: Vec<String> = (1..=n)
            .filter(|k| !seen.contains(k))
            .take(MISSING_SHOWN)
            .map(|k| format!("{k}/{n}"))
            .collect();
        let count = n - seen.len() as u64;
        return Err(format!(
            "{count} part(s) missing: {}{} (of {n} parts)",
            missing.join(", "),
            if count > MISSING_SHOWN as u64 {
                ", …"
            } else {
                ""
            }
        ));
    }
    Ok(())
}

/// What every part's first line says, whichever command wrote it: the
/// scenario it was made from (its path as given and its content hash) and
/// its shard; with the path the part was read from.
#[derive(Debug)]
pub struct Header {
    pub path: std::path::PathBuf,
    pub file: String,
    pub hash: String,
    pub k: u64,
    pub n: u64,
}

impl Header {
    /// The common fields of a part's header line, or `None`.
    fn of(path: &Path, v: &Value) -> Option<Header> {
        Some(Header {
            path: path.to_path_buf(),
            file: v.get("file")?.as_str()?.to_string(),
            hash: v.get("hash")?.as_str()?.to_string(),
            k: v.get("k")?.as_u64()?,
            n: v.get("n")?.as_u64()?,
        })
    }
}

/// A part of a sharded command, read: what the merge of either command
/// needs to know of it.
pub trait Part: Sized {
    /// The command that writes it: `scen bench` or `scen falsify`.
    const COMMAND: &'static str;
    /// Reads the part at `path`.
    fn read(path: &Path) -> Result<Self, String>;
    fn header(&self) -> &Header;
    /// What every part of one split shares (file, hash, N and the
    /// command's options), as an error names it: parts whose origins
    /// differ do not belong together.
    fn origin(&self) -> String;
}

/// The first step of `merge`, the same for both commands: the parts read
/// and shown to come from one split of one scenario.
pub fn read_parts<P: Part>(paths: &[std::path::PathBuf]) -> Result<Vec<P>, String> {
    if paths.is_empty() {
        return Err(format!(
            "`{0} merge` needs the parts: `{0} merge part-*.jsonl`",
            P::COMMAND
        ));
    }
    let parts = paths
        .iter()
        .map(|p| P::read(p))
        .collect::<Result<Vec<P>, _>>()?;
    let first = &parts[0];
    for p in &parts[1..] {
        if p.origin() != first.origin() {
            return Err(format!(
                "`{}` does not belong with `{}`: it was made from {}; the other from {}",
                p.header().path.display(),
                first.header().path.display(),
                p.origin(),
                first.origin()
            ));
        }
    }
    Ok(parts)
}

/// Whether the parts are each K of 1 … N once (after the command's own
/// checks that N is a split it makes).
pub fn whole<P: Part>(parts: &[P]) -> Result<(), String> {
    check_whole(
        parts
            .iter()
            .map(|p| (p.header().k, p.header().path.as_path())),
        parts[0].header().n,
    )
}

/// Whether the scenario the parts were made from is unchanged: its content
/// hash `now` is the one the parts recorded.
pub fn unchanged<P: Part>(first: &P, now: &str) -> Result<(), String> {
    let h = first.header();
    if now != h.hash {
        return Err(format!(
            "`{}` has changed since the parts were made (hash {now}, the parts say {})",
            h.file, h.hash
        ));
    }
    Ok(())
}
