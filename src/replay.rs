//! `ilmrc replay TRACE.jsonl --plot OUT.svg`: draws a finished run again from the trace
//! `ilmrc run --trace` wrote, without running anything. The figure is the one `run
//! --plot` draws from the same trace, byte for byte.

use std::path::PathBuf;
use std::process::ExitCode;

use ilmr_plot::{self as plot, RunRecord};

#[derive(clap::Args)]
pub struct ReplayArgs {
    /// A trace written by `ilmrc run --trace`.
    pub trace: PathBuf,
    /// Where to draw the run (SVG).
    #[arg(long)]
    pub plot: PathBuf,
}

pub fn run(args: ReplayArgs) -> ExitCode {
    match replay(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

fn replay(args: &ReplayArgs) -> Result<(), String> {
    let text = ilmr_files::read_text(&args.trace, ilmr_files::Kind::Trace)
        .map_err(|e| format!("cannot read trace `{}`: {e}", args.trace.display()))?;
    let record = RunRecord::from_jsonl(&text).map_err(|e| {
        format!(
            "`{}` is not a trace of ilmrc run: {e}",
            args.trace.display()
        )
    })?;
    if record.poses.is_empty() {
        return Err(format!(
            "`{}` has no pose samples to draw (a run with --robot none has none)",
            args.trace.display()
        ));
    }
    plot::write_svg(&record, &args.plot)?;
    println!("{}: drew {}", args.trace.display(), args.plot.display());
    Ok(())
}
