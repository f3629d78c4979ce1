//! `experiments [--out DIR]`: runs the dissertation's tests 1-7 and Figure 20, writes
//! `DIR/experiments.md` and `DIR/experiments/*.svg` (DIR: the repository's `docs/`
//! unless given), and prints what each run cost: simulated seconds, the CPU seconds of
//! its thread, and their ratio (only here: the report is the same on every machine).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
use ilmr_experiments::Costed;

#[derive(Parser)]
#[command(
    about = "Runs the dissertation's tests 1-7 and Figure 20, writes experiments.md and a picture of each, and prints what each run cost"
)]
struct Args {
    /// Where experiments.md and experiments/*.svg go (default: the repository's docs/).
    #[arg(long)]
    out: Option<PathBuf>,
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("cannot write `{}`: {e}", path.display()))
}

/// One line per run: simulated seconds, CPU seconds, simulated per CPU second.
fn print_costs(costs: &[Costed]) {
    let width = costs.iter().map(|c| c.name.len()).max().unwrap_or(0);
    println!(
        "{:width$}  {:>11}  {:>8}  {:>12}",
        "run", "simulated s", "CPU s", "x real time"
    );
    for Costed { name, cost } in costs {
        let cpu = cost
            .cpu
            .map_or("-".to_string(), |c| format!("{:.3}", c.as_secs_f64()));
        let factor = cost
            .real_time_factor()
            .map_or("-".to_string(), |r| format!("{r:.0}"));
        println!(
            "{name:width$}  {:>11.2}  {cpu:>8}  {factor:>12}",
            cost.simulated
        );
    }
}

fn report(out: &Path) -> Result<(), String> {
    let (results, costs) = ilmr_experiments::run_all_costed(ilmr_experiments::seeds::FULL)?;
    print_costs(&costs);
    let doc = out.join("experiments.md");
    let existing = match std::fs::read_to_string(&doc) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
        Err(e) => return Err(format!("cannot read `{}`: {e}", doc.display())),
    };
    let pictures = out.join("experiments");
    std::fs::create_dir_all(&pictures)
        .map_err(|e| format!("cannot create `{}`: {e}", pictures.display()))?;
    for (name, figure) in results.figures() {
        let path = pictures.join(name);
        write(&path, &figure.to_svg()?)?;
        println!("wrote {}", path.display());
    }
    write(&doc, &ilmr_experiments::doc::render(&results, &existing))?;
    println!("wrote {}", doc.display());
    Ok(())
}

fn main() -> ExitCode {
    let args = Args::parse();
    let out = args
        .out
        .unwrap_or_else(|| ilmr_experiments::harness::repo().join("docs"));
    match report(&out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("experiments: {e}");
            ExitCode::FAILURE
        }
    }
}
