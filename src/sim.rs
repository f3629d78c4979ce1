//! `ilmrc sim --ros2`: the simulated robot as a ROS 2 robot. It steps in real time
//! (10 ms), obeys `cmd_vel` as a base driver does, and publishes its odometry and `tf`
//! at the model's `odometry_rate`, each new scan (at `scanner_rate`), the battery once a
//! second, and its true pose on `ground_truth`: Foxglove, RViz, Nav2 or
//! `ilmrc run --robot ros2` in another process see a robot (docs/ros2.md).

use std::io::Write;
use std::process::ExitCode;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use ilmr_hal::{Hal, Pose};
use ilmr_ros2::base::{Base, BaseConfig};
use ilmr_ros2::convert::Limits;
use ilmr_ros2::msg::Time;
use ilmr_sim::SimRobot;

use crate::ros2::Ros2Args;
use crate::run::backend::WorldScan;
use crate::run::setup::{self, Backend, Choice};

/// One simulation step, s: the simulator's own.
const STEP: f64 = 0.01;

/// Behind the wall clock by more than this, s, the simulation stops catching up and
/// says so: a step that runs late is not made up by a burst of steps.
const MAX_LAG: f64 = 0.25;

#[derive(clap::Args)]
pub struct SimArgs {
    /// Serve the robot over ROS 2 (DDS): the one way `sim` serves it today.
    #[arg(long)]
    pub ros2: bool,
    /// The simulated robot: `moro`, `workpartner` or a ROBO.INI path.
    #[arg(long, default_value = "moro")]
    pub robot: String,
    /// Its world: `office`, `yard`, `empty` or a world file (default: the robot's).
    #[arg(long)]
    pub world: Option<String>,
    /// Where it starts, `X,Y,HEADING` in metres and degrees.
    #[arg(long, allow_hyphen_values = true)]
    pub start: Option<String>,
    /// Seed of the simulated robot's noise.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// The simulated robot's errors: `ideal`, `basic` or `calibrated` (the default; as
    /// `ilmrc run --sim-profile`).
    #[arg(long, value_name = "PROFILE", value_parser = crate::run::parse_profile)]
    pub sim_profile: Option<ilmr_sim::SimProfile>,
    /// Publish `/clock` and stamp every message with simulated time (for nodes with
    /// `use_sim_time`); otherwise messages carry the wall clock.
    #[arg(long)]
    pub clock: bool,
    /// Stop when no `cmd_vel` came for this long, s (a base driver's command timeout).
    #[arg(long, default_value_t = 0.5)]
    pub cmd_timeout: f64,
    /// Stop after this many seconds (default: run until interrupted).
    #[arg(long)]
    pub duration: Option<f64>,
    /// Stop when standard input closes: a launcher's lifeline (`ilmrc fleet` starts
    /// its simulators so), so that a simulator never outlives what started it, however
    /// that ended.
    #[arg(long)]
    pub stdin_lifeline: bool,
    #[command(flatten)]
    pub ros: Ros2Args,
    #[command(flatten)]
    pub view: crate::view::live::FoxgloveArgs,
}

