//! `ilmrc fmt`.

use std::path::PathBuf;
use std::process::ExitCode;

use ilmr_compiler::render::{self, RenderFile, Style};

use crate::inputs;

#[derive(clap::Args)]
pub struct FmtArgs {
    /// Report files that are not in canonical form instead of rewriting them.
    #[arg(long)]
    pub check: bool,
    /// Robot model, to tell its object and sensor names from variables of the same spelling.
    #[arg(long, default_value = "moro")]
    pub robot: String,
    /// Task and skill files.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

pub fn run(args: FmtArgs) -> ExitCode {
    let robot = match inputs::load_robot(&args.robot) {
        Ok(r) => r,
        Err(message) => {
            eprintln!("error: {message}");
            return ExitCode::from(crate::EXIT_USAGE);
        }
    };
    let mut failed = false;
    for path in &args.files {
        let source = match inputs::read_source(path) {
            Ok(s) => s,
            Err(message) => {
                eprintln!("error: {message}");
                return ExitCode::from(crate::EXIT_USAGE);
            }
        };
        match ilmr_compiler::format::format(&source.text, &robot.model) {
            Ok(formatted) if formatted == source.text => {}
            Ok(_) if args.check => {
                println!("would reformat {}", path.display());
                failed = true;
            }
            Ok(formatted) => {
                if let Err(e) = std::fs::write(path, formatted) {
                    eprintln!("error: cannot write `{}`: {e}", path.display());
                    return ExitCode::from(crate::EXIT_USAGE);
                }
            }
            Err(diagnostics) => {
                let files = [RenderFile {
                    path: &source.path,
                    text: &source.text,
                }];
                print!("{}", render::human(&diagnostics, &files, Style::PLAIN));
                println!("{} not formatted: it does not parse", path.display());
                failed = true;
            }
        }
    }
    ExitCode::from(if failed { crate::EXIT_ERRORS } else { 0 })
}
