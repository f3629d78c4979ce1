//! The protocol layer: a route table from LSP methods to the engine's methods, and the
//! engine's thread. `transport.rs` stands between it and stdio.
//!
//! The engine lives on a thread of its own and takes jobs in the order the handlers
//! send them. Each handler sends its job before its first `await`, and the transport
//! starts handlers in the order messages arrive, so a completion that follows a
//! `didChange` always sees the change.

use std::panic::AssertUnwindSafe;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, mpsc};

use serde_json::Value;
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer, LspService, Server};

use crate::analysis::panic_message;
use crate::engine::{Engine, Publish, Settings};
use crate::run::{self, RUN_COMMAND};
use crate::semantic;
use crate::transport::{self, Outgoing, Output};

type Job = Box<dyn FnOnce(&mut Engine) + Send>;

/// The engine thread's stack. The compiler bounds how deep any pass over a tree
/// recurses (`ilmr_compiler::limits`) and the server's own walks recurse only over
/// blocks. At those limits one analysis with every feature asked at the deepest point
/// was measured to need 3.5 MB in an unoptimised build (a line of 256 parentheses; 256
/// nested blocks need 0.5 MB), so this is 18 times that. `tests/limits.rs` runs such
/// files, and files 1,000,000 levels deep, on a stack `STACK_MARGIN` times smaller.
/// Untouched stack costs no memory.
pub const ENGINE_STACK_BYTES: usize = 4 * ilmr_compiler::limits::COMPILER_STACK;

/// How many times the stack the deepest accepted file needs the engine thread has, at
/// least: the margin `tests/limits.rs` proves.
pub const STACK_MARGIN: usize = 8;

/// Sends jobs to the engine's thread.
#[derive(Clone)]
struct EngineHandle {
    jobs: mpsc::Sender<Job>,
}

/// A job's answer (`None` if it failed) and the lines for the client's log.
struct Done<R> {
    value: Option<R>,
    log: Vec<String>,
}

impl EngineHandle {
    fn spawn() -> EngineHandle {
        let (jobs, queue) = mpsc::channel::<Job>();
        let started = std::thread::Builder::new()
            .name("ilmr-engine".into())
            .stack_size(ENGINE_STACK_BYTES)
            .spawn(move || {
                let mut engine = Engine::default();
                while let Ok(job) = queue.recv() {
                    // Jobs catch their own panics; this is for a panic in the catching.
                    let _ = std::panic::catch_unwind(AssertUnwindSafe(|| job(&mut engine)));
                }
            });
        if let Err(e) = started {
            // Every request then answers as if the engine had failed on it.
            eprintln!("ilmr-lsp: cannot start the engine's thread: {e}");
        }
        EngineHandle { jobs }
    }

    /// Queues `f` now. A bug in one feature must not take the server down with it:
    /// a panic becomes a failed answer and a line in the log, and the next change
    /// rebuilds the analysis anyway.
    fn run<R: Send + 'static>(
        &self,
        f: impl FnOnce(&mut Engine) -> R + Send + 'static,
    ) -> tokio::sync::oneshot::Receiver<Done<R>> {
        let (tx, rx) = tokio::sync::oneshot::channel();
        let _ = self.jobs.send(Box::new(move |engine| {
            let value = std::panic::catch_unwind(AssertUnwindSafe(|| f(engine)));
            let mut log = engine.take_log();
            let value = value
                .map_err(|p| {
                    log.push(format!(
                        "ilmr-lsp: a request failed inside the engine: {}",
                        panic_message(p.as_ref())
                    ))
                })
                .ok();
            let _ = tx.send(Done { value, log });
        }));
        rx
    }
}

struct Backend {
    client: Client,
    engine: EngineHandle,
    /// Edits received: an edit's job checks only when no newer edit has come, so a
    /// burst of keystrokes costs one check after the last, not one per keystroke.
    edits: Arc<AtomicU64>,
    /// Diagnostics from edits' jobs, published in the order the jobs ran.
    publishes: tokio::sync::mpsc::UnboundedSender<Vec<Publish>>,
    /// Which refresh requests the client takes, from `initialize`.
    refresh: std::sync::OnceLock<Refresh>,
}

