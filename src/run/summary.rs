//! The summary printed when a run ends: how it ended, how long it took, what the
//! commands did, and for a simulated robot where it was and how far it went.

use ilmr_vm::runtime::safety::Code;
use ilmr_vm::runtime::trace::fmt_num;
use ilmr_vm::{Clock, Vm};

use super::RunArgs;
use super::backend::{AnyRobot, Robot};
use super::report::Report;
use super::session::Session;
use super::setup::{Backend, Setup};
use crate::{EXIT_HELD, EXIT_MAX_TIME, EXIT_TROUBLE};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// No command is left.
    Finished,
    /// Only waiting guards and endless readings are left, and the robot is at rest.
    Waiting,
    /// A supervisor hold lasted `--hold-limit`.
    Held,
    MaxTime,
    /// A replay ran out of recorded inputs before the task ended (its task changed).
    RecordingEnded,
}

/// How a run ended and what it met on the way.
pub struct Ended<'a> {
    pub outcome: Outcome,
    pub session: &'a Session,
    pub report: &'a Report,
}

impl Ended<'_> {
    /// 0 when the task ended by itself untroubled; see `docs/run.md`.
    pub fn exit_code(&self) -> u8 {
        let k = &self.session.tally;
        match self.outcome {
            Outcome::Held => EXIT_HELD,
            Outcome::MaxTime if !self.report.holds.is_empty() => EXIT_HELD,
            Outcome::MaxTime | Outcome::RecordingEnded => EXIT_MAX_TIME,
            Outcome::Finished | Outcome::Waiting if k.refused + k.errors > 0 => EXIT_TROUBLE,
            Outcome::Finished | Outcome::Waiting => 0,
        }
    }

    /// The summary's `how` line: how the run ended.
    pub fn how<C: Clock>(&self, vm: &Vm<AnyRobot, C>, args: &RunArgs) -> String {
        let a = vm.activity();
        let hold = self.report.longest_hold(vm.time()).map(|(h, held)| {
            format!(
                "{} {} since t={} ({} s): {}",
                Code::Fault(h.fault).code(),
                h.fault.name(),
                fmt_num(h.since),
                fmt_num(held),
                h.message
            )
        });
        match self.outcome {
            Outcome::Finished => "finished: no command left".to_string(),
            Outcome::Waiting if a.endless_readings > 0 => format!(
                "finished: only {} endless reading(s) and {} waiting guard(s) left, robot at rest",
                a.endless_readings, a.waiting_guards
            ),
            Outcome::Waiting => "finished: only waiting guards left, robot at rest".to_string(),
            Outcome::Held => format!(
                "held: gave up after --hold-limit {} s of a supervisor hold, {}",
                fmt_num(args.hold_limit),
                hold.unwrap_or_default()
            ),
            Outcome::MaxTime => {
                let live = match hold {
                    Some(hold) => format!("held, {hold}"),
                    None => format!("{} statement(s) live", vm.live_statements().len()),
                };
                format!("max-time: stopped at --max-time {}, {live}", args.max_time)
            }
            Outcome::RecordingEnded => format!(
                "recording ended: no recorded inputs after t={}, {} statement(s) live",
                fmt_num(vm.time()),
                vm.live_statements().len()
            ),
        }
    }
}

pub fn render<C: Clock>(
    ended: &Ended<'_>,
    vm: &Vm<AnyRobot, C>,
    args: &RunArgs,
    setup: &Setup,
) -> String {
    let t = fmt_num(vm.time());
    let how = ended.how(vm, args);
    let session = ended.session;
    let k = &session.tally;
    let mut s = format!("{}: {how}\n", args.task.display());
    let world = setup
        .world
        .as_ref()
        .filter(|_| matches!(setup.backend, Backend::Sim(_)));
    if let Some(w) = world {
        let p = w.world.start;
        let errors = match setup.profile {
            ilmr_sim::SimProfile::Basic => String::new(),
            other => format!(" ({other} errors)"),
        };
        s.push_str(&format!(
            "  robot           {}{errors} in {}, seed {}, from ({}, {}, {} deg)\n",
            setup.model_spec,
            w.name,
            args.seed,
            fmt_num(p.x),
            fmt_num(p.y),
            fmt_num(p.h.to_degrees())
        ));
    }
    let ros2 = setup
        .ros2
        .as_ref()
        .filter(|_| setup.backend == Backend::Ros2);
    if let Some(r) = ros2 {
        s.push_str(&format!(
            "  robot           ROS 2 in namespace {}, DDS domain {}, model {}\n",
            r.namespace, r.domain_id, setup.model_spec
        ));
        s.push_str(&format!("  time            {t} s ({} ticks)\n", vm.ticks()));
    } else {
        s.push_str(&format!("  simulated time  {t} s ({} ticks)\n", vm.ticks()));
    }
    if world.is_some() || ros2.is_some() {
        let at = session
            .last_pose()
            .map(|p| {
                format!(
                    ", ended at ({}, {}, {} deg)",
                    fmt_num(p.x),
                    fmt_num(p.y),
                    fmt_num(p.h.to_degrees())
                )
            })
            .unwrap_or_default();
        s.push_str(&format!(
            "  distance        {} m{at}\n",
            fmt_num((session.distance * 100.0).round() / 100.0)
        ));
    }
    s.push_str(&format!(
        "  commands ended  {} completed, {} broken, {} refused\n  guards waiting  {}\n  overruns        {}\n  runtime errors  {}\n",
        k.completed,
        k.broken,
        k.refused,
        vm.activity().waiting_guards,
        k.overruns,
        k.errors,
    ));
    s.push_str(&format!("  holds           {}\n", ended.report.holds_begun));
    if !ended.report.first.is_empty() {
        s.push_str("  first notices\n");
        for n in &ended.report.first {
            s.push_str(&format!("    {n}\n"));
        }
    }
    if world.is_some() {
        s.push_str(&format!("  contacts        {}\n", vm.hal().contacts()));
    }
    if let (Some(_), Some(m)) = (ros2, vm.hal().scanner_mount()) {
        s.push_str(&format!(
            "  scanner         at ({}, {}) m on the robot, by tf\n",
            fmt_num(m.x),
            fmt_num(m.y)
        ));
    }
    if let Some(l) = vm.hal().link_stats() {
        s.push_str(&format!(
            "  ros 2 link      {} cmd_vel sent; odom {} taken, {} dropped ({} not numbers); scan {} taken, {} dropped; battery {} taken; at most {} of a topic in a tick; held {} times for a stale stream\n",
            l.twists_sent,
            l.odometry.0,
            l.odometry.1,
            l.odometry_unusable,
            l.scans.0,
            l.scans.1,
            l.battery.0,
            l.most_in_one_tick,
            l.stale_holds
        ));
        if l.foreign_commands > 0 {
            s.push_str(&format!(
                "  other drivers   {} cmd_vel samples from {} other writer(s); yielded the robot {} times\n",
                l.foreign_commands, l.foreign_writers, l.yields
            ));
        }
    }
    if k.lines_accepted + k.lines_rejected > 0 {
        s.push_str(&format!(
            "  lines           {} joined, {} rejected\n",
            k.lines_accepted, k.lines_rejected
        ));
    }
    s.push_str(&format!("  exit            {}\n", ended.exit_code()));
    s
}
