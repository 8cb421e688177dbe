//! `scen lsp`: a Language Server on stdin/stdout (SPEC §4), on the message
//! types of the synchronous `lsp-server` scaffold that rust-analyzer uses,
//! with a transport of our own ([`transport`]): a malformed message gets a
//! JSON-RPC error response and the server goes on; it stops at `exit` or at
//! the end of its input.
//!
//! One thread answers messages in order. Each open document is analysed as
//! `scen check` would analyse it (the loader and the analyzer, with the
//! open documents' text before the disk's), once per change of any open
//! document; diagnostics are published after the messages that had already
//! arrived are handled. Completion reads the text at the cursor and may
//! use the last analysis; hover, definition, references, the outline and
//! formatting use the current text's. A panic while answering becomes an
//! error response (or no diagnostics), and the server goes on.

mod analysis;
mod complete;
mod navigate;
mod text;
mod transport;

use std::collections::BTreeMap;
use std::io::{self, Write};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, sync_channel};

use lsp_server::{ErrorCode, Message, Notification, Request, RequestId, Response};
use lsp_types::notification::{
    DidChangeTextDocument, DidCloseTextDocument, DidOpenTextDocument, DidSaveTextDocument, Exit,
    Notification as _, PublishDiagnostics,
};
use lsp_types::request::{
    Completion, DocumentSymbolRequest, Formatting, GotoDefinition, HoverRequest, Initialize,
    References, Request as _, Shutdown,
};
use lsp_types::{
    CompletionOptions, CompletionParams, CompletionResponse, Diagnostic,
    DiagnosticRelatedInformation, DiagnosticSeverity, DocumentFormattingParams, DocumentSymbol,
    DocumentSymbolParams, DocumentSymbolResponse, GotoDefinitionParams, GotoDefinitionResponse,
    Hover, HoverContents, HoverParams, HoverProviderCapability, InitializeParams, Location,
    MarkupContent, MarkupKind, NumberOrString, OneOf, PositionEncodingKind,
    PublishDiagnosticsParams, ReferenceParams, ServerCapabilities, SymbolKind,
    TextDocumentSyncCapability, TextDocumentSyncKind, TextEdit, Url,
};

use crate::diagnostics::{Diag, FileId, Level, Span};
use crate::scenario::loader::{MAX_SCENARIO_BYTES, canonical};

use analysis::Analysis;
use text::{Encoding, LineIndex};
use transport::{Incoming, Reader, Rejected};

/// Runs the server until the client says `exit` or closes stdin; returns
/// the exit code the LSP specifies for `exit`: 0 when `shutdown` came
/// before, 1 otherwise.
pub fn run() -> i32 {
    let incoming = read_stdin();
    match serve(&incoming, &mut io::stdout().lock()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("scen lsp: {e}");
            1
        }
    }
}

/// Reads stdin on a thread of its own, so that the messages that arrive
/// while one is handled are there to be handled before the next analysis.
/// (The thread is not joined: it may be blocked reading when `exit` comes,
/// and the process ends then.)
fn read_stdin() -> Receiver<Incoming> {
    // A few messages read ahead, not more: each may be large.
    let (sender, receiver) = sync_channel(4);
    std::thread::spawn(move || {
        let mut reader = Reader::new(io::stdin().lock());
        loop {
            match reader.next_message() {
                Ok(Some(message)) => {
                    if sender.send(message).is_err() {
                        return;
                    }
                }
                Ok(None) => return,
                Err(e) => {
                    eprintln!("scen lsp: cannot read stdin: {e}");
                    return;
                }
            }
        }
    });
    receiver
}

fn send(out: &mut impl Write, message: impl Into<Message>) -> io::Result<()> {
    message.into().write(out)
}

fn refuse(out: &mut impl Write, rejected: &Rejected) -> io::Result<()> {
    transport::write_message(out, &rejected.response())
}