/// The client asks again for inlay hints / code lenses when told to (after a run).
#[derive(Debug, Clone, Copy, Default)]
struct Refresh {
    inlay_hints: bool,
    code_lenses: bool,
}

impl Backend {
    /// Runs `f` on the engine, in the order of the calls, and passes on its log.
    async fn ask<R: Send + 'static>(
        &self,
        f: impl FnOnce(&mut Engine) -> R + Send + 'static,
    ) -> Option<R> {
        let done = self.engine.run(f).await.ok()?;
        for line in done.log {
            eprintln!("{line}");
            self.client.log_message(MessageType::ERROR, line).await;
        }
        done.value
    }

    /// Publishes through the one queue edits' jobs use, so that every document's
    /// diagnostics go out in the order the engine made them.
    async fn publish(&self, publishes: Option<Vec<Publish>>) {
        if let Some(p) = publishes {
            let _ = self.publishes.send(p);
        }
    }

    /// Queues `f` on the engine without waiting for it; its log reaches the client.
    fn tell(&self, f: impl FnOnce(&mut Engine) + Send + 'static) {
        let done = self.engine.run(f);
        let client = self.client.clone();
        tokio::spawn(async move {
            if let Ok(done) = done.await {
                for line in done.log {
                    eprintln!("{line}");
                    client.log_message(MessageType::ERROR, line).await;
                }
            }
        });
    }

    /// Runs a query on the analysis of the latest text (checked first if an edit's
    /// check was left to a newer edit that has not been checked yet).
    async fn query<R: Send + 'static>(
        &self,
        f: impl FnOnce(&Engine) -> R + Send + 'static,
    ) -> Option<R> {
        self.ask(move |e| {
            e.refresh();
            f(e)
        })
        .await
    }

    async fn position_query<R: Send + 'static>(
        &self,
        doc: TextDocumentPositionParams,
        f: impl FnOnce(&Engine, &Uri, Position) -> R + Send + 'static,
    ) -> Option<R> {
        self.query(move |e| f(e, &doc.text_document.uri, doc.position))
            .await
    }
}

pub fn run_stdio() -> ExitCode {
    let runtime = match tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("ilmr-lsp: cannot start: {e}");
            return ExitCode::FAILURE;
        }
    };
    runtime.block_on(async {
        let (service, socket) = LspService::new(|client| {
            let (publishes, queue) = tokio::sync::mpsc::unbounded_channel();
            tokio::spawn(forward(client.clone(), queue));
            Backend {
                client,
                engine: EngineHandle::spawn(),
                edits: Arc::default(),
                publishes,
                refresh: std::sync::OnceLock::new(),
            }
        });
        let output = Output::new(std::io::stdout());
        let input = match transport::incoming(std::io::stdin(), output.clone()) {
            Ok(input) => input,
            Err(e) => {
                eprintln!("ilmr-lsp: cannot read stdin: {e}");
                return ExitCode::FAILURE;
            }
        };
        Server::new(input, Outgoing::new(output), socket)
            .serve(service)
            .await;
        ExitCode::SUCCESS
    })
}

async fn publish(client: &Client, publishes: Vec<Publish>) {
    for p in publishes {
        client
            .publish_diagnostics(p.uri, p.diagnostics, p.version)
            .await;
    }
}

/// Publishes what edits' jobs checked, in order, for as long as the server runs.
async fn forward(client: Client, mut queue: tokio::sync::mpsc::UnboundedReceiver<Vec<Publish>>) {
    while let Some(publishes) = queue.recv().await {
        publish(&client, publishes).await;
    }
}

/// `{"robot": "workpartner"}` in initialization options, or `{"ilmr": {"robot": ..}}`
/// in a configuration change.
fn robot_setting(value: &Value) -> Option<String> {
    let v = value.get("ilmr").unwrap_or(value);
    v.get("robot").and_then(Value::as_str).map(str::to_string)
}

