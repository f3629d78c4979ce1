//! Issue 7's proof, one test per injected fault: the VM drives the simulated
//! robot through the fault, and each test asserts the supervisor's documented
//! reaction (`docs/reliability.md`), that the robot never touches a wall or an
//! obstacle, and that the speed setpoint never changes faster than the model's
//! acceleration and deceleration allow.

mod experiment;

use experiment::{compile, moro, workpartner};
use ilmr_hal::{Hal, OpId, OpStatus, Recorded};
use ilmr_sim::faults::flag;
use ilmr_sim::{SimRobot, World};
use ilmr_vm::runtime::safety::Safety;
use ilmr_vm::{Config, SimClock, Vm};

/// The simulated robot with every speed setpoint the VM sent recorded, failed
/// calls included: the VM's setpoint is what must not jump.
type Recorder = Recorded<SimRobot>;

type FaultVm = Vm<Recorder, SimClock>;

/// What a run left behind.
struct Ran {
    vm: FaultVm,
    trace: String,
    finished: bool,
    /// (time, true x) after every tick.
    xs: Vec<(f64, f64)>,
}

fn world_with(file: &str, faults: &[&str]) -> World {
    let mut w = experiment::world(file);
    add(&mut w, faults);
    w
}

fn add(w: &mut World, faults: &[&str]) {
    for f in faults {
        w.faults
            .push(flag::parse(f).unwrap_or_else(|e| panic!("{f}: {e}")));
    }
}

fn empty(faults: &[&str]) -> World {
    let mut w = experiment::shipped("empty");
    add(&mut w, faults);
    w
}

/// Runs `task` for at most `seconds`, with the model's safety thresholds
/// (changed by `tweak`), and checks the two guarantees every fault keeps.
fn drive(robot: SimRobot, task: &str, seconds: f64, tweak: impl FnOnce(&mut Config)) -> Ran {
    let model = robot.model().clone();
    let module = compile("fault.ilmr", task, &model);
    let mut cfg = experiment::vm_config(&model, robot.sim().config());
    cfg.safety = Safety::from_model(&model);
    tweak(&mut cfg);
    let hal = Recorded::new(robot);
    let mut vm = Vm::new(module, hal, SimClock, cfg).expect("valid module");
    let ticks = (seconds / vm.config().period).round() as u64;
    let mut xs = Vec::new();
    for _ in 0..ticks {
        if vm.finished() {
            break;
        }
        vm.tick();
        let sim = vm.hal().inner.sim();
        xs.push((sim.time(), sim.true_pose().x));
        assert!(
            sim.contact_count() == 0,
            "the robot touched something at t = {:.2} s, true pose {:?}",
            sim.time(),
            sim.true_pose()
        );
    }
    assert_setpoints_ramp(&vm);
    let trace = ilmr_vm::to_jsonl(vm.module(), vm.events());
    let finished = vm.finished();
    Ran {
        vm,
        trace,
        finished,
        xs,
    }
}

/// The true x at time `t`.
fn pose_at(r: &Ran, t: f64) -> f64 {
    r.xs.iter()
        .find(|(at, _)| *at >= t - 1e-9)
        .map_or_else(|| true_x(r), |(_, x)| *x)
}

/// Tick to tick, the speed setpoint rises by at most the acceleration and
/// falls by at most the deceleration, times the tick.
fn assert_setpoints_ramp(vm: &FaultVm) {
    let cfg = vm.config();
    if let Some(jump) = vm
        .hal()
        .first_jump(cfg.period, cfg.acceleration, cfg.deceleration)
    {
        panic!("{jump}");
    }
}

/// Times of the trace lines of `event` for `fault`.
fn times(trace: &str, event: &str, fault: &str) -> Vec<f64> {
    let ev = format!("\"event\":\"{event}\"");
    let name = format!("\"fault\":\"{fault}\"");
    trace
        .lines()
        .filter(|l| l.contains(&ev) && l.contains(&name))
        .map(|l| {
            l.strip_prefix("{\"t\":")
                .and_then(|r| r.split(',').next())
                .and_then(|n| n.parse().ok())
                .unwrap_or_else(|| panic!("no time in {l}"))
        })
        .collect()
}

