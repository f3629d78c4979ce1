//! The language server's logic without the protocol: the workspace's files, the robot
//! model, and the checked program, re-checked whole on every change (a 10,000-line
//! task re-checks in a few milliseconds), with one method per LSP feature taking and
//! returning LSP values. Tests drive it directly; `server.rs` only carries messages.

use std::cell::RefCell;
use std::collections::{BTreeSet, HashMap};
use std::path::PathBuf;
use std::rc::Rc;

use ilmr_compiler::Span;
use ilmr_compiler::check::schedule::{Moment, schedule};
use ilmr_compiler::diagnostic::FileId;
use tower_lsp_server::ls_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, CodeLens, Command, CompletionItem,
    CompletionList, Diagnostic, DocumentHighlight, DocumentHighlightKind, DocumentSymbol,
    FoldingRange, Hover, HoverContents, InlayHint, InlayHintKind, InlayHintLabel, InlayHintTooltip,
    Location, MarkupContent, MarkupKind, Position, PrepareRenameResponse, Range, SemanticToken,
    SignatureHelp, SymbolInformation, TextDocumentContentChangeEvent, TextEdit, Uri, WorkspaceEdit,
};

use crate::analysis::{Analyzer, Program};
use crate::diagnostics::{self, Locate};
use crate::lens::{self, Breaks, FileLens};
use crate::navigation::{self, RenameError};
use crate::robot::{self, Robot};
use crate::run::{self, Invocation, LastRun};
use crate::testfiles::{self, TestFiles};
use crate::workspace::{Document, FileKind, Workspace};
use crate::{completion, hover, outline, semantic, signature, symbols, units};

/// Diagnostics to send for one document, with the version they were computed for.
#[derive(Debug, Clone, PartialEq)]
pub struct Publish {
    pub uri: Uri,
    pub version: Option<i32>,
    pub diagnostics: Vec<Diagnostic>,
}

#[derive(Debug, Clone, Default)]
pub struct Settings {
    /// `moro`, `workpartner` or a path to a ROBO.INI; the workspace's ROBO.INI wins.
    pub robot: Option<String>,
    /// Whether the client inserts snippets (`turn(d=${1:d},c=${2:c})`).
    pub snippets: bool,
    /// The `ilmrc` the "run in simulator" lens runs (`initializationOptions.ilmrc`);
    /// `None`: beside the server, else on `PATH` ([`run::find_ilmrc`]).
    pub ilmrc: Option<String>,
}

/// What the concurrency lens computed from the current analysis, kept until the next
/// check: inlay hints are asked on every scroll.
#[derive(Default)]
struct LensCache {
    schedules: HashMap<FileId, Rc<Vec<Moment>>>,
    breaks: Option<Rc<Breaks>>,
}

pub struct Engine {
    workspace: Workspace,
    settings: Settings,
    robot: Robot,
    program: Program,
    /// Documents last sent a non-empty list, so that an emptied one is cleared.
    published: BTreeSet<String>,
    analyzer: Analyzer,
    /// Lines for the client's log (`window/logMessage`), taken after each job.
    log: Vec<String>,
    /// Edits applied since the last check (and whether one was to the robot model):
    /// a burst of edits is checked once, after its last ([`Engine::apply_change`]).
    stale: Option<bool>,
    lens: RefCell<LensCache>,
    /// Each task's last run (the "run in simulator" lens), by URI.
    runs: HashMap<String, LastRun>,
    /// Open test files (`*.test.toml`), apart from the program.
    tests: TestFiles,
}

impl Default for Engine {
    fn default() -> Engine {
        Engine::new(Vec::new(), Settings::default())
    }
}

impl Engine {
    pub fn new(roots: Vec<PathBuf>, settings: Settings) -> Engine {
        Engine::with_analyzer(roots, settings, ilmr_compiler::check::analyze)
    }

    /// An engine analysing with `analyzer` in place of the compiler's own.
    pub fn with_analyzer(roots: Vec<PathBuf>, settings: Settings, analyzer: Analyzer) -> Engine {
        let workspace = Workspace::new(roots);
        let robot = robot::choose(&workspace, settings.robot.as_deref());
        let mut log = Vec::new();
        let program = check(&workspace, &robot, analyzer, &mut log);
        Engine {
            workspace,
            settings,
            robot,
            program,
            published: BTreeSet::new(),
            analyzer,
            log,
            stale: None,
            lens: RefCell::default(),
            runs: HashMap::new(),
            tests: TestFiles::default(),
        }
    }

