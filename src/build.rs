//! `ilmrc build` and `ilmrc disasm`: a checked task to an `.ilmb` module, and a module
//! back to a readable listing. [`compile`] also takes a built module where a task is
//! expected, so `run`, `serve --task` and `shell --task` run `.ilmb` files.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use ilmr_compiler::check::{Analysis, Detail, Given, Source, analyze_given};
use ilmr_compiler::render::{self, RenderFile, Style};
use ilmr_compiler::{Diagnostic, FileId};
use ilmr_vm::Module;

use crate::check::{CheckArgs, Format};
use crate::inputs;
use crate::run::console::Console;

#[derive(clap::Args)]
pub struct BuildArgs {
    /// Robot model: `moro`, `workpartner`, or a path to a ROBO.INI file.
    #[arg(long, default_value = "moro")]
    pub robot: String,
    /// A skill file, or a directory of skill files (`*.ilms`), the task may call.
    #[arg(long)]
    pub skills: Option<PathBuf>,
    /// Where to write the module.
    #[arg(short, long)]
    pub output: PathBuf,
    /// The task file.
    pub task: PathBuf,
}

#[derive(clap::Args)]
pub struct DisasmArgs {
    /// `text`: the listing, one instruction a line with its source; `json`: the
    /// module's tables.
    #[arg(long, value_enum, default_value_t = ListingFormat::Text)]
    pub format: ListingFormat,
    /// An `.ilmb` module written by `ilmrc build`.
    pub file: PathBuf,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ListingFormat {
    Text,
    Json,
}

/// What `check` and the lowering made of a task.
pub enum Compiled {
    Module(Box<Module>),
    /// Diagnostics were printed; the task has errors.
    Rejected,
}

/// Checks the task exactly as `ilmrc check` does (printing what it prints when there is
/// anything to say), then lowers it. `extra` adds problems found in the lowered module
/// (`--robot none`); they are rendered in the same way. A built module (a file that
/// starts with the `.ilmb` magic) is loaded and validated instead.
pub fn compile(
    task: &Path,
    robot: &str,
    skills: Option<&Path>,
    extra: impl Fn(&Module) -> Vec<Diagnostic>,
) -> Result<Compiled, String> {
    let console = &mut Console::Terminal;
    compile_leaving(
        task,
        robot,
        skills,
        &Given::default(),
        console,
        extra,
        false,
    )
}

/// [`compile`], telling the check what the run is given from outside the program (a
/// scenario's taught paths); what the check says goes to `console`.
pub fn compile_given(
    task: &Path,
    robot: &str,
    skills: Option<&Path>,
    given: &Given,
    console: &mut Console,
    extra: impl Fn(&Module) -> Vec<Diagnostic>,
) -> Result<Compiled, String> {
    compile_leaving(task, robot, skills, given, console, extra, false)
}

/// [`compile`]; with `leave`, the analysis is left to the operating system instead of
/// freed (freeing a large one costs a tenth of making it, and `build` ends right after).
fn compile_leaving(
    task: &Path,
    robot: &str,
    skills: Option<&Path>,
    given: &Given,
    console: &mut Console,
    extra: impl Fn(&Module) -> Vec<Diagnostic>,
    leave: bool,
) -> Result<Compiled, String> {
    if is_module(task) {
        return load_module(task, skills, extra);
    }
    let args = CheckArgs {
        robot: robot.to_string(),
        skills: skills.map(Path::to_path_buf),
        format: Format::Human,
        files: vec![task.to_path_buf()],
    };
    let loaded = inputs::load_robot(robot)?;
    let mut sources: Vec<Source> = vec![inputs::read_source(task)?];
    if let Some(dir) = skills {
        sources.extend(inputs::read_skill_dir(dir)?);
    }
    // One analysis, the full one the lowering reads; what `check` reports of it is what
    // `check` reports of its own lighter one (`compiler/tests/detail.rs`).
    let analysis = analyze_given(&sources, &loaded.model, Detail::Full, given);
    let report = crate::check::report(&args, &loaded, &analysis);
    inputs::warn_about(robot, &loaded.warnings);
    let model = &loaded.model;
    let quiet = analysis.diagnostics.is_empty() && !report.errors;
    if !quiet {
        console.out(&report.output);
    }
    if report.errors {
        return Ok(Compiled::Rejected);
    }
    let problems = match ilmr_compiler::lower::lower(&analysis, model, FileId(0)) {
        Ok(module) => {
            let problems = extra(&module);
            if problems.is_empty() {
                if leave {
                    std::mem::forget(analysis);
                    std::mem::forget(sources);
                }
                return Ok(Compiled::Module(Box::new(module)));
            }
            problems
        }
        Err(problems) => problems,
    };
    console.out(&render_diagnostics(&analysis, &problems));
    Ok(Compiled::Rejected)
}

/// Whether the file starts as an `.ilmb` does (no task text can: its first byte is not
/// UTF-8 on its own). Only a regular file is opened: opening a FIFO would wait for a
/// writer, and whatever is not a regular file is refused by the read that follows.
fn is_module(path: &Path) -> bool {
    use std::io::Read;
    if !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return false;
    }
    let mut head = [0u8; 8];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok_and(|()| head == ilmr_vm::bytecode::file::MAGIC)
}