fn roots(params: &InitializeParams) -> Vec<PathBuf> {
    let folders = params.workspace_folders.iter().flatten().map(|f| &f.uri);
    #[allow(deprecated)]
    let root = params.root_uri.iter();
    let mut out: Vec<PathBuf> = folders
        .chain(root)
        .filter_map(|u| u.to_file_path().map(|p| p.into_owned()))
        .collect();
    out.dedup();
    out
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        let settings = Settings {
            robot: params
                .initialization_options
                .as_ref()
                .and_then(robot_setting),
            snippets: params
                .capabilities
                .text_document
                .as_ref()
                .and_then(|t| t.completion.as_ref())
                .and_then(|c| c.completion_item.as_ref())
                .and_then(|i| i.snippet_support)
                .unwrap_or(false),
            ilmrc: params
                .initialization_options
                .as_ref()
                .and_then(|o| o.get("ilmrc"))
                .and_then(Value::as_str)
                .map(str::to_string),
        };
        let workspace = params.capabilities.workspace.as_ref();
        let refresh = Refresh {
            inlay_hints: workspace
                .and_then(|w| w.inlay_hint.as_ref())
                .and_then(|c| c.refresh_support)
                .unwrap_or(false),
            code_lenses: workspace
                .and_then(|w| w.code_lens.as_ref())
                .and_then(|c| c.refresh_support)
                .unwrap_or(false),
        };
        let _ = self.refresh.set(refresh);
        let roots = roots(&params);
        let note = self
            .ask(move |e| {
                *e = Engine::new(roots, settings);
                e.robot().note.clone()
            })
            .await
            .flatten();
        if let Some(note) = note {
            self.client.show_message(MessageType::WARNING, note).await;
        }
        Ok(InitializeResult {
            server_info: Some(ServerInfo {
                name: "ilmr-lsp".into(),
                version: Some(env!("CARGO_PKG_VERSION").into()),
            }),
            capabilities: capabilities(),
            offset_encoding: None,
        })
    }

    async fn initialized(&self, _: InitializedParams) {
        let watchers = [
            "**/*.ilmr",
            "**/*.ilms",
            "**/ROBO.INI",
            "**/robo.ini",
            "**/Robo.ini",
        ]
        .into_iter()
        .map(|glob| FileSystemWatcher {
            glob_pattern: GlobPattern::String(glob.into()),
            kind: None,
        })
        .collect();
        let options = DidChangeWatchedFilesRegistrationOptions { watchers };
        let registration = Registration {
            id: "ilmr-files".into(),
            method: "workspace/didChangeWatchedFiles".into(),
            register_options: serde_json::to_value(options).ok(),
        };
        // Clients without dynamic registration refuse; the server then sees only what
        // the editor opens, which is still correct.
        let _ = self.client.register_capability(vec![registration]).await;
    }

    async fn shutdown(&self) -> Result<()> {
        Ok(())
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        let d = params.text_document;
        let out = self.ask(move |e| e.open(d.uri, d.version, d.text));
        self.publish(out.await).await;
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        let d = params.text_document;
        let changes = params.content_changes;
        let this = self.edits.fetch_add(1, Ordering::SeqCst) + 1;
        let edits = Arc::clone(&self.edits);
        let publishes = self.publishes.clone();
        // Not waited for, so that the next edits are read (and counted) while this
        // one's job waits or runs.
        self.tell(move |e| {
            e.apply_change(&d.uri, d.version, changes);
            // A newer edit's job comes behind this one and checks both.
            if edits.load(Ordering::SeqCst) == this
                && let Some(out) = e.refresh()
            {
                let _ = publishes.send(out);
            }
        });
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        let out = self.ask(move |e| e.close(&uri));
        self.publish(out.await).await;
    }

    async fn did_change_configuration(&self, params: DidChangeConfigurationParams) {
        let robot = robot_setting(&params.settings);
        let out = self.ask(move |e| {
            let out = e.configure(robot);
            (out, e.robot().note.clone())
        });
        if let Some((out, note)) = out.await {
            if let Some(note) = note {
                self.client.show_message(MessageType::WARNING, note).await;
            }
            self.publish(Some(out)).await;
        }
    }

    async fn did_change_watched_files(&self, params: DidChangeWatchedFilesParams) {
        let uris: Vec<Uri> = params.changes.into_iter().map(|c| c.uri).collect();
        let out = self.ask(move |e| e.files_changed(&uris));
        self.publish(out.await).await;
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        let items = self
            .position_query(params.text_document_position, |e, u, p| {
                e.completion_list(u, p)
            })
            .await;
        Ok(items.map(CompletionResponse::List))
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let hover = self
            .position_query(params.text_document_position_params, |e, u, p| {
                e.hover(u, p)
            })
            .await;
        Ok(hover.flatten())
    }

    async fn signature_help(&self, params: SignatureHelpParams) -> Result<Option<SignatureHelp>> {
        let help = self
            .position_query(params.text_document_position_params, |e, u, p| {
                e.signature_help(u, p)
            })
            .await;
        Ok(help.flatten())
    }

    async fn goto_definition(
        &self,
        params: GotoDefinitionParams,
    ) -> Result<Option<GotoDefinitionResponse>> {
        let defs = self
            .position_query(params.text_document_position_params, |e, u, p| {
                e.definition(u, p)
            })
            .await
            .unwrap_or_default();
        Ok((!defs.is_empty()).then_some(GotoDefinitionResponse::Array(defs)))
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        let declaration = params.context.include_declaration;
        let refs = self
            .position_query(params.text_document_position, move |e, u, p| {
                e.references(u, p, declaration)
            })
            .await;
        Ok(refs)
    }

    async fn prepare_rename(
        &self,
        params: TextDocumentPositionParams,
    ) -> Result<Option<PrepareRenameResponse>> {
        let answer = self
            .position_query(params, |e, u, p| e.prepare_rename(u, p))
            .await;
        Ok(answer.flatten())
    }

    async fn rename(&self, params: RenameParams) -> Result<Option<WorkspaceEdit>> {
        let name = params.new_name;
        let edit = self
            .position_query(params.text_document_position, move |e, u, p| {
                e.rename(u, p, &name)
            })
            .await;
        match edit {
            Some(Ok(edit)) => Ok(Some(edit)),
            Some(Err(e)) => Err(Error::invalid_params(e.to_string())),
            None => Err(Error::internal_error()),
        }
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        let uri = params.text_document.uri;
        let symbols = self.query(move |e| e.document_symbols(&uri)).await;
        Ok(symbols.map(DocumentSymbolResponse::Nested))
    }

    async fn folding_range(&self, params: FoldingRangeParams) -> Result<Option<Vec<FoldingRange>>> {
        let uri = params.text_document.uri;
        Ok(self.query(move |e| e.folding_ranges(&uri)).await)
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        let uri = params.text_document.uri;
        let data = self.query(move |e| e.semantic_tokens(&uri)).await;
        Ok(data.map(|data| {
            SemanticTokensResult::Tokens(SemanticTokens {
                result_id: None,
                data,
            })
        }))
    }

    async fn semantic_tokens_range(
        &self,
        params: SemanticTokensRangeParams,
    ) -> Result<Option<SemanticTokensRangeResult>> {
        let uri = params.text_document.uri;
        let range = params.range;
        let data = self.query(move |e| e.semantic_tokens_in(&uri, range)).await;
        Ok(data.map(|data| {
            SemanticTokensRangeResult::Tokens(SemanticTokens {
                result_id: None,
                data,
            })
        }))
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        let uri = params.text_document.uri;
        Ok(self.query(move |e| e.formatting(&uri)).await.flatten())
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        let uri = params.text_document.uri;
        let range = params.range;
        Ok(self.query(move |e| e.inlay_hints(&uri, range)).await)
    }

    async fn code_lens(&self, params: CodeLensParams) -> Result<Option<Vec<CodeLens>>> {
        let uri = params.text_document.uri;
        Ok(self.query(move |e| e.code_lenses(&uri)).await)
    }

    async fn symbol(
        &self,
        params: WorkspaceSymbolParams,
    ) -> Result<Option<WorkspaceSymbolResponse>> {
        let query = params.query;
        let found = self.query(move |e| e.workspace_symbols(&query)).await;
        Ok(found.map(WorkspaceSymbolResponse::Flat))
    }

    async fn document_highlight(
        &self,
        params: DocumentHighlightParams,
    ) -> Result<Option<Vec<DocumentHighlight>>> {
        let highlights = self
            .position_query(params.text_document_position_params, |e, u, p| {
                e.document_highlights(u, p)
            })
            .await;
        Ok(highlights)
    }

    /// `ilmr.run`: runs the task in the simulator off the engine's thread, shows the
    /// summary, keeps the trace's times, and has the client ask for hints and lenses
    /// again. Answers `{"summary", "exit", "lines"}`.
    async fn execute_command(&self, params: ExecuteCommandParams) -> Result<Option<Value>> {
        if params.command != RUN_COMMAND {
            return Err(Error::invalid_params(format!(
                "unknown command `{}`; this server runs `{RUN_COMMAND}`",
                params.command
            )));
        }
        let uri: Uri = params
            .arguments
            .first()
            .and_then(Value::as_str)
            .and_then(|u| u.parse().ok())
            .ok_or_else(|| {
                Error::invalid_params(format!("`{RUN_COMMAND}` takes a document's URI"))
            })?;
        let asked = uri.clone();
        let plan = self
            .query(move |e| e.run_invocation(&asked))
            .await
            .ok_or_else(Error::internal_error)?;
        let (invocation, text, note) = plan.map_err(Error::invalid_params)?;
        let mut last = tokio::task::spawn_blocking(move || run::run(&invocation, &text))
            .await
            .map_err(|_| Error::internal_error())?;
        if let Some(note) = note {
            last.summary.push_str(&format!("\n({note})"));
        }
        let answer = serde_json::json!({
            "summary": last.summary,
            "exit": last.exit,
            "lines": last.times.len(),
        });
        let kind = if last.exit == Some(0) {
            MessageType::INFO
        } else {
            MessageType::WARNING
        };
        self.client.show_message(kind, last.summary.clone()).await;
        self.ask(move |e| e.set_run(&uri, last)).await;
        let refresh = self.refresh.get().copied().unwrap_or_default();
        if refresh.inlay_hints {
            let _ = self.client.inlay_hint_refresh().await;
        }
        if refresh.code_lenses {
            let _ = self.client.code_lens_refresh().await;
        }
        Ok(Some(answer))
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        let uri = params.text_document.uri;
        let range = params.range;
        let actions = self.query(move |e| e.code_actions(&uri, range)).await;
        Ok(actions)
    }
}

fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        position_encoding: Some(PositionEncodingKind::UTF16),
        text_document_sync: Some(TextDocumentSyncCapability::Kind(
            TextDocumentSyncKind::INCREMENTAL,
        )),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec!["(".into(), ",".into(), "=".into()]),
            ..Default::default()
        }),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        signature_help_provider: Some(SignatureHelpOptions {
            trigger_characters: Some(vec!["(".into(), ",".into()]),
            retrigger_characters: Some(vec!["=".into()]),
            work_done_progress_options: Default::default(),
        }),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        rename_provider: Some(OneOf::Right(RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: Default::default(),
        })),
        document_symbol_provider: Some(OneOf::Left(true)),
        folding_range_provider: Some(FoldingRangeProviderCapability::Simple(true)),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: semantic::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                range: Some(true),
                work_done_progress_options: Default::default(),
            },
        )),
        document_formatting_provider: Some(OneOf::Left(true)),
        inlay_hint_provider: Some(OneOf::Left(true)),
        code_lens_provider: Some(CodeLensOptions {
            resolve_provider: Some(false),
        }),
        workspace_symbol_provider: Some(OneOf::Left(true)),
        document_highlight_provider: Some(OneOf::Left(true)),
        execute_command_provider: Some(ExecuteCommandOptions {
            commands: vec![RUN_COMMAND.to_string()],
            work_done_progress_options: Default::default(),
        }),
        code_action_provider: Some(CodeActionProviderCapability::Options(CodeActionOptions {
            code_action_kinds: Some(vec![CodeActionKind::QUICKFIX]),
            ..Default::default()
        })),
        ..Default::default()
    }
}