    /// What happened since the last call that the client's log should show.
    pub fn take_log(&mut self) -> Vec<String> {
        std::mem::take(&mut self.log)
    }

    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    pub fn document(&self, uri: &Uri) -> Option<&Document> {
        self.workspace.get(uri)
    }

    // ------------------------------------------------------------ changes

    pub fn open(&mut self, uri: Uri, version: i32, text: String) -> Vec<Publish> {
        if testfiles::is_test(&uri) {
            return self.tests.open(uri, version, text);
        }
        let kind = FileKind::of(uri.as_str());
        if self.workspace.open(uri, version, text) {
            self.recheck(kind == Some(FileKind::RobotModel))
        } else {
            Vec::new()
        }
    }

    pub fn change(
        &mut self,
        uri: &Uri,
        version: i32,
        changes: Vec<TextDocumentContentChangeEvent>,
    ) -> Vec<Publish> {
        self.apply_change(uri, version, changes);
        self.refresh().unwrap_or_default()
    }

    /// Applies an edit without checking: the server applies every edit of a burst as
    /// it comes and checks once, when no newer edit waits ([`Engine::refresh`]).
    pub fn apply_change(
        &mut self,
        uri: &Uri,
        version: i32,
        changes: Vec<TextDocumentContentChangeEvent>,
    ) {
        if testfiles::is_test(uri) {
            return self.tests.change(uri, version, changes);
        }
        if self.workspace.change(uri, version, changes) {
            let model = FileKind::of(uri.as_str()) == Some(FileKind::RobotModel);
            self.stale = Some(self.stale.unwrap_or(false) | model);
        }
    }

    /// Checks the edits applied since the last check, if any: what to publish.
    /// Queries call it first, so that they never answer from an older text's analysis.
    pub fn refresh(&mut self) -> Option<Vec<Publish>> {
        let tests = self.tests.refresh();
        let Some(model) = self.stale.take() else {
            return tests;
        };
        let mut out = self.recheck(model);
        out.extend(tests.into_iter().flatten());
        Some(out)
    }

    pub fn close(&mut self, uri: &Uri) -> Vec<Publish> {
        if testfiles::is_test(uri) {
            return self.tests.close(uri);
        }
        self.workspace.close(uri);
        self.recheck(FileKind::of(uri.as_str()) == Some(FileKind::RobotModel))
    }

    /// Files changed on disk (the client's file watcher).
    pub fn files_changed(&mut self, uris: &[Uri]) -> Vec<Publish> {
        let mut changed = false;
        let mut model = false;
        for uri in uris {
            if self.workspace.disk_changed(uri) {
                changed = true;
                model |= FileKind::of(uri.as_str()) == Some(FileKind::RobotModel);
            }
            // A model named by the setting may live outside the workspace.
            model |= self.robot.file.as_ref().is_some_and(|f| f == uri);
            changed |= model;
        }
        // What a test file names (its task, skills, world, model) is read from disk.
        let tests = self.tests.recheck();
        let mut out = if changed {
            self.recheck(model)
        } else {
            Vec::new()
        };
        out.extend(tests);
        out
    }

    pub fn configure(&mut self, robot: Option<String>) -> Vec<Publish> {
        if self.settings.robot == robot {
            return Vec::new();
        }
        self.settings.robot = robot;
        self.recheck(true)
    }

    fn recheck(&mut self, model_changed: bool) -> Vec<Publish> {
        // Whatever asked, this check covers the edits applied before it.
        let model_changed = model_changed | self.stale.take().unwrap_or(false);
        if model_changed {
            self.robot = robot::choose(&self.workspace, self.settings.robot.as_deref());
        }
        self.program = check(&self.workspace, &self.robot, self.analyzer, &mut self.log);
        self.lens = RefCell::default();
        self.publish()
    }