/// A module `ilmrc build` wrote, read within `MAX_MODULE_BYTES` and validated. Its
/// problems (`extra`) point at statements whose source is not at hand: each is said
/// with its file, line and statement text.
fn load_module(
    path: &Path,
    skills: Option<&Path>,
    extra: impl Fn(&Module) -> Vec<Diagnostic>,
) -> Result<Compiled, String> {
    let module = read_module(path)?;
    if skills.is_some() {
        eprintln!(
            "warning: --skills is ignored for `{}`: a built module holds the skills its task calls",
            path.display()
        );
    }
    let problems = extra(&module);
    if problems.is_empty() {
        return Ok(Compiled::Module(Box::new(module)));
    }
    let statements: std::collections::HashMap<(u32, (u32, u32)), &ilmr_vm::bytecode::Stmt> = module
        .stmts
        .iter()
        .map(|s| ((s.file.0, s.span), s))
        .collect();
    for d in &problems {
        let file = module
            .files
            .get(d.file.0 as usize)
            .map_or("?", String::as_str);
        let at = statements.get(&(d.file.0, (d.span.start, d.span.end)));
        let (line, text) = at.map_or((0, ""), |s| (s.line, s.text.as_str()));
        println!(
            "error[{}]: {}\n  --> {file}:{line}: {text}",
            d.code.as_str(),
            d.message
        );
        if let Some(help) = &d.help {
            println!("  = help: {help}");
        }
    }
    Ok(Compiled::Rejected)
}

/// Reads and validates an `.ilmb` file; the error says which file and what is wrong.
fn read_module(path: &Path) -> Result<Module, String> {
    let bytes = ilmr_files::read(path, ilmr_files::Kind::Module)
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    Module::from_bytes(&bytes)
        .map_err(|e| format!("`{}` is not a valid ILMR module: {e}", path.display()))
}

/// Diagnostics as `ilmrc check` shows them (colour only on a terminal).
pub fn render_diagnostics(analysis: &Analysis<'_>, diagnostics: &[Diagnostic]) -> String {
    use std::io::IsTerminal;
    let files: Vec<RenderFile<'_>> = analysis
        .files
        .iter()
        .map(|f| RenderFile {
            path: f.path,
            text: f.text,
        })
        .collect();
    let style = Style::on_terminal(std::io::stdout().is_terminal());
    render::human(diagnostics, &files, style)
}

pub fn build(args: BuildArgs) -> ExitCode {
    let compiled = compile_leaving(
        &args.task,
        &args.robot,
        args.skills.as_deref(),
        &Given::default(),
        &mut Console::Terminal,
        |_| Vec::new(),
        true,
    );
    match compiled {
        Ok(Compiled::Module(module)) => {
            let written = std::fs::File::create(&args.output).and_then(|f| {
                let mut out = std::io::BufWriter::new(f);
                let len = ilmr_vm::bytecode::file::write(&module, &mut out)?;
                std::io::Write::flush(&mut out)?;
                Ok(len)
            });
            let bytes = match written {
                Ok(len) => len,
                Err(e) => {
                    eprintln!("error: cannot write `{}`: {e}", args.output.display());
                    return ExitCode::from(crate::EXIT_USAGE);
                }
            };
            println!(
                "built {}: {} statement(s), {} instruction(s), {} skill(s), {} byte(s)",
                args.output.display(),
                module.stmts.len(),
                module.code.len(),
                module.units.iter().filter(|u| u.skill).count(),
                bytes
            );
            // As the analysis: the process ends now.
            std::mem::forget(module);
            ExitCode::SUCCESS
        }
        Ok(Compiled::Rejected) => ExitCode::from(crate::EXIT_ERRORS),
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

pub fn disasm(args: DisasmArgs) -> ExitCode {
    let module = match read_module(&args.file) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(crate::EXIT_USAGE);
        }
    };
    let text = match args.format {
        ListingFormat::Text => listing(&module),
        ListingFormat::Json => match serde_json::to_string_pretty(&module) {
            Ok(json) => json + "\n",
            Err(e) => {
                eprintln!("error: cannot write the module as JSON: {e}");
                return ExitCode::from(crate::EXIT_USAGE);
            }
        },
    };
    // A reader that stops early (`| head`) is not an error of the listing.
    let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), text.as_bytes());
    ExitCode::SUCCESS
}

/// The source files, then the VM's listing (one instruction per line with its source
/// line and statement text).
pub fn listing(module: &Module) -> String {
    let mut out = String::new();
    for (i, f) in module.files.iter().enumerate() {
        out.push_str(&format!("file {i:>3} {f}\n"));
    }
    out.push_str(&ilmr_vm::bytecode::disassemble(module));
    out
}