fn one(trace: &str, event: &str, fault: &str) -> f64 {
    let t = times(trace, event, fault);
    assert!(t.len() == 1, "{event} {fault}: {t:?}\n{trace}");
    t[0]
}

fn ended_with(trace: &str, text: &str, how: &str, code: &str) -> bool {
    trace.lines().any(|l| {
        l.contains("\"event\":\"end\"")
            && l.contains(&format!("\"text\":\"{text}\""))
            && l.contains(&format!("\"how\":\"{how}\""))
            && l.contains(&format!("\"code\":\"{code}\""))
    })
}

fn true_x(r: &Ran) -> f64 {
    r.vm.hal().inner.sim().true_pose().x
}

const GO: &str = "speed(0.4)\ngoahead(8)\n";

#[test]
fn scanner_dropout_holds_the_robot_until_scans_return() {
    // MoRo scans at 4 Hz; scanner_timeout 1.0 s. The last scan before the
    // dropout is at 1.75 s, so the fault is raised once it is 1 s old.
    let robot = moro(world_with("corridor.toml", &["scanner_dropout@2+3"]), 1);
    let r = drive(robot, GO, 40.0, |_| {});
    let raised = one(&r.trace, "fault", "scanner_lost");
    assert!((2.75..2.8).contains(&raised), "raised at {raised}");
    assert!(r.trace.contains("\"reaction\":\"hold\""));
    let back = one(&r.trace, "recovered", "scanner_lost");
    assert!((5.0..5.05).contains(&back), "recovered at {back}");
    // Held: standing while the scanner was silent (after the braking ramp).
    let sim_speeds_held = r.finished && ended_with_completed(&r.trace, "goahead(8)");
    assert!(
        sim_speeds_held,
        "the movement went on after the hold\n{}",
        r.trace
    );
    assert!((true_x(&r) - 10.0).abs() < 0.3, "x {}", true_x(&r));
}

fn ended_with_completed(trace: &str, text: &str) -> bool {
    trace.lines().any(|l| {
        l.contains("\"event\":\"end\"")
            && l.contains(&format!("\"text\":\"{text}\""))
            && l.contains("\"how\":\"completed\"")
    })
}

#[test]
fn odometry_slip_makes_the_robot_fall_short_but_never_collide() {
    let robot = moro(world_with("corridor.toml", &["odometry_slip@1:0.3"]), 2);
    let r = drive(robot, GO, 40.0, |_| {});
    assert!(r.finished && ended_with_completed(&r.trace, "goahead(8)"));
    // The counters saw 8 m; the ground moved about 70 % of that after 1 s.
    let travelled = true_x(&r) - 2.0;
    assert!((5.5..7.0).contains(&travelled), "travelled {travelled}");
    assert!(!r.trace.contains("\"event\":\"fault\""), "{}", r.trace);
}

#[test]
fn odometry_bias_that_overshoots_is_stopped_by_the_wall_check() {
    // Counters reading 25 % short: goahead(12) would drive 16 m, into the end
    // wall at x = 16. The supervisor's obstacle check (obsavoid is off) holds
    // the robot short of it.
    let robot = moro(world_with("corridor.toml", &["odometry_bias@0:-0.25"]), 3);
    let r = drive(robot, "speed(0.4)\ngoahead(12)\n", 60.0, |_| {});
    let raised = one(&r.trace, "fault", "obstacle_near");
    assert!(raised > 20.0, "raised at {raised}");
    assert!(
        !r.finished,
        "held before the wall, the goahead never arrives"
    );
    let gap = 15.925 - (true_x(&r) + r.vm.config().front_offset);
    assert!(
        (0.05..0.6).contains(&gap),
        "stood {gap:.3} m short of the wall"
    );
}