/// Waits for `initialize` and returns it (`None` when the client leaves
/// first): requests before it get an error, notifications are dropped.
fn initialize(
    incoming: &Receiver<Incoming>,
    out: &mut impl Write,
) -> io::Result<Option<(RequestId, InitializeParams)>> {
    while let Ok(message) = incoming.recv() {
        match message {
            Err(rejected) => refuse(out, &rejected)?,
            Ok(Message::Request(req)) if req.method == Initialize::METHOD => {
                match serde_json::from_value(req.params) {
                    Ok(params) => return Ok(Some((req.id, params))),
                    Err(e) => send(
                        out,
                        Response::new_err(req.id, ErrorCode::InvalidParams as i32, e.to_string()),
                    )?,
                }
            }
            Ok(Message::Request(req)) => send(
                out,
                Response::new_err(
                    req.id,
                    ErrorCode::ServerNotInitialized as i32,
                    format!("`{}` before `initialize`", req.method),
                ),
            )?,
            Ok(Message::Notification(n)) if n.method == Exit::METHOD => return Ok(None),
            Ok(_) => {}
        }
    }
    Ok(None)
}

/// Answers messages until `exit` or the end of the input; returns the exit
/// code.
fn serve(incoming: &Receiver<Incoming>, out: &mut impl Write) -> io::Result<i32> {
    let Some((id, params)) = initialize(incoming, out)? else {
        return Ok(1);
    };
    let utf8 = params
        .capabilities
        .general
        .and_then(|g| g.position_encodings)
        .is_some_and(|e| e.contains(&PositionEncodingKind::UTF8));
    let encoding = if utf8 {
        Encoding::Utf8
    } else {
        Encoding::Utf16
    };
    let capabilities = ServerCapabilities {
        position_encoding: Some(match encoding {
            Encoding::Utf8 => PositionEncodingKind::UTF8,
            Encoding::Utf16 => PositionEncodingKind::UTF16,
        }),
        text_document_sync: Some(TextDocumentSyncCapability::Kind(
            TextDocumentSyncKind::INCREMENTAL,
        )),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec![".".into()]),
            ..CompletionOptions::default()
        }),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        document_formatting_provider: Some(OneOf::Left(true)),
        ..ServerCapabilities::default()
    };
    send(
        out,
        Response::new_ok(
            id,
            serde_json::json!({
                "capabilities": capabilities,
                "serverInfo": { "name": "scen", "version": env!("CARGO_PKG_VERSION") },
            }),
        ),
    )?;
    let mut server = Server {
        docs: BTreeMap::new(),
        encoding,
        generation: 0,
        published: 0,
        closed: Vec::new(),
    };
    let mut shut_down = false;
    while let Ok(message) = incoming.recv() {
        let mut next = Some(message);
        while let Some(message) = next.take() {
            match message {
                Err(rejected) => refuse(out, &rejected)?,
                Ok(Message::Request(req)) => {
                    let response = if shut_down {
                        Response::new_err(
                            req.id,
                            ErrorCode::InvalidRequest as i32,
                            "the server is shut down: only `exit` is expected".into(),
                        )
                    } else if req.method == Shutdown::METHOD {
                        shut_down = true;
                        Response::new_ok(req.id, ())
                    } else {
                        server.answer(req)
                    };
                    send(out, response)?;
                }
                Ok(Message::Notification(n)) if n.method == Exit::METHOD => {
                    return Ok(if shut_down { 0 } else { 1 });
                }
                Ok(Message::Notification(n)) if !shut_down => server.notify(n),
                Ok(_) => {}
            }
            // Handle what has arrived before analysing for diagnostics.
            next = incoming.try_recv().ok();
        }
        for notification in server.diagnostics() {
            send(out, notification)?;
        }
    }
    Ok(if shut_down { 0 } else { 1 })
}

struct Doc {
    /// The canonical path (the loader's key for includes).
    path: PathBuf,
    text: String,
    /// The analysis and the generation it was made at.
    analysis: Option<(Arc<Analysis>, u64)>,
    /// Over the loader's bound ([`MAX_SCENARIO_BYTES`]): the loader refuses it
    /// whatever it says, so it is analysed once when it becomes so (its
    /// one diagnostic published once), and not again while edits keep it
    /// too large; requests on it answer nothing.
    too_large: bool,
    /// Whether the diagnostic of a too large text has been published.
    published_too_large: bool,
}

