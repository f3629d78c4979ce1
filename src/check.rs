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
    /// A directory of skill files (`*.ilms`) the tasks may call.
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
            ExitCode::from(if report.errors { crate::EXIT_ERRORS } else { 0 })
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
}

pub fn check(args: &CheckArgs) -> Result<Report, String> {
    let robot = inputs::load_robot(&args.robot)?;
    let mut sources: Vec<Source> = args
        .files
        .iter()
        .map(|p| inputs::read_source(p))
        .collect::<Result<_, _>>()?;
    if let Some(dir) = &args.skills {
        sources.extend(inputs::read_skill_dir(dir)?);
    }
    let analysis = analyze_with(&sources, &robot.model, Detail::Diagnostics);
    let report = report(args, &robot, &analysis);
    // Freeing a large program's trees and tables costs a tenth of checking it, and the
    // process ends right after: let the operating system reclaim them.
    std::mem::forget(analysis);
    std::mem::forget(sources);
    Ok(report)
}

/// What `check` says about an analysis of `args.files` (with the robot model's own
/// warnings): `build` and `run` print the same of the analysis they lower.
pub fn report(args: &CheckArgs, robot: &inputs::Robot, analysis: &Analysis<'_>) -> Report {
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
    let output = match args.format {
        Format::Json => {
            let json = render::json(&diagnostics, &files);
            let mut s = serde_json::to_string_pretty(&json).expect("diagnostics serialize");
            s.push('\n');
            s
        }
        Format::Human => {
            let terminal = std::io::stdout().is_terminal();
            let style = Style {
                color: terminal && std::env::var_os("NO_COLOR").is_none(),
                unicode: terminal,
            };
            let mut s = render::human(&diagnostics, &files, style);
            let count = |e: bool| diagnostics.iter().filter(|d| d.is_error() == e).count();
            let checked = args.files.len();
            s.push_str(&format!(
                "{checked} file(s) checked against robot `{}`: {} error(s), {} warning(s)\n",
                robot.model.name,
                count(true),
                count(false)
            ));
            s
        }
    };
    Report { output, errors }
}
