//! `rigor lsp`: the Language Server Protocol over standard input and output, on the
//! maintained `lsp-server` and `lsp-types` crates (as rust-analyzer is). A thin world
//! around the one checker entry: every open document is checked on a thread of its own
//! (`world::check`), so a slow document never holds up another's diagnostics; a newer
//! version of a document trips the flag of the check still running on the older one,
//! whose clock then passes every deadline, and the document is checked again once that
//! check has returned (edits that arrive meanwhile are checked once, at their newest).
//!
//! | file | owns |
//! |---|---|
//! | `world.rs` | the open documents as a resolver (memory first, then disk), the clock a newer version stops, running one check |
//! | `diagnostics.rs` | reports as the protocol's diagnostics, notes as related information |
//! | `hover.rs` | hovers on links, names and labels |
//! | `nav.rs` | labels, declarations and imports in the syntax tree; go to definition; the outline |
//! | `actions.rs` | quick fixes from the suggestions under diagnostics |
//! | `text.rs` | byte offsets against lines and UTF-16 columns; file URIs |

mod actions;
mod diagnostics;
mod hover;
mod nav;
mod text;
mod world;

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, Response};
use lsp_types::notification::{self as note, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::{
    CodeActionOrCommand, CodeActionProviderCapability, DocumentSymbolResponse,
    GotoDefinitionResponse, Hover, HoverContents, HoverProviderCapability, Location, MarkupContent,
    MarkupKind, OneOf, PublishDiagnosticsParams, ServerCapabilities, TextDocumentSyncCapability,
    TextDocumentSyncKind, TextDocumentSyncOptions, TextDocumentSyncSaveOptions, Uri,
};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use text::Lines;
use world::{Cancel, Kind, Open, Outcome};

pub use world::Kind as DocumentKind;

/// Serves one editor over standard input and output until it says `exit`, checking
/// with `options` (the command line's limits and time budget; the clock is the
/// server's own).
pub fn run(options: crate::Options) -> Result<(), String> {
    let (conn, io) = Connection::stdio();
    serve(&conn, options).map_err(|e| e.to_string())?;
    drop(conn);
    io.join().map_err(|e| e.to_string())
}

/// What the server says it can do.
fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Options(
            TextDocumentSyncOptions {
                open_close: Some(true),
                change: Some(TextDocumentSyncKind::INCREMENTAL),
                save: Some(TextDocumentSyncSaveOptions::Supported(true)),
                ..TextDocumentSyncOptions::default()
            },
        )),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        code_action_provider: Some(CodeActionProviderCapability::Simple(true)),
        ..ServerCapabilities::default()
    }
}

/// The protocol on `conn`, from `initialize` to `exit`.
fn serve(conn: &Connection, options: crate::Options) -> Result<(), lsp_server::ProtocolError> {
    let caps = serde_json::to_value(capabilities()).unwrap_or_default();
    conn.initialize(caps)?;
    let shared = Arc::new(Shared {
        docs: Mutex::new(HashMap::new()),
        done: Mutex::new(HashMap::new()),
        sender: conn.sender.clone(),
        options,
    });
    for msg in &conn.receiver {
        match msg {
            Message::Request(r) => {
                if conn.handle_shutdown(&r)? {
                    break;
                }
                // Answered on a thread of its own: an outline of a long document does
                // not hold up the next keystroke.
                let (id, shared2) = (r.id.clone(), shared.clone());
                let spawned = std::thread::Builder::new()
                    .name("rigor-request".into())
                    .spawn(move || {
                        let resp = answer(&shared2, r);
                        let _ = shared2.sender.send(Message::Response(resp));
                    });
                if spawned.is_err() {
                    let why = "rigor lsp could not start a thread".to_string();
                    let resp = Response::new_err(id, ErrorCode::InternalError as i32, why);
                    let _ = conn.sender.send(Message::Response(resp));
                }
            }
            Message::Notification(n) => notified(&shared, n),
            Message::Response(_) => {}
        }
    }
    for d in lock(&shared.docs).values() {
        d.cancel.store(true, Ordering::Relaxed);
    }
    Ok(())
}

