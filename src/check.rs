//! `ilmrc check`.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use ilmr_compiler::check::{Analysis, Detail, Source, analyze_with};
use ilmr_compiler::render::{self, RenderFile, Style};
use ilmr_compiler::{Code, Diagnostic, FileId, LineIndex, Span};

use crate::inputs;

#[derive(clap::Args)]
pub struct CheckArgs {
    /// Robot model: `moro`, `workpartner`, or a path to a ROBO.INI file.
    #[arg(long, default_value = "moro")]
    pub robot: String,
    /// A skill file, or a directory of skill files (`*.ilms`), the tasks may call.
    #[arg(long)]
    pub skills: Option<PathBuf>,
    /// `human` for people, `json` for tools (one JSON array).
    #[arg(long, value_enum, default_value_t = Format::Human)]
    pub format: Format,
    /// Task and skill files.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    Human,
    Json,
}

pub fn run(args: CheckArgs) -> ExitCode {
    match check(&args) {
        Ok(report) => {
            let mut out = std::io::stdout().lock();
            let _ = out.write_all(report.output.as_bytes());
            for problem in &report.unread {
                eprintln!("error: {problem}");
            }
            ExitCode::from(if !report.unread.is_empty() {
                crate::EXIT_USAGE
            } else if report.errors {
                crate::EXIT_ERRORS
            } else {
                0
            })
        }
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

pub struct Report {
    pub output: String,
    pub errors: bool,
    /// Files that could not be read, each said as "cannot read `PATH`: why" (they
    /// are diagnostics of the output too).
    pub unread: Vec<String>,
}

/// A file given to check that could not be read, as a diagnostic: E0001 for the file
/// (at its start), E0002 at the line and column of the first byte that is not UTF-8.
struct Unread {
    path: String,
    /// What is shown of the file: its text as far as it could be read.
    text: String,
    code: Code,
    span: Span,
    message: String,
}

impl Unread {
    fn read(path: &std::path::Path) -> Result<Source, Unread> {
        let shown = path.display().to_string();
        let bytes = ilmr_files::read(path, ilmr_files::Kind::Source).map_err(|e| Unread {
            path: shown.clone(),
            text: String::new(),
            code: Code::UnreadableFile,
            span: Span::empty(0),
            message: format!("cannot read `{shown}`: {e}"),
        })?;
        String::from_utf8(bytes)
            .map(|text| Source::new(shown.clone(), text))
            .map_err(|e| {
                let offset = e.utf8_error().valid_up_to();
                let (line, column) = ilmr_files::line_column(&e.as_bytes()[..offset]);
                let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
                // The lossy text keeps the valid prefix byte for byte; the bad byte
                // became U+FFFD.
                let span = Span::new(offset, offset + '\u{FFFD}'.len_utf8());
                let why = ilmr_files::ReadError {
                    kind: ilmr_files::Kind::Source,
                    problem: ilmr_files::Problem::NotUtf8 {
                        offset,
                        line,
                        column,
                    },
                };
                Unread {
                    path: shown.clone(),
                    text,
                    code: Code::NotUtf8,
                    span,
                    message: format!("cannot read `{shown}`: {why}"),
                }
            })
    }
}

pub fn check(args: &CheckArgs) -> Result<Report, String> {
    let robot = inputs::load_robot(&args.robot)?;
    let mut sources: Vec<Source> = Vec::with_capacity(args.files.len());
    let mut unread = Vec::new();
    for path in &args.files {
        match Unread::read(path) {
            Ok(source) => sources.push(source),
            Err(u) => unread.push(u),
        }
    }
    if let Some(dir) = &args.skills {
        sources.extend(inputs::read_skill_dir(dir)?);
    }
    let analysis = analyze_with(&sources, &robot.model, Detail::Diagnostics);
    let report = report_with(args, &robot, &analysis, &unread);
    // Freeing a large program's trees and tables costs a tenth of checking it, and the
    // process ends right after: let the operating system reclaim them.
    std::mem::forget(analysis);
    std::mem::forget(sources);
    Ok(report)
}

/// What `check` says about an analysis of `args.files` (with the robot model's own
/// warnings): `build` and `run` print the same of the analysis they lower.
pub fn report(args: &CheckArgs, robot: &inputs::Robot, analysis: &Analysis<'_>) -> Report {
    report_with(args, robot, analysis, &[])
}

fn report_with(
    args: &CheckArgs,
    robot: &inputs::Robot,
    analysis: &Analysis<'_>,
    unread: &[Unread],
) -> Report {
    let mut files: Vec<RenderFile<'_>> = analysis
        .files
        .iter()
        .map(|f| RenderFile {
            path: f.path,
            text: f.text,
        })
        .collect();
    let mut diagnostics: Vec<Diagnostic> = analysis.diagnostics.clone();
    if !robot.warnings.is_empty() {
        let model_file = FileId(files.len() as u32);
        let (path, text) = robot.file.as_ref().map_or((args.robot.as_str(), ""), |f| {
            (f.path.as_str(), f.text.as_str())
        });
        files.push(RenderFile { path, text });
        let index = LineIndex::new(text);
        for w in &robot.warnings {
            let span = match w.line {
                Some(line) if (line as usize) <= index.line_count() && line > 0 => {
                    let start = index.line_start(line as usize - 1);
                    let end = text[start..].find('\n').map_or(text.len(), |e| start + e);
                    Span::new(start, end)
                }
                _ => Span::empty(0),
            };
            diagnostics.push(Diagnostic::new(
                Code::RobotModel,
                model_file,
                span,
                w.message.clone(),
            ));
        }
    }
    let errors = diagnostics.iter().any(Diagnostic::is_error);
    // Said on stderr in human output; a tool reading JSON finds them in the array.
    if args.format == Format::Json {
        for u in unread {
            let file = FileId(files.len() as u32);
            files.push(RenderFile {
                path: &u.path,
                text: &u.text,
            });
            diagnostics.push(Diagnostic::new(u.code, file, u.span, u.message.clone()));
        }
    }
    let output = match args.format {
        Format::Json => {
            let json = render::json(&diagnostics, &files);
            let mut s = serde_json::to_string_pretty(&json).expect("diagnostics serialize");
            s.push('\n');
            s
        }
        Format::Human => {
            let style = Style::on_terminal(std::io::stdout().is_terminal());
            let mut s = render::human(&diagnostics, &files, style);
            let count = |e: bool| diagnostics.iter().filter(|d| d.is_error() == e).count();
            // An unread file was not checked: said on stderr, and counted here.
            let checked = args.files.len() - unread.len();
            let unread = match unread.len() {
                0 => String::new(),
                n => format!("; {n} could not be read"),
            };
            s.push_str(&format!(
                "{checked} file(s) checked against robot `{}`: {} error(s), {} warning(s){unread}\n",
                robot.model.name,
                count(true),
                count(false)
            ));
            s
        }
    };
    Report {
        output,
        errors,
        unread: unread.iter().map(|u| u.message.clone()).collect(),
    }
}