    /// Diagnostics of every open document, of the robot model when it has warnings,
    /// and empty lists for documents that had some before.
    pub fn publish(&mut self) -> Vec<Publish> {
        let mut out = Vec::new();
        for doc in self.workspace.documents().filter(|d| d.is_open()) {
            if doc.kind == FileKind::Program {
                out.push(Publish {
                    uri: doc.uri.clone(),
                    version: doc.version,
                    diagnostics: self.diagnostics(&doc.uri),
                });
            }
        }
        if let Some(file) = &self.robot.file {
            let doc = self.workspace.get(file);
            let text = doc.map(|d| (d.text.as_str(), &d.index));
            let diagnostics: Vec<Diagnostic> = self
                .robot
                .warnings
                .iter()
                .map(|w| diagnostics::model_warning(w, text))
                .collect();
            if !diagnostics.is_empty() || self.published.contains(file.as_str()) {
                out.push(Publish {
                    uri: file.clone(),
                    version: doc.and_then(|d| d.version),
                    diagnostics,
                });
            }
        }
        let now: BTreeSet<String> = out
            .iter()
            .filter(|p| !p.diagnostics.is_empty())
            .map(|p| p.uri.as_str().to_string())
            .collect();
        for gone in self.published.difference(&now) {
            if out.iter().any(|p| p.uri.as_str() == gone) {
                continue;
            }
            if let Ok(uri) = gone.parse::<Uri>() {
                out.push(Publish {
                    uri,
                    version: None,
                    diagnostics: Vec::new(),
                });
            }
        }
        self.published = now;
        out
    }

    // ------------------------------------------------------------ queries

    /// The document, its file in the program and the byte offset of a position.
    fn at(&self, uri: &Uri, position: Position) -> Option<(&Document, FileId, usize)> {
        let doc = self.workspace.get(uri)?;
        let file = self.program.file_id(uri.as_str())?;
        Some((doc, file, doc.index.offset(&doc.text, position)))
    }

    pub fn diagnostics(&self, uri: &Uri) -> Vec<Diagnostic> {
        if testfiles::is_test(uri) {
            return self.tests.diagnostics(uri);
        }
        if self.workspace.get(uri).is_some_and(too_large) {
            return vec![diagnostics::too_large()];
        }
        if self
            .program
            .failures()
            .iter()
            .any(|f| f.uri == uri.as_str())
        {
            return vec![diagnostics::analysis_failed()];
        }
        let (Some(doc), Some(file)) = (self.workspace.get(uri), self.program.file_id(uri.as_str()))
        else {
            return Vec::new();
        };
        self.program
            .analysis()
            .diagnostics
            .iter()
            .filter(|d| d.file == file)
            .map(|d| diagnostics::to_lsp(d, doc.index.range(&doc.text, d.span), self))
            .collect()
    }

    pub fn completion(&self, uri: &Uri, position: Position) -> Vec<CompletionItem> {
        self.completion_list(uri, position).items
    }

    /// Completion as the client gets it: incomplete when variables were left out
    /// ([`completion::MAX_VARIABLE_ITEMS`]), so that it asks again as a name is typed.
    pub fn completion_list(&self, uri: &Uri, position: Position) -> CompletionList {
        if testfiles::is_test(uri) {
            return self.tests.completion(uri, position);
        }
        let Some((doc, file, offset)) = self.at(uri, position) else {
            return CompletionList::default();
        };
        completion::complete(&completion::Request {
            program: &self.program,
            model: &self.robot.model,
            file,
            index: &doc.index,
            offset,
            snippets: self.settings.snippets,
        })
    }

