//! `calibrate [--replicas N] [--profile P] [--set ROBOT:PARAM=VALUE ...]`: runs Test 1
//! (Table 10) with the robots' error model, parameters of it set otherwise with
//! `--set` (`moro:actuator.steering_dead_time=0.2`), and prints each row beside the
//! dissertation's: the replicas' mean maximum and mean deviation, their 95 %
//! intervals, and how far each is from Table 10. The fit of `docs/experiments.md`
//! ("Calibration") is made with it.

use std::process::ExitCode;

use clap::Parser;
use ilmr_experiments::test1_turn::{Errors, REPLICAS, Robot, SPECS, Sweep, sweep_with};
use ilmr_sim::SimProfile;

#[derive(Parser)]
#[command(about = "Runs Test 1 with an error model and prints it beside Table 10")]
struct Args {
    /// How many times each row of Table 10 is run.
    #[arg(long, default_value_t = REPLICAS)]
    replicas: usize,
    /// ideal, basic or calibrated.
    #[arg(long, default_value = "calibrated")]
    profile: String,
    /// ROBOT:PARAM=VALUE, ROBOT moro or workpartner, PARAM a row of
    /// `ilmr_sim::profile::CALIBRATED`.
    #[arg(long)]
    set: Vec<String>,
    /// Print the calibrated model's predictions of Tables 11 and 12 and Test 5 instead.
    #[arg(long)]
    predictions: bool,
}

fn print_predictions() -> Result<(), String> {
    use ilmr_experiments::predictions as p;
    use ilmr_experiments::{test2_turn_left as t2, test5_short_task as t5};
    let line = |what: &str, s: &ilmr_experiments::stats::Spread, table: f64| {
        println!(
            "{what:<28} {:.4} [{:.4}, {:.4}] range {:.4}-{:.4}  dissertation {table}",
            s.mean, s.lo, s.hi, s.min, s.max
        )
    };
    let n = ilmr_experiments::seeds::FULL;
    let t = p::test2(n)?;
    line("Table 11 x", &t.x, t2::TABLE_11_X);
    line("Table 11 y", &t.y, t2::TABLE_11_Y);
    println!("Table 11 clean turns          {} of {}", t.clean, t.runs);
    for f in p::test3(n)? {
        line(
            &format!("Table 12 from {} m, excess", f.off),
            &f.overshoot,
            f.table,
        );
        println!(
            "{:<28} at the end {:.4}, contacts {}",
            "", f.at_end.mean, f.contacts
        );
    }
    let s = p::test5(n)?;
    line("Test 5 max error", &s.max_error, t5::FIGURE_53);
    line("Test 5 home", &s.home, t5::FIGURE_53);
    println!("Test 5 finished               {} of {}", s.finished, n);
    Ok(())
}

fn parse_set(s: &str) -> Result<(Robot, String, f64), String> {
    let bad = || format!("--set {s}: expected ROBOT:PARAM=VALUE");
    let (robot, rest) = s.split_once(':').ok_or_else(bad)?;
    let (param, value) = rest.split_once('=').ok_or_else(bad)?;
    let robot = match robot {
        "moro" => Robot::Moro,
        "workpartner" => Robot::Workpartner,
        _ => return Err(format!("--set {s}: no robot `{robot}`")),
    };
    let value: f64 = value.parse().map_err(|_| bad())?;
    Ok((robot, param.to_string(), value))
}

fn print(s: &Sweep) {
    let d = s.spec.dissertation;
    let (max, mean) = (s.max(), s.mean());
    println!(
        "{:<20} max  {:.4} [{:.4}, {:.4}] range {:.4}-{:.4}  table {:.4}  {:+.0} %",
        s.label(),
        max.mean,
        max.lo,
        max.hi,
        max.min,
        max.max,
        d.max,
        100.0 * max.relative_error(d.max)
    );
    println!(
        "{:<20} mean {:.4} [{:.4}, {:.4}] range {:.4}-{:.4}  table {:.4}  {:+.0} %",
        "",
        mean.mean,
        mean.lo,
        mean.hi,
        mean.min,
        mean.max,
        d.mean,
        100.0 * mean.relative_error(d.mean)
    );
    let speeds: Vec<String> = s
        .by_speed()
        .iter()
        .map(|(v, sp)| format!("{v}: {:.4}", sp.mean))
        .collect();
    println!("{:<20} by speed {}", "", speeds.join(", "));
}

fn main() -> ExitCode {
    let args = Args::parse();
    let run = || -> Result<(), String> {
        if args.predictions {
            return print_predictions();
        }
        let profile = SimProfile::parse(&args.profile)
            .ok_or_else(|| format!("--profile {}: ideal, basic or calibrated", args.profile))?;
        let overrides = args
            .set
            .iter()
            .map(|s| parse_set(s))
            .collect::<Result<Vec<_>, _>>()?;
        let errors = Errors { profile, overrides };
        let sweeps = std::thread::scope(|sc| {
            let handles: Vec<_> = SPECS
                .iter()
                .map(|spec| {
                    let errors = &errors;
                    sc.spawn(move || sweep_with(spec, args.replicas, errors))
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().map_err(|_| "a sweep panicked".to_string())?)
                .collect::<Result<Vec<_>, _>>()
        })?;
        for s in &sweeps {
            print(s);
        }
        Ok(())
    };
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("calibrate: {e}");
            ExitCode::from(2)
        }
    }
}
