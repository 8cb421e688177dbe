//! Reading files: the main `.scen` file, its includes (resolved relative to
//! the including file, cycles refused) and its map files, all inside the
//! scenario's *root* (SPEC 2.2), so that no input can read what it should
//! not, wait on a FIFO, or exhaust memory.
//!
//! The file-access policy (the manual's "Files a scenario reads"):
//! - the root is the folder of the file named on the command line, or
//!   `--root DIR`; an include or a map outside it is refused;
//! - only regular files are read ([`crate::files::read_regular_file`]);
//! - an include must be a `.scen` file, so that a diagnostic never quotes
//!   another kind of file (a `.env` beside the scenario);
//! - a file that is not UTF-8 is refused without quoting its bytes;
//! - the text of one scenario, includes expanded (a file included twice
//!   counts twice), is at most [`MAX_SCENARIO_BYTES`]; each file is read
//!   and parsed once however often it is included, so a file included
//!   twice per level, many levels deep, costs its expansion's size, bounded,
//!   and not one read per expansion.

use std::collections::{HashMap, HashSet};
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use crate::diagnostics::{Diag, FileId, SourceMap, Span};
use crate::files::{ReadError, human_bytes, invalid_utf8_at, read_regular_file};
use crate::syntax::{self, ast};

use super::Scenario;
use super::family::{Family, SampleChoice};

/// The largest scenario text accepted: every file, includes expanded.
pub const MAX_SCENARIO_BYTES: u64 = 16 << 20;
/// The largest map file (`grid "x.map"`) accepted.
pub const MAX_MAP_BYTES: u64 = 64 << 20;
/// How deep includes may nest.
const MAX_INCLUDE_DEPTH: usize = 32;

pub use super::statements::LoadFailure;
pub use super::statements::SourcedStmt;

/// The text of `.scen` files that are not (only) on disk: the language
/// server's open documents, by canonical path. The loader asks it first,
/// for the main file and for every include.
pub type Overlay<'a> = &'a dyn Fn(&Path) -> Option<Arc<str>>;

/// A scenario's files read and parsed, includes spliced in, maps read,
/// before analysis.
#[derive(Debug, Default)]
pub struct Parsed {
    pub sources: SourceMap,
    pub statements: Vec<SourcedStmt>,
    /// Every `include` that was followed: the span of its path string and
    /// the file it read.
    pub includes: Vec<(Span, FileId)>,
    /// Each map file named by a `grid` (by the span of its path string):
    /// its text's file, or why it could not be read (the analyzer reports
    /// it with the grid's other errors).
    pub maps: HashMap<Span, Result<FileId, Diag>>,
    /// Read and syntax errors (analysis adds its own).
    pub diags: Vec<Diag>,
}

/// Reads, parses and analyses a scenario file; its root is its folder.
pub fn load(path: &Path) -> Result<Scenario, LoadFailure> {
    load_with(path, None, &|_| None)
}

/// [`load`], with another root (`--root DIR`; `None`: the file's folder)
/// and the text of the files in `overlay` instead of the disk's.
pub fn load_with(
    path: &Path,
    root: Option<&Path>,
    overlay: Overlay<'_>,
) -> Result<Scenario, LoadFailure> {
    load_sample(path, root, overlay, SampleChoice::default())
}

/// [`load_with`] for one sample of a family (SPEC 2.8); a scenario without
/// params is its own only sample.
pub fn load_sample(
    path: &Path,
    root: Option<&Path>,
    overlay: Overlay<'_>,
    choice: SampleChoice,
) -> Result<Scenario, LoadFailure> {
    load_member(path, root, overlay, choice, &[])
}

/// [`load_sample`] with some drawn params' values given as `NAME=VALUE`
/// (`scen run --set`, what `scen falsify` reports): the scattered items
/// still come from sample `choice`'s stream.
pub fn load_member(
    path: &Path,
    root: Option<&Path>,
    overlay: Overlay<'_>,
    choice: SampleChoice,
    set: &[String],
) -> Result<Scenario, LoadFailure> {
    let mut parsed = parse_scenario(path, root, overlay);
    if parsed.diags.iter().any(Diag::is_error) {
        crate::diagnostics::sort_diags(&mut parsed.diags);
        return Err(LoadFailure {
            sources: parsed.sources,
            diags: parsed.diags,
        });
    }
    analyze_sample(
        path,
        parsed.statements,
        parsed.sources,
        parsed.maps,
        choice,
        set,
    )
}