#[test]
fn odometry_dropout_locks_movement_out() {
    // MoRo's odometry_timeout is 0.25 s; the last sample is at 1.99 s.
    let robot = moro(world_with("corridor.toml", &["odometry_dropout@2+2"]), 4);
    // The second goahead is issued after the fault has cleared: a new
    // command drives again.
    let task = "speed(0.4)\ngoahead(8)\nwait(5)\ngoahead(1)\n";
    let r = drive(robot, task, 20.0, |_| {});
    let raised = one(&r.trace, "fault", "odometry_lost");
    assert!((2.24..2.26).contains(&raised), "raised at {raised}");
    assert!(r.trace.contains("\"reaction\":\"lockout\""));
    assert!(
        ended_with(&r.trace, "goahead(8)", "refused", "R0203"),
        "{}",
        r.trace
    );
    let back = one(&r.trace, "recovered", "odometry_lost");
    assert!((4.0..4.05).contains(&back), "recovered at {back}");
    assert!(r.finished && ended_with_completed(&r.trace, "goahead(1)"));
    let at_lockout = pose_at(&r, raised);
    assert!(
        (true_x(&r) - at_lockout - 1.0).abs() < 0.3,
        "after the lockout it drove {} m",
        true_x(&r) - at_lockout
    );
}

#[test]
fn a_frozen_navigation_fix_slows_workpartner_down() {
    // Workpartner: fixes at 2 Hz, nav_timeout 1.5 s, degraded_speed 0.1 m/s.
    let robot = workpartner(empty(&["nav_frozen@2+6"]), 5);
    let r = drive(robot, "speed(0.5)\ngoahead(10)\n", 60.0, |_| {});
    let raised = one(&r.trace, "fault", "nav_lost");
    // The last fix before the freeze is at 1.5 s.
    assert!((3.0..3.05).contains(&raised), "raised at {raised}");
    assert!(
        r.trace.contains("\"reaction\":\"slow_down\""),
        "{}",
        r.trace
    );
    let back = one(&r.trace, "recovered", "nav_lost");
    assert!((8.0..8.05).contains(&back), "recovered at {back}");
    // Between the braking and the recovery the setpoint stays within 0.1 m/s.
    let decel = r.vm.config().deceleration;
    let settled = raised + 0.5 / decel + 0.05;
    let over: Vec<_> =
        r.vm.hal()
            .setpoints()
            .iter()
            .filter(|(t, v)| *t > settled && *t < back && v.abs() > 0.1 + 1e-9)
            .collect();
    assert!(over.is_empty(), "too fast while degraded: {over:?}");
    assert!(r.finished && ended_with_completed(&r.trace, "goahead(10)"));
}

#[test]
fn a_dead_battery_raises_battery_low_and_the_robot_rolls_to_rest() {
    // MoRo reads 21 V empty, below LowBattery 23 V.
    let robot = moro(world_with("corridor.toml", &["dead_battery@2"]), 6);
    let task = "B = sensor(battery)\nspeed(0.4)\ngoahead(8)\n";
    let r = drive(robot, task, 15.0, |_| {});
    let raised = one(&r.trace, "fault", "battery_low");
    assert!((2.0..2.05).contains(&raised), "raised at {raised}");
    assert!(r.trace.contains("\"reaction\":\"raise\""), "{}", r.trace);
    let sim = r.vm.hal().inner.sim();
    assert!(sim.true_speed() == 0.0);
    // It rolled to rest within MoRo's deceleration from 0.4 m/s.
    assert!(true_x(&r) < 2.0 + 0.4 * 2.0 + 0.4 * 0.4 / 2.0 / sim.config().limits.max_decel + 0.01);
}

#[test]
fn a_silent_drive_is_reported_and_the_task_goes_on() {
    let robot = moro(world_with("corridor.toml", &["actuator_dead@2+1.5"]), 7);
    let r = drive(robot, GO, 40.0, |_| {});
    let errors: Vec<&str> = r
        .trace
        .lines()
        .filter(|l| l.contains("\"event\":\"error\"") && l.contains("does not answer"))
        .collect();
    // One failed set_motion per tick for the fault's 1.5 s.
    assert!(
        (140..=160).contains(&errors.len()),
        "{} errors",
        errors.len()
    );
    assert!(r.finished && ended_with_completed(&r.trace, "goahead(8)"));
    assert!((true_x(&r) - 10.0).abs() < 0.3, "x {}", true_x(&r));
}