impl Doc {
    fn new(path: PathBuf, text: String) -> Doc {
        Doc {
            path,
            too_large: is_too_large(&text),
            text,
            analysis: None,
            published_too_large: false,
        }
    }
}

fn is_too_large(text: &str) -> bool {
    text.len() as u64 > MAX_SCENARIO_BYTES
}

struct Server {
    /// By URI, in order, so that diagnostics are published in one order.
    docs: BTreeMap<Url, Doc>,
    encoding: Encoding,
    /// Counts changes to open documents: an analysis of an older generation
    /// may be out of date (an included document changed too).
    generation: u64,
    /// The generation whose diagnostics were published.
    published: u64,
    /// Documents closed since then, whose diagnostics are to be cleared.
    closed: Vec<Url>,
}

/// The file a document's URI names (a made-up one for `untitled:` URIs).
fn uri_path(uri: &Url) -> PathBuf {
    match uri.to_file_path() {
        Ok(path) => canonical(&path),
        Err(()) => PathBuf::from(uri.path()),
    }
}

fn path_uri(path: &Path) -> Option<Url> {
    Url::from_file_path(canonical(path)).ok()
}

impl Server {
    fn notify(&mut self, n: Notification) {
        let method = n.method.clone();
        let handled = catch_unwind(AssertUnwindSafe(|| self.notification(n)));
        if handled.is_err() {
            eprintln!("scen lsp: internal error while handling `{method}`");
        }
    }

    fn notification(&mut self, n: Notification) {
        match n.method.as_str() {
            DidOpenTextDocument::METHOD => {
                let Ok(p) =
                    n.extract::<lsp_types::DidOpenTextDocumentParams>(DidOpenTextDocument::METHOD)
                else {
                    return;
                };
                let doc = Doc::new(uri_path(&p.text_document.uri), p.text_document.text);
                self.docs.insert(p.text_document.uri, doc);
                self.generation += 1;
            }
            DidChangeTextDocument::METHOD => {
                let Ok(p) = n.extract::<lsp_types::DidChangeTextDocumentParams>(
                    DidChangeTextDocument::METHOD,
                ) else {
                    return;
                };
                if let Some(doc) = self.docs.get_mut(&p.text_document.uri) {
                    for change in p.content_changes {
                        text::apply_change(
                            &mut doc.text,
                            change.range,
                            &change.text,
                            self.encoding,
                        );
                    }
                    let was_too_large = doc.too_large;
                    doc.too_large = is_too_large(&doc.text);
                    if was_too_large != doc.too_large {
                        // Its last analysis, and what was published, were
                        // of the other kind.
                        doc.analysis = None;
                        doc.published_too_large = false;
                    }
                    // Still too large: nothing that reads it can tell.
                    if !(was_too_large && doc.too_large) {
                        self.generation += 1;
                    }
                }
            }
            DidCloseTextDocument::METHOD => {
                if let Ok(p) =
                    n.extract::<lsp_types::DidCloseTextDocumentParams>(DidCloseTextDocument::METHOD)
                {
                    self.docs.remove(&p.text_document.uri);
                    self.closed.push(p.text_document.uri);
                    self.generation += 1;
                }
            }
            // A file saved may be included by another open document.
            DidSaveTextDocument::METHOD => self.generation += 1,
            _ => {}
        }
    }

    /// The current analysis of a document (made now if out of date; a too
    /// large document's first one is kept).
    fn analysis(&mut self, uri: &Url) -> Option<Arc<Analysis>> {
        let generation = self.generation;
        let doc = self.docs.get(uri)?;
        if let Some((a, g)) = &doc.analysis
            && (*g == generation || doc.too_large)
        {
            return Some(a.clone());
        }
        // Only the files the loader reads are copied.
        let docs = &self.docs;
        let lookup = |p: &Path| {
            docs.values()
                .find(|d| d.path == p)
                .map(|d| Arc::from(d.text.as_str()))
        };
        let analysis = Arc::new(Analysis::new(&doc.path, &lookup));
        self.docs.get_mut(uri)?.analysis = Some((analysis.clone(), generation));
        Some(analysis)
    }