/// Analyses statements with nothing left to draw (a family's sample).
pub fn analyze_statements(
    path: &Path,
    statements: Vec<SourcedStmt>,
    sources: SourceMap,
    maps: HashMap<Span, Result<FileId, Diag>>,
) -> Result<Scenario, LoadFailure> {
    super::analyze(path, statements, sources, maps)
}

/// Analyses sample `choice` of the parsed statements: a plain scenario
/// directly, a family's sample drawn (and drawn again when rejected) first.
pub fn analyze_sample(
    path: &Path,
    statements: Vec<SourcedStmt>,
    sources: SourceMap,
    maps: HashMap<Span, Result<FileId, Diag>>,
    choice: SampleChoice,
    set: &[String],
) -> Result<Scenario, LoadFailure> {
    let family = match Family::of(&statements) {
        Ok(f) => f,
        Err(mut diags) => {
            crate::diagnostics::sort_diags(&mut diags);
            return Err(LoadFailure { sources, diags });
        }
    };
    let set = match family.resolve_set(set) {
        Ok(s) => s,
        Err(mut diags) => {
            crate::diagnostics::sort_diags(&mut diags);
            return Err(LoadFailure { sources, diags });
        }
    };
    let result = if family.is_active() {
        family
            .sample(&statements, choice, &set, |instance| {
                super::analyze(path, instance, sources.clone(), maps.clone()).map_err(|f| f.diags)
            })
            .map(|(mut scenario, drawn)| {
                scenario.family = family.draws().then_some(drawn);
                scenario
            })
    } else {
        super::analyze(path, statements.clone(), sources.clone(), maps.clone()).map_err(|f| f.diags)
    };
    match result {
        Ok(mut scenario) => {
            // `worlds N` runs samples 0 … N − 1: only a family has them.
            if !family.draws()
                && let Some(span) = scenario.benches.iter().find_map(|b| b.worlds_span)
            {
                return Err(LoadFailure {
                    sources,
                    diags: vec![
                        Diag::error(
                            "scen::analyze::worlds_without_family",
                            "`worlds` runs the samples of a family, and this scenario draws nothing",
                        )
                        .at(span, "every world would be the same")
                        .help("draw something with `param NAME = uniform(a, b)` or a `scatter`, or use `runs` for more seeds"),
                    ],
                });
            }
            if family.draws() {
                scenario.template = Some(Arc::new(Template {
                    path: path.to_path_buf(),
                    statements,
                    sources: scenario.sources.clone(),
                    maps,
                    family_seed: choice.family_seed,
                }));
            }
            Ok(scenario)
        }
        Err(mut diags) => {
            crate::diagnostics::sort_diags(&mut diags);
            Err(LoadFailure { sources, diags })
        }
    }
}

/// What it takes to draw another sample of a family: its statements
/// before analysis, as read.
#[derive(Debug)]
pub struct Template {
    path: PathBuf,
    statements: Vec<SourcedStmt>,
    sources: SourceMap,
    maps: HashMap<Span, Result<FileId, Diag>>,
    family_seed: u64,
}

impl Scenario {
    /// Sample `k` of the family this scenario was drawn from (same family
    /// seed); a scenario that draws nothing is its own only sample.
    pub fn sample(&self, k: u64) -> Result<Scenario, LoadFailure> {
        let Some(t) = &self.template else {
            return Ok(self.clone());
        };
        analyze_sample(
            &t.path,
            t.statements.clone(),
            t.sources.clone(),
            t.maps.clone(),
            SampleChoice {
                sample: k,
                family_seed: t.family_seed,
            },
            &[],
        )
    }
}