    pub fn hover(&self, uri: &Uri, position: Position) -> Option<Hover> {
        if testfiles::is_test(uri) {
            return self.tests.hover(uri, position);
        }
        let (doc, file, offset) = self.at(uri, position)?;
        let (value, span) = hover::hover(&self.program, &self.robot.model, file, offset)?;
        Some(Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value,
            }),
            range: Some(doc.index.range(&doc.text, span)),
        })
    }

    pub fn signature_help(&self, uri: &Uri, position: Position) -> Option<SignatureHelp> {
        let (doc, _, offset) = self.at(uri, position)?;
        let line = doc.index.line_of(offset);
        let start = doc.index.line_span(&doc.text, line).start as usize;
        signature::help(&doc.text, start, offset, &self.robot.model)
    }

    pub fn definition(&self, uri: &Uri, position: Position) -> Vec<Location> {
        let Some((_, file, offset)) = self.at(uri, position) else {
            return Vec::new();
        };
        self.locations(navigation::definition(&self.program, file, offset))
    }

    pub fn references(&self, uri: &Uri, position: Position, declaration: bool) -> Vec<Location> {
        let Some((_, file, offset)) = self.at(uri, position) else {
            return Vec::new();
        };
        self.locations(navigation::references(
            &self.program,
            file,
            offset,
            declaration,
        ))
    }

    pub fn prepare_rename(&self, uri: &Uri, position: Position) -> Option<PrepareRenameResponse> {
        let (doc, file, offset) = self.at(uri, position)?;
        let (span, placeholder) = navigation::prepare_rename(&self.program, file, offset)?;
        Some(PrepareRenameResponse::RangeWithPlaceholder {
            range: doc.index.range(&doc.text, span),
            placeholder,
        })
    }

    pub fn rename(
        &self,
        uri: &Uri,
        position: Position,
        new_name: &str,
    ) -> Result<WorkspaceEdit, RenameError> {
        let (_, file, offset) = self.at(uri, position).ok_or(RenameError::NothingToRename)?;
        let spans = navigation::rename(&self.program, &self.robot.model, file, offset, new_name)?;
        let mut changes = std::collections::HashMap::new();
        for (file, span) in spans {
            if let Some((uri, range)) = self.locate(file, span) {
                changes
                    .entry(uri)
                    .or_insert_with(Vec::new)
                    .push(TextEdit::new(range, new_name.to_string()));
            }
        }
        Ok(WorkspaceEdit::new(changes))
    }

    pub fn document_symbols(&self, uri: &Uri) -> Vec<DocumentSymbol> {
        let (Some(doc), Some(file)) = (self.workspace.get(uri), self.program.file_id(uri.as_str()))
        else {
            return Vec::new();
        };
        outline::symbols(self.program.tree(file), &doc.text, &doc.index)
    }

    pub fn folding_ranges(&self, uri: &Uri) -> Vec<FoldingRange> {
        let (Some(doc), Some(file)) = (self.workspace.get(uri), self.program.file_id(uri.as_str()))
        else {
            return Vec::new();
        };
        outline::folding_ranges(self.program.tree(file), &doc.text, &doc.index)
    }

    pub fn semantic_tokens(&self, uri: &Uri) -> Vec<SemanticToken> {
        let (Some(doc), Some(file)) = (self.workspace.get(uri), self.program.file_id(uri.as_str()))
        else {
            return Vec::new();
        };
        let whole = Span::new(0, doc.text.len());
        semantic::tokens(&self.program, file, &doc.index, whole)
    }

    /// The semantic tokens of the lines an editor shows: on a file of a million
    /// tokens, what it can colour at once without waiting for all of them.
    pub fn semantic_tokens_in(&self, uri: &Uri, range: Range) -> Vec<SemanticToken> {
        let (Some(doc), Some(file)) = (self.workspace.get(uri), self.program.file_id(uri.as_str()))
        else {
            return Vec::new();
        };
        let within = doc.index.span(&doc.text, range);
        semantic::tokens(&self.program, file, &doc.index, within)
    }

    /// `ilmrc fmt`'s text as one edit; `None` when the file has syntax errors.
    pub fn formatting(&self, uri: &Uri) -> Option<Vec<TextEdit>> {
        let doc = self.workspace.get(uri)?;
        if doc.kind != FileKind::Program {
            return None;
        }
        let formatted = ilmr_compiler::format::format(&doc.text, &self.robot.model).ok()?;
        if formatted == doc.text {
            return Some(Vec::new());
        }
        let whole = doc.index.range(&doc.text, Span::new(0, doc.text.len()));
        Some(vec![TextEdit::new(whole, formatted)])
    }

    /// Quick fixes for the diagnostics in `range` that carry one.
    pub fn code_actions(&self, uri: &Uri, range: Range) -> Vec<CodeActionOrCommand> {
        let (Some(doc), Some(file)) = (self.workspace.get(uri), self.program.file_id(uri.as_str()))
        else {
            return Vec::new();
        };
        let wanted = doc.index.span(&doc.text, range);
        let mut out = Vec::new();
        for d in self.program.analysis().diagnostics.iter() {
            let Some(fix) = &d.fix else { continue };
            let overlaps =
                d.file == file && d.span.start <= wanted.end && wanted.start <= d.span.end;
            if !overlaps {
                continue;
            }
            let Some((fix_uri, fix_range)) = self.locate(d.file, fix.span) else {
                continue;
            };
            let diagnostic = diagnostics::to_lsp(d, doc.index.range(&doc.text, d.span), self);
            let mut changes = std::collections::HashMap::new();
            changes.insert(
                fix_uri,
                vec![TextEdit::new(fix_range, fix.replacement.clone())],
            );
            out.push(CodeActionOrCommand::CodeAction(CodeAction {
                title: fix.title.clone(),
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![diagnostic]),
                edit: Some(WorkspaceEdit::new(changes)),
                is_preferred: Some(true),
                ..Default::default()
            }));
        }
        out
    }

    // ------------------------------------------------------------ the lens

    /// The concurrency lens, the units of arguments and the last run's times, for the
    /// statements inside `range`.
    pub fn inlay_hints(&self, uri: &Uri, range: Range) -> Vec<InlayHint> {
        let (Some(doc), Some(file)) = (self.workspace.get(uri), self.program.file_id(uri.as_str()))
        else {
            return Vec::new();
        };
        let wanted = doc.index.span(&doc.text, range);
        let (moments, breaks) = self.lens_facts(file);
        let lens = FileLens {
            program: &self.program,
            file,
            text: &doc.text,
            index: &doc.index,
            moments: &moments,
            breaks: &breaks,
        };
        let mut out: Vec<(usize, u8, InlayHint)> = Vec::new();
        let position = |at: usize| doc.index.position(&doc.text, at);
        for u in units::hints(&self.program, file, wanted) {
            let hint = InlayHint {
                position: position(u.at),
                label: InlayHintLabel::String(u.symbol.to_string()),
                kind: Some(InlayHintKind::TYPE),
                text_edits: None,
                tooltip: Some(InlayHintTooltip::String(format!("{}: {}", u.param, u.doc))),
                padding_left: Some(true),
                padding_right: None,
                data: None,
            };
            out.push((u.at, 0, hint));
        }
        for l in lens.labels(wanted) {
            let hint = InlayHint {
                position: position(l.at),
                label: InlayHintLabel::String(l.text),
                kind: None,
                text_edits: None,
                tooltip: Some(InlayHintTooltip::String(l.tooltip)),
                padding_left: Some(true),
                padding_right: None,
                data: None,
            };
            out.push((l.at, 1, hint));
        }
        if let Some(last) = self.runs.get(uri.as_str())
            && last.text == run::fingerprint(&doc.text)
        {
            let first = doc.index.line_of(wanted.start as usize) as u32 + 1;
            let last_line = doc.index.line_of(wanted.end as usize) as u32 + 1;
            for (&line, times) in last.times.range(first..=last_line) {
                let at = doc.index.line_span(&doc.text, line as usize - 1).end as usize;
                let hint = InlayHint {
                    position: position(at),
                    label: InlayHintLabel::String(times.label()),
                    kind: None,
                    text_edits: None,
                    tooltip: Some(InlayHintTooltip::String(format!(
                        "From the last run in the simulator: {}",
                        last.headline()
                    ))),
                    padding_left: Some(true),
                    padding_right: None,
                    data: None,
                };
                out.push((at, 2, hint));
            }
        }
        out.sort_by_key(|(at, order, _)| (*at, *order));
        out.into_iter().map(|(_, _, h)| h).collect()
    }

    /// The file's schedule and the program's breaks, computed once per check.
    fn lens_facts(&self, file: FileId) -> (Rc<Vec<Moment>>, Rc<Breaks>) {
        let mut cache = self.lens.borrow_mut();
        let moments = cache
            .schedules
            .entry(file)
            .or_insert_with(|| Rc::new(schedule(self.program.analysis(), &self.robot.model, file)))
            .clone();
        let breaks = cache
            .breaks
            .get_or_insert_with(|| Rc::new(lens::breaks(&self.program)))
            .clone();
        (moments, breaks)
    }

    /// "Run in simulator" on a task file, with how its last run ended.
    pub fn code_lenses(&self, uri: &Uri) -> Vec<CodeLens> {
        let Some(doc) = self.workspace.get(uri) else {
            return Vec::new();
        };
        let task = uri.as_str().to_ascii_lowercase().ends_with(".ilmr");
        if doc.kind != FileKind::Program || !task {
            return Vec::new();
        }
        let mut title = "▶ run in simulator".to_string();
        if let Some(last) = self.runs.get(uri.as_str()) {
            title.push_str(&format!(" · last run: {}", last.headline()));
            if last.text != run::fingerprint(&doc.text) {
                title.push_str(" (an earlier text)");
            }
        }
        vec![CodeLens {
            range: Range::new(Position::new(0, 0), Position::new(0, 0)),
            command: Some(Command {
                title,
                command: run::RUN_COMMAND.to_string(),
                arguments: Some(vec![serde_json::Value::String(uri.as_str().to_string())]),
            }),
            data: None,
        }]
    }

    /// How to run a task file as it is saved, that text, and a note on what the run
    /// leaves out; why it cannot run, else.
    pub fn run_invocation(
        &self,
        uri: &Uri,
    ) -> Result<(Invocation, String, Option<String>), String> {
        let doc = self.workspace.get(uri).ok_or("the document is not known")?;
        let task = doc
            .uri
            .to_file_path()
            .map(|p| p.into_owned())
            .filter(|p| {
                p.extension()
                    .is_some_and(|e| e.eq_ignore_ascii_case("ilmr"))
            })
            .ok_or("only a task file (.ilmr) on disk can run")?;
        let saved = std::fs::read_to_string(&task)
            .map_err(|e| format!("cannot read {}: {e}", task.display()))?;
        let robot = match &self.robot.file {
            Some(model) => model
                .to_file_path()
                .map(|p| p.to_string_lossy().into_owned())
                .unwrap_or_else(|| robot::DEFAULT_ROBOT.to_string()),
            None => self
                .settings
                .robot
                .clone()
                .unwrap_or_else(|| robot::DEFAULT_ROBOT.to_string()),
        };
        let paths = |ext: &str| -> Vec<PathBuf> {
            self.workspace
                .programs()
                .filter_map(|d| d.uri.to_file_path().map(|p| p.into_owned()))
                .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case(ext)))
                .collect()
        };
        let skills = run::skills_argument(&paths("ilms"), &paths("ilmr"));
        let invocation = Invocation {
            ilmrc: run::find_ilmrc(self.settings.ilmrc.as_deref()),
            task,
            robot,
            skills: skills.clone().unwrap_or(None),
        };
        Ok((invocation, saved, skills.err()))
    }

    /// Keeps a run's outcome for the task's hints and lens.
    pub fn set_run(&mut self, uri: &Uri, last: LastRun) {
        self.runs.insert(uri.as_str().to_string(), last);
    }

    pub fn last_run(&self, uri: &Uri) -> Option<&LastRun> {
        self.runs.get(uri.as_str())
    }

    /// Skills, variables and paths of the whole program whose names hold the query.
    pub fn workspace_symbols(&self, query: &str) -> Vec<SymbolInformation> {
        let (found, _) = symbols::workspace(&self.program, query);
        found
            .into_iter()
            .filter_map(|f| {
                let (uri, range) = self.locate(f.file, f.span)?;
                #[allow(deprecated)]
                Some(SymbolInformation {
                    name: f.name,
                    kind: f.kind,
                    tags: None,
                    deprecated: None,
                    location: Location::new(uri, range),
                    container_name: Some(f.detail.to_string()),
                })
            })
            .collect()
    }

    /// The occurrences in this document of the name under the cursor.
    pub fn document_highlights(&self, uri: &Uri, position: Position) -> Vec<DocumentHighlight> {
        let Some((doc, file, offset)) = self.at(uri, position) else {
            return Vec::new();
        };
        symbols::highlights(&self.program, file, offset)
            .into_iter()
            .map(|(span, binds)| DocumentHighlight {
                range: doc.index.range(&doc.text, span),
                kind: Some(if binds {
                    DocumentHighlightKind::WRITE
                } else {
                    DocumentHighlightKind::READ
                }),
            })
            .collect()
    }

    fn locations(&self, spans: Vec<(FileId, Span)>) -> Vec<Location> {
        spans
            .into_iter()
            .filter_map(|(f, s)| self.locate(f, s))
            .map(|(uri, range)| Location::new(uri, range))
            .collect()
    }
}

impl Locate for Engine {
    fn locate(&self, file: FileId, span: Span) -> Option<(Uri, Range)> {
        let uri = self.program.uri(file)?;
        let doc = self.workspace.get_str(uri)?;
        Some((doc.uri.clone(), doc.index.range(&doc.text, span)))
    }
}

fn check(
    workspace: &Workspace,
    robot: &Robot,
    analyzer: Analyzer,
    log: &mut Vec<String>,
) -> Program {
    let files = workspace
        .programs()
        .filter(|d| !too_large(d))
        .map(|d| (d.uri.as_str().to_string(), d.text.clone()))
        .collect();
    let program = Program::check(files, &robot.model, analyzer);
    for f in program.failures() {
        log.push(format!(
            "ilmr-lsp: the analysis failed on {}: {}",
            f.uri, f.panic
        ));
    }
    program
}

/// A program file larger than `ilmrc` reads one: not analysed (the disk scan does not
/// even read one; an editor may still open it).
fn too_large(doc: &Document) -> bool {
    doc.kind == FileKind::Program && doc.text.len() as u64 > ilmr_files::MAX_SOURCE_BYTES
}
