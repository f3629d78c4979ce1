//! The summary printed when a run ends: how it ended, how long it took, what the
//! commands did, and for a simulated robot where it was and how far it went.

use ilmr_vm::runtime::trace::fmt_num;
use ilmr_vm::{Clock, Vm};

use super::RunArgs;
use super::backend::{AnyRobot, Robot};
use super::session::Session;
use super::setup::{Backend, Setup};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// No command is left.
    Finished,
    /// Only waiting guards are left, and the robot is at rest.
    Waiting,
    MaxTime,
}

pub fn render<C: Clock>(
    session: &Session,
    vm: &Vm<AnyRobot, C>,
    outcome: Outcome,
    args: &RunArgs,
    setup: &Setup,
) -> String {
    let t = fmt_num(vm.time());
    let how = match outcome {
        Outcome::Finished => "finished: no command left".to_string(),
        Outcome::Waiting => "finished: only waiting guards left, robot at rest".to_string(),
        Outcome::MaxTime => format!("max-time: stopped at --max-time {}", args.max_time),
    };
    let k = &session.tally;
    let mut s = format!("{}: {how}\n", args.task.display());
    let world = setup
        .world
        .as_ref()
        .filter(|_| matches!(setup.backend, Backend::Sim(_)));
    if let Some(w) = world {
        let p = w.world.start;
        s.push_str(&format!(
            "  robot           {} in {}, seed {}, from ({}, {}, {} deg)\n",
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
    }
    if k.lines_accepted + k.lines_rejected > 0 {
        s.push_str(&format!(
            "  lines           {} joined, {} rejected\n",
            k.lines_accepted, k.lines_rejected
        ));
    }
    s
}