/// Reads and parses a scenario file, its includes and its maps (the first
/// half of [`load_with`]); the main file is [`FileId`] 0 when it could be
/// read.
pub fn parse_scenario(path: &Path, root: Option<&Path>, overlay: Overlay<'_>) -> Parsed {
    let root = canonical(root.unwrap_or_else(|| match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }));
    let mut reader = Reader {
        root,
        overlay,
        parsed: Parsed::default(),
        files: HashMap::new(),
        read: HashMap::new(),
        included: HashMap::new(),
        reported: HashSet::new(),
        total_bytes: 0,
        stopped: false,
    };
    let canon = canonical(path);
    if !canon.starts_with(&reader.root) {
        reader.parsed.diags.push(
            Diag::error(
                "scen::load::outside_root",
                format!(
                    "`{}` lies outside the root `{}`",
                    path.display(),
                    reader.root.display()
                ),
            )
            .help("the file named on the command line must lie inside `--root DIR`"),
        );
        return reader.parsed;
    }
    match reader.read_scen(path, &canon, None) {
        Ok(id) if reader.count(id) => reader.parse_into(id, true, &mut vec![id]),
        Ok(_) => {
            let d = scenario_too_large(path, None, &mut reader.parsed.sources);
            reader.parsed.diags.push(d);
        }
        Err(d) => reader.parsed.diags.push(d),
    }
    reader.parsed
}

/// The path with symbolic links resolved where it exists; otherwise made
/// absolute and free of `.` and `..` by its text alone, so that a missing
/// file is still placed inside or outside the root.
pub fn canonical(path: &Path) -> PathBuf {
    if let Ok(p) = path.canonicalize() {
        return p;
    }
    let absolute = std::env::current_dir()
        .map(|d| d.join(path))
        .unwrap_or_else(|_| path.to_path_buf());
    let mut out = PathBuf::new();
    for c in absolute.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// A `.scen` file read once: its statements and its length.
struct ReadFile {
    statements: Arc<Vec<ast::Stmt>>,
    bytes: u64,
}

struct Reader<'a> {
    root: PathBuf,
    overlay: Overlay<'a>,
    parsed: Parsed,
    /// Every `.scen` file read, by canonical path: a file is read and
    /// parsed once however often it is included.
    files: HashMap<PathBuf, FileId>,
    /// Each `.scen` file read.
    read: HashMap<FileId, ReadFile>,
    /// What each `include` (by the span of its path) led to: the file, or
    /// `None` when it was refused (its error is reported once). A file
    /// included many times is resolved once: resolving asks the file system
    /// about every component of the path.
    included: HashMap<Span, Option<FileId>>,
    /// Includes whose cycle or depth error was reported (once each).
    reported: HashSet<Span>,
    /// The scenario's text so far, includes expanded.
    total_bytes: u64,
    /// The size bound was crossed: nothing more is read.
    stopped: bool,
}