/// An open document.
struct Doc {
    /// Its path, if it is a file.
    path: Option<PathBuf>,
    /// The name it is checked under (its path, else its URI).
    name: String,
    kind: Kind,
    text: Arc<String>,
    version: i32,
    /// Bumped by every change (and by a save of another document it may import).
    generation: u64,
    /// The generation whose diagnostics were last published.
    published: u64,
    /// The flag of the newest check.
    cancel: Cancel,
    /// Whether a thread is checking it.
    running: bool,
}

/// A finished check: the text it read and what it found.
struct Done {
    text: Arc<String>,
    outcome: Outcome,
}

/// What the main loop and the checking threads share.
struct Shared {
    docs: Mutex<HashMap<Uri, Doc>>,
    done: Mutex<HashMap<Uri, Arc<Done>>>,
    sender: crossbeam_channel::Sender<Message>,
    /// The options every check starts from.
    options: crate::Options,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// A notification from the editor: documents opened, changed, saved, closed.
fn notified(shared: &Arc<Shared>, n: Notification) {
    match n.method.as_str() {
        note::DidOpenTextDocument::METHOD => {
            let Ok(p) = serde_json::from_value::<lsp_types::DidOpenTextDocumentParams>(n.params)
            else {
                return;
            };
            let d = p.text_document;
            let path = text::path_of(&d.uri).map(|p| world::key(&p));
            let name = path
                .as_ref()
                .map_or_else(|| d.uri.as_str().to_string(), |p| p.display().to_string());
            let kind = if matches!(d.language_id.as_str(), "markdown" | "latex" | "tex") {
                Kind::of(if d.language_id == "markdown" {
                    "x.md"
                } else {
                    "x.tex"
                })
            } else {
                Kind::of(&name)
            };
            let doc = Doc {
                path,
                name,
                kind,
                text: Arc::new(d.text),
                version: d.version,
                generation: 1,
                published: 0,
                cancel: Arc::new(AtomicBool::new(false)),
                running: false,
            };
            lock(&shared.docs).insert(d.uri.clone(), doc);
            schedule(shared, &d.uri);
        }
        note::DidChangeTextDocument::METHOD => {
            let Ok(p) = serde_json::from_value::<lsp_types::DidChangeTextDocumentParams>(n.params)
            else {
                return;
            };
            let uri = p.text_document.uri;
            {
                let mut docs = lock(&shared.docs);
                let Some(doc) = docs.get_mut(&uri) else {
                    return;
                };
                let mut t = doc.text.to_string();
                for c in p.content_changes {
                    match c.range {
                        Some(r) => {
                            let s = actions::span_of(&t, r);
                            t.replace_range(s.start..s.end.max(s.start), &c.text);
                        }
                        None => t = c.text,
                    }
                }
                doc.text = Arc::new(t);
                doc.version = p.text_document.version;
                restart(doc);
            }
            schedule(shared, &uri);
        }
        note::DidSaveTextDocument::METHOD => {
            // Another open document may import the one saved: check them all again.
            let uris: Vec<Uri> = {
                let mut docs = lock(&shared.docs);
                for d in docs.values_mut() {
                    restart(d);
                }
                docs.keys().cloned().collect()
            };
            for u in uris {
                schedule(shared, &u);
            }
        }
        note::DidCloseTextDocument::METHOD => {
            let Ok(p) = serde_json::from_value::<lsp_types::DidCloseTextDocumentParams>(n.params)
            else {
                return;
            };
            let uri = p.text_document.uri;
            let mut docs = lock(&shared.docs);
            if let Some(d) = docs.remove(&uri) {
                d.cancel.store(true, Ordering::Relaxed);
            }
            lock(&shared.done).remove(&uri);
            publish(shared, uri, Vec::new(), None);
        }
        _ => {}
    }
}

/// A new generation of `doc`: its running check is stopped, the next one gets a fresh
/// flag.
fn restart(doc: &mut Doc) {
    doc.cancel.store(true, Ordering::Relaxed);
    doc.cancel = Arc::new(AtomicBool::new(false));
    doc.generation += 1;
}

/// Makes sure a thread checks `uri` at its newest generation.
fn schedule(shared: &Arc<Shared>, uri: &Uri) {
    let mut docs = lock(&shared.docs);
    let Some(doc) = docs.get_mut(uri) else {
        return;
    };
    if doc.running {
        return;
    }
    doc.running = true;
    let (shared2, uri2) = (shared.clone(), uri.clone());
    let spawned = std::thread::Builder::new()
        .name("rigor-check".into())
        .stack_size(32 << 20)
        .spawn(move || checker(&shared2, &uri2));
    if spawned.is_err() {
        doc.running = false;
    }
}

/// One job of a checking thread: a generation of a document and what it needs.
struct Job {
    name: String,
    text: Arc<String>,
    kind: Kind,
    generation: u64,
    version: i32,
    cancel: Cancel,
    open: Open,
}

/// The checking thread of one document: checks its newest generation until the
/// diagnostics published are the newest's, then ends.
fn checker(shared: &Arc<Shared>, uri: &Uri) {
    loop {
        let job = {
            let mut docs = lock(&shared.docs);
            let open: Open = docs
                .values()
                .filter_map(|d| Some((d.path.clone()?, d.text.clone())))
                .collect();
            let Some(doc) = docs.get_mut(uri) else {
                return;
            };
            if doc.published == doc.generation {
                doc.running = false;
                return;
            }
            Job {
                name: doc.name.clone(),
                text: doc.text.clone(),
                kind: doc.kind,
                generation: doc.generation,
                version: doc.version,
                cancel: doc.cancel.clone(),
                open,
            }
        };
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            world::check(
                &job.name,
                &job.text,
                job.kind,
                (&job.open, &job.cancel),
                &shared.options,
            )
        }));
        let mut docs = lock(&shared.docs);
        let Some(doc) = docs.get_mut(uri) else {
            return;
        };
        if doc.generation != job.generation {
            continue;
        }
        doc.published = job.generation;
        let Ok(outcome) = outcome else {
            continue;
        };
        let diags = match &outcome {
            Outcome::Derivation(r) => diagnostics::of_report(r, uri),
            Outcome::Notes(r) => diagnostics::of_lint(r, uri),
        };
        let done = Done {
            text: job.text.clone(),
            outcome,
        };
        lock(&shared.done).insert(uri.clone(), Arc::new(done));
        // Still holding the documents: a close cannot slip in between.
        publish(shared, uri.clone(), diags, Some(job.version));
    }
}