pub fn run(args: SimArgs) -> ExitCode {
    match execute(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

fn execute(args: &SimArgs) -> Result<(), String> {
    if !args.ros2 {
        return Err("say how to serve the simulated robot: `ilmrc sim --ros2`".into());
    }
    if args.ros.ros_wait.is_some() {
        return Err("--ros-wait is for a robot's client (`run --robot ros2`)".into());
    }
    if !(args.cmd_timeout.is_finite() && args.cmd_timeout > 0.0) {
        return Err(format!("--cmd-timeout {} is not a time", args.cmd_timeout));
    }
    if let Some(d) = args.duration.filter(|d| !(d.is_finite() && *d >= 0.0)) {
        return Err(format!("--duration {d} is not a time"));
    }
    let setup = setup::choose(&Choice {
        robot: &args.robot,
        profile: args.sim_profile,
        model: None,
        world: args.world.as_deref(),
        start: args.start.as_deref(),
        ros2: &Ros2Args::default(),
    })?;
    let (Backend::Sim(kind), Some(world)) = (setup.backend, setup.world.as_ref()) else {
        return Err(format!(
            "--robot {}: `sim` runs a simulated robot (moro, workpartner or a ROBO.INI path)",
            args.robot
        ));
    };
    setup::check_faults(world, &setup.model, kind, None, 0)?;
    let ros = args.ros.config(&setup.model)?;
    let start = world.world.start;
    let mut robot = SimRobot::with_profile(
        setup.model.clone(),
        kind,
        setup.profile,
        world.world.clone(),
        args.seed,
    )
    .map_err(|e| format!("the robot cannot start in `{}`: {e}", world.name))?;
    let mut base = Base::open(BaseConfig {
        domain_id: ros.domain_id,
        namespace: ros.namespace.clone(),
        reach: ros.reach,
        topics: ros.topics.clone(),
        frames: ros.frames.clone(),
        limits: Limits::of(&setup.model),
        cmd_timeout: args.cmd_timeout,
        clock: args.clock,
    })
    .map_err(|e| e.to_string())?;
    // The line a launcher (and the tests) wait for: the endpoints exist.
    println!(
        "ilmrc sim: {} in {} at ({}, {}, {} deg), seed {}; ROS 2 namespace {}, DDS domain {}: \
         cmd_vel in; odom and tf at {} Hz, scan at {} Hz, battery_state, ground_truth{} out",
        setup.model_spec,
        world.name,
        start.x,
        start.y,
        start.h.to_degrees(),
        args.seed,
        ros.namespace,
        ros.domain_id,
        setup.model.odometry_rate(),
        setup.model.scanner_rate(),
        if args.clock { ", /clock" } else { "" },
    );
    let _ = std::io::stdout().flush();
    if args.stdin_lifeline {
        watch_lifeline();
    }
    let mut view = args.view.open(&world.name, Some(&world.world))?;
    let lags = serve(&mut robot, &mut base, args, &setup.model, view.as_mut())?;
    if let Some(v) = view {
        crate::view::live::close(v);
    }
    let s = base.stats();
    println!(
        "ilmrc sim: {:.2} s; cmd_vel {} taken, {} dropped; published odom {}, scan {}, battery {}, clock {}; fell behind {lags} times",
        robot.sim().time(),
        s.commands.0,
        s.commands.1,
        s.odometry,
        s.scans,
        s.battery,
        s.clock
    );
    Ok(())
}

/// Steps the robot in real time until `--duration`; returns how often it fell behind.
fn serve(
    robot: &mut SimRobot,
    base: &mut Base,
    args: &SimArgs,
    model: &ilmr_model::RobotModel,
    mut view: Option<&mut crate::view::live::Live>,
) -> Result<u64, String> {
    let scan_period = 1.0 / model.scanner_rate();
    let odometry_period = 1.0 / model.odometry_rate();
    let mut odometry_sent = f64::NEG_INFINITY;
    let full = model.battery_full();
    let mut epoch = Instant::now();
    let mut done: u64 = 0;
    let mut lags = 0;
    let mut odometry_t = f64::NAN;
    let mut scan_seq = None;
    let mut battery_t = f64::NEG_INFINITY;
    let link = |e: ilmr_ros2::LinkError| e.to_string();
    loop {
        let step = done + 1;
        let t = step as f64 * STEP;
        if args.duration.is_some_and(|d| t > d + 1e-9) {
            return Ok(lags);
        }
        let due = epoch + Duration::from_secs_f64(step as f64 * STEP);
        let now = Instant::now();
        if due > now {
            std::thread::sleep(due - now);
        } else if now - due > Duration::from_secs_f64(MAX_LAG) {
            lags += 1;
            epoch = now - Duration::from_secs_f64(step as f64 * STEP);
        }
        let (speed, curvature) = base.command(t);
        // The simulated drive refuses what its body cannot do (parked, say); the
        // command stream goes on, as a driver's does.
        let _ = robot.set_motion(speed, curvature);
        robot
            .update(t)
            .map_err(|e| format!("the simulator failed: {e}"))?;
        done = step;
        let stamp = if args.clock {
            Time::from_secs(t)
        } else {
            wall_clock()
        };
        base.clock(stamp).map_err(link)?;
        let sim = robot.sim();
        let seen = sim.snapshot();
        // The simulator reads its wheel counters every step; a robot publishes them at
        // its odometry rate.
        if seen.odometry_time != odometry_t && t - odometry_sent >= odometry_period - 1e-9 {
            odometry_t = seen.odometry_time;
            odometry_sent = t;
            let scanner = seen
                .scan
                .as_ref()
                .map(|s| Pose::new(s.mount.x, s.mount.y, 0.0));
            base.odometry(seen.pose, seen.speed, seen.curvature, scanner, stamp)
                .map_err(link)?;
            let truth = robot.true_pose();
            base.ground_truth(truth, sim.true_speed(), sim.true_curvature(), stamp)
                .map_err(link)?;
            if let Some(v) = view.as_deref_mut() {
                let motion = (sim.true_speed(), sim.true_curvature());
                v.robot(t, (truth.x, truth.y, truth.h), motion);
            }
        }
        if let Some(s) = seen.scan.as_ref().filter(|s| scan_seq != Some(s.seq)) {
            scan_seq = Some(s.seq);
            let scan = ilmr_hal::Scan {
                device: "scanner".into(),
                t: s.time,
                angle_min: s.angle_min,
                angle_step: s.angle_increment,
                ranges: s.ranges.clone(),
            };
            base.scan(&scan, s.max_range, scan_period, stamp)
                .map_err(link)?;
            if let (Some(v), Some((_, scan))) = (view.as_deref_mut(), WorldScan::last_of(robot)) {
                v.scan(&scan);
            }
        }
        if t - battery_t >= 1.0 - 1e-9 {
            battery_t = t;
            let v = seen.battery.voltage;
            base.battery(v, v / full, stamp).map_err(link)?;
        }
    }
}

/// Ends the process when standard input reaches its end (the launcher is gone).
fn watch_lifeline() {
    std::thread::spawn(|| {
        let mut sink = [0u8; 256];
        let mut stdin = std::io::stdin().lock();
        while matches!(std::io::Read::read(&mut stdin, &mut sink), Ok(n) if n > 0) {}
        std::process::exit(0);
    });
}

fn wall_clock() -> Time {
    let since = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap_or_default();
    Time::from_secs(since.as_secs_f64())
}