impl Reader<'_> {
    /// Splices in the statements of file `id`; `stack` holds the files that
    /// include it (itself last).
    fn parse_into(&mut self, id: FileId, in_main_file: bool, stack: &mut Vec<FileId>) {
        let Some(statements) = self.read.get(&id).map(|f| f.statements.clone()) else {
            return;
        };
        for stmt in statements.iter() {
            if self.stopped {
                return;
            }
            match stmt {
                ast::Stmt::Include { path, span } => self.include(id, path, *span, stack),
                ast::Stmt::Robot(ast::RobotDecl {
                    team: Some(team), ..
                }) if matches!(**team, ast::TeamBody::From { .. }) => {
                    // A team's MovingAI scenario is read like a map.
                    if let ast::TeamBody::From { file, .. } = &**team {
                        self.map(id, file);
                    }
                    self.parsed.statements.push(SourcedStmt {
                        stmt: stmt.clone(),
                        in_main_file,
                    });
                }
                ast::Stmt::World(w) => {
                    for item in &w.items {
                        if let ast::WorldItem::Obstacle(ast::ObstacleDecl {
                            shape: ast::ObstacleShape::Grid(g),
                            ..
                        }) = item
                            && let Some(file) = &g.file
                        {
                            self.map(id, file);
                        }
                    }
                    self.parsed.statements.push(SourcedStmt {
                        stmt: stmt.clone(),
                        in_main_file,
                    });
                }
                _ => self.parsed.statements.push(SourcedStmt {
                    stmt: stmt.clone(),
                    in_main_file,
                }),
            }
        }
    }

    /// The folder of file `id`, where the paths it names start.
    fn folder_of(&self, id: FileId) -> PathBuf {
        self.parsed
            .sources
            .get(id)
            .and_then(|f| f.path.parent().map(Path::to_path_buf))
            .unwrap_or_default()
    }

    fn include(
        &mut self,
        from: FileId,
        path: &crate::diagnostics::Spanned<String>,
        span: Span,
        stack: &mut Vec<FileId>,
    ) {
        let child = match self.included.get(&path.span) {
            Some(&child) => child,
            None => {
                let child = match self.resolve_include(from, path) {
                    Ok(child) => Some(child),
                    Err(d) => {
                        self.parsed.diags.push(d);
                        None
                    }
                };
                self.included.insert(path.span, child);
                child
            }
        };
        let Some(child) = child else {
            return;
        };
        if stack.contains(&child) {
            if self.reported.insert(path.span) {
                self.parsed.diags.push(
                    Diag::error(
                        "scen::load::include_cycle",
                        format!(
                            "`{}` includes itself (through {} file(s))",
                            path.value,
                            stack.len()
                        ),
                    )
                    .at(path.span, "this include closes a cycle")
                    .help("remove one of the includes; a file may be included only once along a chain"),
                );
            }
            return;
        }
        if stack.len() >= MAX_INCLUDE_DEPTH {
            if self.reported.insert(path.span) {
                self.parsed.diags.push(
                    Diag::error("scen::load::include_depth", "includes nest too deeply")
                        .at(
                            span,
                            format!("more than {MAX_INCLUDE_DEPTH} nested includes"),
                        )
                        .help("flatten the chain of includes"),
                );
            }
            return;
        }
        if !self.count(child) {
            let target = self.folder_of(from).join(&path.value);
            let d = scenario_too_large(&target, Some(path.span), &mut self.parsed.sources);
            self.parsed.diags.push(d);
            return;
        }
        self.parsed.includes.push((path.span, child));
        stack.push(child);
        self.parse_into(child, false, stack);
        stack.pop();
    }

    /// The file an include names, read and parsed (once), or why not.
    #[allow(clippy::result_large_err)]
    fn resolve_include(
        &mut self,
        from: FileId,
        path: &crate::diagnostics::Spanned<String>,
    ) -> Result<FileId, Diag> {
        let target = self.folder_of(from).join(&path.value);
        if target.extension().is_none_or(|e| e != "scen") {
            return Err(Diag::error(
                "scen::load::not_scen",
                format!("`{}` is not a `.scen` file", path.value),
            )
            .at(path.span, "not a scenario file")
            .help("`include` reads scenario files (`NAME.scen`); a MovingAI map is read with `grid NAME \"file.map\" cell 1 origin (0, 0)` in the world"));
        }
        let canon = canonical(&target);
        self.inside_root(&canon, &path.value, path.span)?;
        self.read_scen(&target, &canon, Some(path.span))
    }

    /// Refuses a file outside the root, at the string that named it.
    #[allow(clippy::result_large_err)]
    fn inside_root(&self, canon: &Path, written: &str, at: Span) -> Result<(), Diag> {
        if canon.starts_with(&self.root) {
            return Ok(());
        }
        Err(Diag::error(
            "scen::load::outside_root",
            format!(
                "`{written}` lies outside the scenario's root `{}`",
                self.root.display()
            ),
        )
        .at(at, "outside the root")
        .help("a scenario reads only files inside the folder of the file named on the command line; move the file there, or widen the root with `--root DIR`"))
    }

    /// A `.scen` file's text and statements: the overlay's if it has the
    /// file, else the disk's; read and parsed once.
    #[allow(clippy::result_large_err)]
    fn read_scen(&mut self, path: &Path, canon: &Path, from: Option<Span>) -> Result<FileId, Diag> {
        if let Some(&id) = self.files.get(canon) {
            return Ok(id);
        }
        let text: Arc<str> = match (self.overlay)(canon) {
            Some(text) if text.len() as u64 > MAX_SCENARIO_BYTES => {
                return Err(scenario_too_large(path, from, &mut self.parsed.sources));
            }
            Some(text) => text,
            None => read_text(
                path,
                MAX_SCENARIO_BYTES,
                from,
                "scenario",
                &mut self.parsed.sources,
            )?,
        };
        let bytes = text.len() as u64;
        let id = self.parsed.sources.add(path, text.clone());
        let (ast, mut errors) = syntax::parse(&text, id);
        self.parsed.diags.append(&mut errors);
        self.files.insert(canon.to_path_buf(), id);
        self.read.insert(
            id,
            ReadFile {
                statements: Arc::new(ast.statements),
                bytes,
            },
        );
        Ok(id)
    }

    /// Counts file `id` once more against [`MAX_SCENARIO_BYTES`] (each
    /// expansion of an include counts); `false` past it, and then nothing
    /// more is read.
    fn count(&mut self, id: FileId) -> bool {
        self.total_bytes += self.read.get(&id).map_or(0, |f| f.bytes);
        if self.total_bytes > MAX_SCENARIO_BYTES {
            self.stopped = true;
        }
        !self.stopped
    }

    /// Reads the map file a `grid` names (once per `grid`).
    fn map(&mut self, from: FileId, file: &crate::diagnostics::Spanned<String>) {
        if self.parsed.maps.contains_key(&file.span) {
            return;
        }
        let target = self.folder_of(from).join(&file.value);
        let canon = canonical(&target);
        let read = match self.inside_root(&canon, &file.value, file.span) {
            // The overlay's text first (a map made in memory: the Python
            // module's `scen.plan` from a numpy grid), as for `.scen` files.
            Ok(()) => match (self.overlay)(&canon) {
                Some(text) if text.len() as u64 > MAX_MAP_BYTES => {
                    Err(map_too_large(&target, file.span))
                }
                Some(text) => Ok(self.parsed.sources.add(&target, text)),
                None => read_text(
                    &target,
                    MAX_MAP_BYTES,
                    Some(file.span),
                    "map",
                    &mut self.parsed.sources,
                )
                .map(|text| self.parsed.sources.add(&target, text)),
            },
            Err(d) => Err(d),
        };
        self.parsed.maps.insert(file.span, read);
    }
}