fn publish(
    shared: &Shared,
    uri: Uri,
    diagnostics: Vec<lsp_types::Diagnostic>,
    version: Option<i32>,
) {
    let params = PublishDiagnosticsParams {
        uri,
        diagnostics,
        version,
    };
    let n = Notification::new(note::PublishDiagnostics::METHOD.to_string(), params);
    let _ = shared.sender.send(Message::Notification(n));
}

/// The answer to a request.
fn answer(shared: &Shared, r: Request) -> Response {
    let id = r.id.clone();
    let result = match r.method.as_str() {
        req::HoverRequest::METHOD => params(r).map(|p| to_json(hover_at(shared, p))),
        req::GotoDefinition::METHOD => params(r).map(|p| to_json(definition(shared, p))),
        req::DocumentSymbolRequest::METHOD => params(r).map(|p| to_json(outline(shared, p))),
        req::CodeActionRequest::METHOD => params(r).map(|p| to_json(code_actions(shared, p))),
        _ => {
            return Response::new_err(
                id,
                ErrorCode::MethodNotFound as i32,
                format!("rigor lsp does not answer {}", r.method),
            )
        }
    };
    match result {
        Ok(v) => Response::new_ok(id, v),
        Err(e) => Response::new_err(id, ErrorCode::InvalidParams as i32, e),
    }
}

