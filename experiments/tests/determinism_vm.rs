//! The same task on the same seed gives byte-identical traces (the VM's
//! JSON Lines and every true pose); another seed gives another run; so with
//! each error profile.

mod experiment;

use experiment::{A, Task, moro_with, run, shipped, speed, vm};
use ilmr_sim::SimProfile;
use ilmr_stdlib::Command;

fn trace_bytes(seed: u64, profile: SimProfile) -> String {
    let task = speed(Task::new(), 0.5)
        .cmd("obsavoid(on)", Command::ObsAvoid, &[A::W("on")], None)
        .cmd("goahead(2)", Command::Goahead, &[A::N(2.0)], None)
        .cmd(
            "turn(d=90,c=0.6)",
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", 0.6)],
            None,
        )
        .cmd(
            "followwall(right,1.0)",
            Command::FollowWall,
            &[A::W("right"), A::N(1.0)],
            None,
        )
        .finish();
    let mut vm = vm(task, moro_with(shipped("office"), seed, profile));
    let out = run(&mut vm, 20.0);
    let mut s = ilmr_vm::to_jsonl(vm.module(), vm.events());
    for p in &out.trace {
        s.push_str(&format!("{:?} {:?} {:?}\n", p.x, p.y, p.h));
    }
    s
}

#[test]
fn same_seed_same_bytes_other_seed_other_run() {
    let a = trace_bytes(11, SimProfile::Basic);
    let b = trace_bytes(11, SimProfile::Basic);
    assert!(a == b, "two runs with seed 11 differ");
    assert!(
        a != trace_bytes(12, SimProfile::Basic),
        "seed 12 gave the same run"
    );
}

#[test]
fn calibrated_and_ideal_runs_are_byte_identical_per_seed() {
    let a = trace_bytes(11, SimProfile::Calibrated);
    assert!(
        a == trace_bytes(11, SimProfile::Calibrated),
        "calibrated, seed 11 twice"
    );
    assert!(
        a != trace_bytes(12, SimProfile::Calibrated),
        "calibrated, seeds 11 and 12"
    );
    assert!(
        a != trace_bytes(11, SimProfile::Basic),
        "the profile changes the run"
    );
    // Without noise the seed has nothing to change.
    let ideal = trace_bytes(11, SimProfile::Ideal);
    assert!(
        ideal == trace_bytes(12, SimProfile::Ideal),
        "ideal runs differ by seed"
    );
}