/// A map file (on disk or in the overlay) larger than [`MAX_MAP_BYTES`],
/// at the `grid` that names it.
fn map_too_large(path: &Path, at: Span) -> Diag {
    Diag::error(
        "scen::load::too_large",
        format!(
            "map file `{}` is larger than {}",
            path.display(),
            human_bytes(MAX_MAP_BYTES)
        ),
    )
    .at(at, "file too large")
    .help("a MovingAI map may be at most 64 MiB: use a coarser map, or a smaller part of it")
}

/// The scenario's text passed [`MAX_SCENARIO_BYTES`]: at the include that
/// crossed it, or at the main file's start.
fn scenario_too_large(path: &Path, from: Option<Span>, sources: &mut SourceMap) -> Diag {
    let d = Diag::error(
        "scen::load::too_large",
        format!(
            "the scenario's text, includes expanded, is larger than {} (at `{}`)",
            human_bytes(MAX_SCENARIO_BYTES),
            path.display()
        ),
    )
    .help(format!(
        "a scenario, with every include counted each time it is included, may be at most {}; large grids belong in a map file (`grid NAME \"file.map\"`), which may be up to {}",
        human_bytes(MAX_SCENARIO_BYTES),
        human_bytes(MAX_MAP_BYTES)
    ));
    match from {
        Some(span) => d.at(span, "this include passes the limit"),
        None => {
            let id = sources.add(path, "");
            d.at(Span::new(id, 0, 0), "file too large")
        }
    }
}