    /// The last analysis of a document, however old (for completion).
    fn any_analysis(&mut self, uri: &Url) -> Option<Arc<Analysis>> {
        match &self.docs.get(uri)?.analysis {
            Some((a, _)) => Some(a.clone()),
            None => self.analysis(uri),
        }
    }

    fn answer(&mut self, req: Request) -> Response {
        let id = req.id.clone();
        let method = req.method.clone();
        match catch_unwind(AssertUnwindSafe(|| self.request(req))) {
            Ok(Ok(value)) => Response::new_ok(id, value),
            Ok(Err((code, message))) => Response::new_err(id, code as i32, message),
            Err(_) => Response::new_err(
                id,
                ErrorCode::InternalError as i32,
                format!("internal error while answering `{method}`"),
            ),
        }
    }

    fn request(&mut self, req: Request) -> Result<serde_json::Value, (ErrorCode, String)> {
        fn params<P: serde::de::DeserializeOwned>(req: Request) -> Result<P, (ErrorCode, String)> {
            serde_json::from_value(req.params)
                .map_err(|e| (ErrorCode::InvalidParams, e.to_string()))
        }
        let json = |v: Result<serde_json::Value, serde_json::Error>| {
            v.map_err(|e| (ErrorCode::InternalError, e.to_string()))
        };
        match req.method.as_str() {
            Completion::METHOD => {
                let p: CompletionParams = params(req)?;
                let pos = p.text_document_position;
                let items = self.at(
                    &pos.text_document.uri,
                    pos.position,
                    true,
                    |doc, a, offset| complete::completions(&doc.text, offset, a),
                );
                json(serde_json::to_value(items.map(CompletionResponse::Array)))
            }
            HoverRequest::METHOD => {
                let p: HoverParams = params(req)?;
                let pos = p.text_document_position_params;
                let encoding = self.encoding;
                let hover = self.at(
                    &pos.text_document.uri,
                    pos.position,
                    false,
                    |doc, a, offset| {
                        let (value, span) = navigate::hover(a, offset)?;
                        let index = LineIndex::new(&doc.text, encoding);
                        Some(Hover {
                            contents: HoverContents::Markup(MarkupContent {
                                kind: MarkupKind::Markdown,
                                value,
                            }),
                            range: Some(index.range(span.start, span.end)),
                        })
                    },
                );
                json(serde_json::to_value(hover.flatten()))
            }
            GotoDefinition::METHOD => {
                let p: GotoDefinitionParams = params(req)?;
                let pos = p.text_document_position_params;
                let encoding = self.encoding;
                let found = self.at(
                    &pos.text_document.uri,
                    pos.position,
                    false,
                    |_, a, offset| {
                        let span = navigate::definition(a, offset)?;
                        location(a, span, encoding).map(GotoDefinitionResponse::Scalar)
                    },
                );
                json(serde_json::to_value(found.flatten()))
            }
            References::METHOD => {
                let p: ReferenceParams = params(req)?;
                let with_declaration = p.context.include_declaration;
                let pos = p.text_document_position;
                let locations =
                    self.references(&pos.text_document.uri, pos.position, with_declaration);
                json(serde_json::to_value(locations))
            }
            DocumentSymbolRequest::METHOD => {
                let p: DocumentSymbolParams = params(req)?;
                let encoding = self.encoding;
                let uri = p.text_document.uri;
                let symbols = self.analysis(&uri).map(|a| {
                    let index = a.text(0).map(|t| t.to_string()).unwrap_or_default();
                    let index = LineIndex::new(&index, encoding);
                    let outline = navigate::outline(&a);
                    DocumentSymbolResponse::Nested(
                        outline.iter().map(|o| symbol(o, &index)).collect(),
                    )
                });
                json(serde_json::to_value(symbols))
            }
            Formatting::METHOD => {
                let p: DocumentFormattingParams = params(req)?;
                let encoding = self.encoding;
                let doc = self.docs.get(&p.text_document.uri);
                let edits = doc.filter(|doc| !doc.too_large).and_then(|doc| {
                    let formatted = crate::format::format_text(&doc.text).ok()?;
                    let index = LineIndex::new(&doc.text, encoding);
                    let edits = if formatted == doc.text {
                        Vec::new()
                    } else {
                        vec![TextEdit {
                            range: index.range(0, doc.text.len()),
                            new_text: formatted,
                        }]
                    };
                    Some(edits)
                });
                json(serde_json::to_value(edits))
            }
            method => Err((
                ErrorCode::MethodNotFound,
                format!("`scen lsp` does not answer `{method}`"),
            )),
        }
    }