fn params<P: serde::de::DeserializeOwned>(r: Request) -> Result<P, String> {
    serde_json::from_value(r.params).map_err(|e| e.to_string())
}

fn to_json<T: serde::Serialize>(t: T) -> serde_json::Value {
    serde_json::to_value(t).unwrap_or_default()
}

/// The last finished check of `uri`, the document's path and the open documents.
fn finished(shared: &Shared, uri: &Uri) -> Option<(Arc<Done>, Option<PathBuf>, Open)> {
    let done = lock(&shared.done).get(uri).cloned()?;
    let docs = lock(&shared.docs);
    let open: Open = docs
        .values()
        .filter_map(|d| Some((d.path.clone()?, d.text.clone())))
        .collect();
    let path = docs.get(uri).and_then(|d| d.path.clone());
    Some((done, path, open))
}

fn hover_at(shared: &Shared, p: lsp_types::HoverParams) -> Option<Hover> {
    let at = p.text_document_position_params;
    let (done, path, open) = finished(shared, &at.text_document.uri)?;
    let Outcome::Derivation(r) = &done.outcome else {
        return None;
    };
    let offset = Lines::new(&r.source).offset(at.position);
    let value = hover::hover(r, offset, path.as_deref(), &open)?;
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value,
        }),
        range: None,
    })
}

fn definition(
    shared: &Shared,
    p: lsp_types::GotoDefinitionParams,
) -> Option<GotoDefinitionResponse> {
    let at = p.text_document_position_params;
    let uri = at.text_document.uri;
    let (done, path, open) = finished(shared, &uri)?;
    let Outcome::Derivation(r) = &done.outcome else {
        return None;
    };
    let file = r.ast.as_ref()?;
    let lines = Lines::new(&r.source);
    let offset = lines.offset(at.position);
    let here = |span| Location::new(uri.clone(), lines.range(span));
    let loc = match nav::target_at(file, &r.source, offset)? {
        nav::Target::Label(c) => {
            let name = &c.label.name;
            match c.from.or_else(|| nav::imported_from(file, name)) {
                Some(from) => {
                    let imported = nav::import(path.as_deref()?, from, &open)?;
                    let (label, _) = nav::labelled(imported.file.as_ref()?, name)?;
                    let range = Lines::new(&imported.text).range(label.span);
                    Location::new(text::uri_of(&imported.path)?, range)
                }
                None => here(nav::labelled(file, name)?.0.span),
            }
        }
        nav::Target::Name(name) => here(nav::declaration(file, &name)?.0.span),
    };
    Some(GotoDefinitionResponse::Scalar(loc))
}

fn outline(shared: &Shared, p: lsp_types::DocumentSymbolParams) -> Option<DocumentSymbolResponse> {
    let (done, _, _) = finished(shared, &p.text_document.uri)?;
    let Outcome::Derivation(r) = &done.outcome else {
        return None;
    };
    let lines = Lines::new(&r.source);
    Some(DocumentSymbolResponse::Nested(nav::outline(
        r.ast.as_ref()?,
        &r.source,
        &lines,
    )))
}

fn code_actions(
    shared: &Shared,
    p: lsp_types::CodeActionParams,
) -> Option<Vec<CodeActionOrCommand>> {
    let uri = p.text_document.uri;
    let (done, path, open) = finished(shared, &uri)?;
    // Edits are offsets into the text checked: offered only while it is the text shown.
    let current = lock(&shared.docs).get(&uri).map(|d| d.text.clone())?;
    if current != done.text {
        return Some(Vec::new());
    }
    let Outcome::Derivation(r) = &done.outcome else {
        return None;
    };
    let want = actions::span_of(&r.source, p.range);
    let found = actions::actions(r, want, &uri, path.as_deref(), &open);
    Some(
        found
            .into_iter()
            .map(CodeActionOrCommand::CodeAction)
            .collect(),
    )
}