/// Reads a text file named by a scenario (`what`: "scenario" or "map").
/// `from` is the span that named it (an include or a grid), where a failure
/// is reported; a main file's failure is reported at its own 1:1. The error
/// is a full diagnostic; the file's bytes are never quoted in it.
#[allow(clippy::result_large_err)]
pub(crate) fn read_text(
    path: &Path,
    max_bytes: u64,
    from: Option<Span>,
    what: &str,
    sources: &mut SourceMap,
) -> Result<Arc<str>, Diag> {
    let (code, message, label, help) = match read_regular_file(path, max_bytes) {
        Ok(bytes) => match invalid_utf8_at(&bytes) {
            None => return Ok(String::from_utf8(bytes).unwrap_or_default().into()),
            Some((line, column)) => (
                "scen::load::not_utf8",
                format!(
                    "{what} file `{}` is not UTF-8 text (an invalid byte at line {line}, column {column})",
                    path.display()
                ),
                "not UTF-8 text".to_string(),
                format!(
                    "{what} files are UTF-8 text; is this a binary file? (its bytes are not shown)"
                ),
            ),
        },
        Err(ReadError::TooLarge(_)) => {
            return Err(match from {
                Some(span) if what == "map" => map_too_large(path, span),
                _ => scenario_too_large(path, from, sources),
            });
        }
        Err(ReadError::Folder) => (
            "scen::load::read",
            format!("`{}` is a folder, not a {what} file", path.display()),
            "a folder".to_string(),
            if from.is_none() {
                // The file named on the command line.
                format!(
                    "name a file; `scen test {}` runs every scenario under a folder",
                    path.display()
                )
            } else {
                "name a file".to_string()
            },
        ),
        Err(e @ ReadError::NotRegular(_)) => (
            "scen::load::not_regular",
            format!("cannot read {what} file `{}`: {e}", path.display()),
            "not a regular file".to_string(),
            "scenarios read only regular files: not FIFOs, devices or /proc entries".to_string(),
        ),
        Err(ReadError::Io(e)) => (
            "scen::load::read",
            format!("cannot read {what} file `{}`: {e}", path.display()),
            "cannot be read".to_string(),
            if from.is_some() {
                "paths are relative to the folder of the file that names them".to_string()
            } else {
                "check the file's path".to_string()
            },
        ),
    };
    let d = Diag::error(code, message).help(help);
    Err(match from {
        Some(span) => d.at(span, label),
        None => {
            // The main file: located at its 1:1 without its text.
            let id = sources.add(path, "");
            d.at(Span::new(id, 0, 0), label)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_overlay_is_read_before_the_disk_for_the_main_file_and_includes() {
        let dir = std::env::temp_dir().join(format!("scen-overlay-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let main = dir.join("main.scen");
        let part = dir.join("_part.scen");
        std::fs::write(&main, "this is not a scenario").unwrap();
        std::fs::write(&part, "robot r point\n").unwrap();
        let (main_c, part_c) = (canonical(&main), canonical(&part));
        let overlay = |p: &Path| -> Option<Arc<str>> {
            if p == main_c {
                Some("include \"_part.scen\"\nworld { bounds (0, 0) (2, 2) }\nplan p astar q { start (1, 1) goal (1, 1) }\n".into())
            } else if p == part_c {
                Some("robot q point\n".into())
            } else {
                None
            }
        };
        let s = load_with(&main, None, &overlay).expect("the overlay's text loads");
        assert_eq!(s.robots[0].name, "q");
        let parsed = parse_scenario(&main, None, &overlay);
        assert_eq!(parsed.includes.len(), 1);
        assert_eq!(
            parsed.sources.snippet(parsed.includes[0].0),
            "\"_part.scen\""
        );
        assert_eq!(parsed.sources.get(parsed.includes[0].1).unwrap().path, part);
        // Without it, the disk's text.
        assert!(load(&main).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_map_file_comes_from_the_overlay_too() {
        // Neither file is on disk: a scenario and its map made in memory.
        let dir = std::env::temp_dir().join(format!("scen-overlay-map-{}", std::process::id()));
        let main = dir.join("made.scen");
        let (main_c, map_c) = (canonical(&main), canonical(&dir.join("cells.map")));
        let overlay = |p: &Path| -> Option<Arc<str>> {
            if p == main_c {
                Some("world { bounds (0, 0) (3, 2) grid g \"cells.map\" cell 1 }\nrobot r point\nplan p astar r { start (0.5, 0.5) goal (2.5, 0.5) }\n".into())
            } else if p == map_c {
                Some("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n".into())
            } else {
                None
            }
        };
        let s = load_with(&main, None, &overlay).expect("the overlay's map loads");
        let crate::geometry::Shape::Grid(g) = &s.world.obstacles[0].shape else {
            panic!("a grid: {:?}", s.world.obstacles[0].shape);
        };
        assert_eq!((g.width, g.height), (3, 2));
        // Row 0 is the top row: the blocked cell is the bottom row's middle.
        assert!(g.is_blocked(1, 1) && !g.is_blocked(1, 0));
        // Without the overlay, the map is missing (and located at the grid).
        let without = |p: &Path| (p == main_c).then(|| overlay(p)).flatten();
        let err = load_with(&main, None, &without).expect_err("no map on disk");
        assert!(
            err.diags.iter().any(|d| d.code == "scen::load::read"),
            "{:?}",
            err.diags
        );
    }
}