    /// Runs `f` on a document, its analysis and the offset of `position`
    /// (`None` for a document that is not open). With `stale`, the last
    /// analysis will do.
    fn at<T>(
        &mut self,
        uri: &Url,
        position: lsp_types::Position,
        stale: bool,
        f: impl FnOnce(&Doc, &Analysis, usize) -> T,
    ) -> Option<T> {
        if self.docs.get(uri)?.too_large {
            return None;
        }
        let analysis = if stale {
            self.any_analysis(uri)?
        } else {
            self.analysis(uri)?
        };
        let doc = self.docs.get(uri)?;
        let offset = LineIndex::new(&doc.text, self.encoding).offset(position);
        Some(f(doc, &analysis, offset))
    }

    /// The uses (and the declaration) of the name at `position`, in this
    /// document's scenario and in every open document's that declares it
    /// in the same place (through `include`s).
    fn references(
        &mut self,
        uri: &Url,
        position: lsp_types::Position,
        with_declaration: bool,
    ) -> Option<Vec<Location>> {
        let encoding = self.encoding;
        let here = self.at(uri, position, false, |_, a, offset| {
            let s = navigate::symbol_at(a, offset)?;
            Some((s.kind, s.name.clone(), declared_at(a, s.decl)?))
        })??;
        let uris: Vec<Url> = self.docs.keys().cloned().collect();
        let mut locations: Vec<Location> = Vec::new();
        for other in std::iter::once(uri.clone()).chain(uris.into_iter().filter(|u| u != uri)) {
            let Some(a) = self.analysis(&other) else {
                continue;
            };
            let Some(s) = a.symbol(here.0, &here.1) else {
                continue;
            };
            if declared_at(&a, s.decl).as_ref() != Some(&here.2) {
                continue;
            }
            let spans = with_declaration
                .then_some(s.decl)
                .into_iter()
                .chain(s.uses.iter().copied());
            for span in spans {
                if let Some(l) = location(&a, span, encoding)
                    && !locations.contains(&l)
                {
                    locations.push(l);
                }
            }
        }
        Some(locations)
    }

    /// Diagnostics of every open document, when something changed since
    /// they were last published.
    fn diagnostics(&mut self) -> Vec<Notification> {
        if self.published == self.generation {
            return Vec::new();
        }
        self.published = self.generation;
        let uris: Vec<Url> = self.docs.keys().cloned().collect();
        let mut out: Vec<Notification> = std::mem::take(&mut self.closed)
            .into_iter()
            .filter(|uri| !self.docs.contains_key(uri))
            .map(|uri| {
                let params = PublishDiagnosticsParams::new(uri, Vec::new(), None);
                Notification::new(PublishDiagnostics::METHOD.into(), params)
            })
            .collect();
        for uri in uris {
            if let Some(doc) = self.docs.get_mut(&uri)
                && doc.too_large
            {
                if doc.published_too_large {
                    continue;
                }
                doc.published_too_large = true;
            }
            let encoding = self.encoding;
            let diagnostics = catch_unwind(AssertUnwindSafe(|| {
                let a = self.analysis(&uri)?;
                Some(
                    a.diags
                        .iter()
                        .map(|d| diagnostic(&a, d, encoding))
                        .collect::<Vec<_>>(),
                )
            }));
            let diagnostics = match diagnostics {
                Ok(d) => d.unwrap_or_default(),
                Err(_) => {
                    eprintln!("scen lsp: internal error while analysing `{uri}`");
                    Vec::new()
                }
            };
            let params = PublishDiagnosticsParams::new(uri, diagnostics, None);
            out.push(Notification::new(PublishDiagnostics::METHOD.into(), params));
        }
        out
    }
}