#[test]
fn a_silent_manipulator_is_given_up_after_the_operation_timeout() {
    let robot = workpartner(empty(&["manipulator_silent"]), 8);
    let r = drive(robot, "T = manipulate(take)\nwait(T)\n", 30.0, |c| {
        c.safety.operation_timeout = Some(10.0);
    });
    let raised = one(&r.trace, "fault", "operation_timeout");
    assert!((10.0..10.05).contains(&raised), "raised at {raised}");
    assert!(
        ended_with(&r.trace, "T = manipulate(take)", "refused", "R0207"),
        "{}",
        r.trace
    );
    // The robot side was told: the operation is cancelled, not left pending.
    let mut robot = r.vm.hal().inner.clone();
    assert!(matches!(robot.poll(OpId(1)), Ok(OpStatus::Failed(_))));
    assert!(r.finished);
}

#[test]
fn an_obstacle_appearing_ahead_holds_the_robot_short_of_it() {
    // At 4 s MoRo is driving 0.4 m/s; a 0.25 m post appears 1.5 m ahead of
    // its front and stays.
    let robot = moro(world_with("corridor.toml", &["obstacle_appears@4:1.5"]), 9);
    let r = drive(robot, GO, 15.0, |_| {});
    // Raised when the post comes inside the braking distance plus
    // stop_margin, about 2.9 s later at 0.4 m/s.
    let raised = one(&r.trace, "fault", "obstacle_near");
    assert!((6.5..7.5).contains(&raised), "raised at {raised}");
    assert!(r.trace.contains("\"reaction\":\"hold\""));
    assert!(!r.finished, "held: the goahead does not arrive");
    assert!(r.vm.hal().inner.sim().true_speed() == 0.0);
    let front = true_x(&r) + r.vm.config().front_offset;
    let obstacle =
        r.vm.hal()
            .inner
            .sim()
            .scene()
            .solids()
            .iter()
            .find(|s| s.what == ilmr_sim::geometry::SolidRef::Fault(0))
            .map(|s| s.shape.center().x - 0.25)
            .expect("the post is in the scene");
    let gap = obstacle - front;
    assert!(
        (0.1..0.5).contains(&gap),
        "held {gap:.3} m short of the post"
    );
}

#[test]
fn an_obstacle_that_goes_away_releases_the_robot() {
    // The same post, gone after 5 s: new scans see through where it stood, the
    // VM forgets it, and the goahead drives on to its end.
    let robot = moro(
        world_with("corridor.toml", &["obstacle_appears@4+5:1.5"]),
        9,
    );
    let r = drive(robot, GO, 40.0, |_| {});
    let raised = one(&r.trace, "fault", "obstacle_near");
    let back = one(&r.trace, "recovered", "obstacle_near");
    assert!(
        (9.0..10.5).contains(&back),
        "raised {raised}, recovered {back}"
    );
    assert!(r.finished, "the goahead arrives once the post has gone");
}

#[test]
fn faults_from_the_world_file_run_byte_identically() {
    let text = std::fs::read_to_string(ilmr_experiments::harness::worlds().join("corridor.toml"))
        .expect("corridor world");
    let text = format!(
        "{text}\n[[fault]]\nkind = \"odometry_slip\"\nstart = 1.0\nslip = 0.2\n\n\
         [[fault]]\nkind = \"scanner_dropout\"\nstart = 3.0\nduration = 2.0\n"
    );
    let run = |seed| {
        let w = World::from_toml(&text, "corridor+faults").expect("world with faults");
        let r = drive(moro(w, seed), GO, 30.0, |_| {});
        let sim = r.vm.hal().inner.sim();
        format!("{}{:?}", r.trace, sim.true_pose())
    };
    let a = run(21);
    assert!(a == run(21), "same seed and faults, different runs");
    assert!(a != run(22), "the slip is seeded");
}