/// A declaration's place as a path and offset (the same file has other
/// ids in other documents' analyses).
fn declared_at(a: &Analysis, span: Span) -> Option<(PathBuf, usize)> {
    Some((canonical(&a.sources.get(span.file)?.path), span.start))
}

fn location(a: &Analysis, span: Span, encoding: Encoding) -> Option<Location> {
    let file = a.sources.get(span.file)?;
    let index = LineIndex::new(&file.text, encoding);
    Some(Location::new(
        path_uri(&file.path)?,
        index.range(span.start, span.end),
    ))
}

/// A diagnostic of `scen check` for the document (file 0). One that points
/// into an included file is shown at the `include` that brought it in.
fn diagnostic(a: &Analysis, d: &Diag, encoding: Encoding) -> Diagnostic {
    let text = a.text(0).unwrap_or_default();
    let index = LineIndex::new(&text, encoding);
    let mut message = d.message.clone();
    let mut related: Vec<DiagnosticRelatedInformation> = d
        .related
        .iter()
        .filter_map(|(span, label)| {
            Some(DiagnosticRelatedInformation {
                location: location(a, *span, encoding)?,
                message: label.clone(),
            })
        })
        .collect();
    let range = match d.span {
        None => index.range(0, 0),
        Some(span) if span.file == 0 => index.range(span.start, span.end),
        Some(span) => {
            message = format!("in `{}`: {message}", a.sources.location(span));
            if let Some(l) = location(a, span, encoding) {
                related.insert(
                    0,
                    DiagnosticRelatedInformation {
                        location: l,
                        message: d.label.clone(),
                    },
                );
            }
            let include = include_in_main(a, span.file).unwrap_or_default();
            index.range(include.start, include.end)
        }
    };
    if let Some(help) = &d.help {
        message.push_str("\nhelp: ");
        message.push_str(help);
    }
    Diagnostic {
        range,
        severity: Some(match d.level {
            Level::Error => DiagnosticSeverity::ERROR,
            Level::Warning => DiagnosticSeverity::WARNING,
        }),
        code: Some(NumberOrString::String(d.code.to_string())),
        source: Some("scen".into()),
        message,
        related_information: Some(related).filter(|r| !r.is_empty()),
        ..Diagnostic::default()
    }
}

/// The `include` of the main file through which `file` was read.
fn include_in_main(a: &Analysis, mut file: FileId) -> Option<Span> {
    for _ in 0..=a.includes.len() {
        let &(span, _) = a.includes.iter().find(|(_, child)| *child == file)?;
        if span.file == 0 {
            return Some(span);
        }
        file = span.file;
    }
    None
}

#[allow(deprecated)] // `DocumentSymbol::deprecated` must be written out.
fn symbol(o: &navigate::Outline, index: &LineIndex<'_>) -> DocumentSymbol {
    DocumentSymbol {
        name: o.name.clone(),
        detail: Some(o.detail.clone()).filter(|d| !d.is_empty()),
        kind: match o.kind {
            navigate::OutlineKind::World => SymbolKind::NAMESPACE,
            navigate::OutlineKind::Obstacle => SymbolKind::OBJECT,
            navigate::OutlineKind::Robot => SymbolKind::CLASS,
            navigate::OutlineKind::Plan => SymbolKind::FUNCTION,
            navigate::OutlineKind::Bench => SymbolKind::STRUCT,
        },
        tags: None,
        deprecated: None,
        range: index.range(o.full.start, o.full.end),
        selection_range: index.range(o.name_span.start, o.name_span.end),
        children: Some(o.children.iter().map(|c| symbol(c, index)).collect())
            .filter(|c: &Vec<DocumentSymbol>| !c.is_empty()),
    }
}
