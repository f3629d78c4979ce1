//! Guards of the compiled shape (`var.field <op> const`, `const <op> var.field`, a bare
//! variable) wait by threshold, general guards and waits in subscription lists; a wake
//! must still fire them all in the order they were issued, whichever list holds them,
//! and under a budget that runs out in the middle of a wake.

mod common;

use common::{Asm, X, config, robot, vm};
use ilmr_stdlib::Field;
use ilmr_vm::bytecode::ExprOp;
use ilmr_vm::{Config, EventKind};

/// Statement texts of the `start` events, in trace order.
fn starts(vm: &common::TestVm) -> Vec<String> {
    vm.events()
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Start { .. }))
        .filter_map(|e| e.stmt.and_then(|s| vm.module().stmt(s)))
        .map(|s| s.text.clone())
        .collect()
}

/// Guards of every shape on `t`, issued in this order; `t` jumps from 1 to 3, which
/// makes all of them true in one wake, then to 0.
fn mixed(cfg: Config) -> common::TestVm {
    let mut a = Asm::new();
    let body = |a: &mut Asm, n: &str| vec![a.assign(&format!("{n}=1"), n, &[X::N(1.0)])];
    let guards = vec![
        a.assign("t=1", "t", &[X::N(1.0)]),
        a.if_("if(t>2)", &[X::V("t"), X::N(2.0), X::Op(ExprOp::Gt)], |a| {
            body(a, "g1")
        }),
        a.if_(
            "if(t+0>2)",
            &[
                X::V("t"),
                X::N(0.0),
                X::Op(ExprOp::Add),
                X::N(2.0),
                X::Op(ExprOp::Gt),
            ],
            |a| body(a, "g2"),
        ),
        a.if_(
            "if(3<=t)",
            &[X::N(3.0), X::V("t"), X::Op(ExprOp::Le)],
            |a| body(a, "g3"),
        ),
        a.if_(
            "if(t==3)",
            &[X::V("t"), X::N(3.0), X::Op(ExprOp::Eq)],
            |a| body(a, "g4"),
        ),
        a.if_(
            "if(t>2) again",
            &[X::V("t"), X::N(2.0), X::Op(ExprOp::Gt)],
            |a| body(a, "g5"),
        ),
        a.if_("if(t<0)", &[X::V("t"), X::N(0.0), X::Op(ExprOp::Lt)], |a| {
            body(a, "never")
        }),
        a.if_(
            "if(t==1)",
            &[X::V("t"), X::N(1.0), X::Op(ExprOp::Eq)],
            |a| body(a, "g0"),
        ),
    ];
    let b1 = a.block(guards);
    a.blank();
    let driver = vec![
        a.wait("wait(0.05)", 0.05),
        a.assign("t=3", "t", &[X::N(3.0)]),
        a.wait("wait(0.05) again", 0.05),
        a.assign("t=0", "t", &[X::N(0.0)]),
    ];
    let b2 = a.block(driver);
    vm(a.task(&[b1, b2]), robot(), cfg)
}

#[test]
fn guards_of_every_shape_fire_in_issue_order_in_one_wake() {
    let mut vm = mixed(config());
    vm.run_for(0.5);
    assert_eq!(
        starts(&vm),
        [
            "if(t==1)",
            "if(t>2)",
            "if(t+0>2)",
            "if(3<=t)",
            "if(t==3)",
            "if(t>2) again"
        ]
    );
    assert_eq!(vm.var("never").map(|v| v.status), Some(0.0));
    assert_eq!(vm.activity().waiting_guards, 1, "only if(t<0) waits");
    assert!(vm.only_guards_waiting());
}

#[test]
fn a_budget_that_runs_out_in_a_wake_keeps_the_order() {
    // `t=3` and the wake's first guards use up the budget; the rest are queued.
    let cfg = Config {
        budget_ops: 12,
        ..config()
    };
    let mut vm = mixed(cfg);
    vm.run_for(0.5);
    assert!(
        vm.events().iter().any(|e| e.kind.name() == "overrun"),
        "the budget ran out"
    );
    assert_eq!(
        starts(&vm),
        [
            "if(t==1)",
            "if(t>2)",
            "if(t+0>2)",
            "if(3<=t)",
            "if(t==3)",
            "if(t>2) again"
        ]
    );
    assert_eq!(vm.activity().waiting_guards, 1);
}

#[test]
fn broken_guards_never_fire_and_their_place_is_reused() {
    // Many guards on one threshold, broken before it is crossed, then new ones
    // issued on the freed nodes: only the new ones fire.
    let mut a = Asm::new();
    let mut code = vec![a.assign("t=0", "t", &[X::N(0.0)])];
    for _ in 0..200 {
        code.push(a.if_(
            "if(t>=1) old",
            &[X::F("t", Field::Value), X::N(1.0), X::Op(ExprOp::Ge)],
            |a| {
                vec![a.assign(
                    "old=old+1",
                    "old",
                    &[X::V("old"), X::N(1.0), X::Op(ExprOp::Add)],
                )]
            },
        ));
    }
    code.push(a.wait("wait(0.05)", 0.05));
    code.push(a.brk("break(old)", "old"));
    for _ in 0..150 {
        code.push(a.if_(
            "if(t>=1) new",
            &[X::F("t", Field::Value), X::N(1.0), X::Op(ExprOp::Ge)],
            |a| {
                vec![a.assign(
                    "new=new+1",
                    "new",
                    &[X::V("new"), X::N(1.0), X::Op(ExprOp::Add)],
                )]
            },
        ));
    }
    code.push(a.wait("wait(0.05) again", 0.05));
    code.push(a.assign("t=1", "t", &[X::N(1.0)]));
    let b = a.block(code);
    let mut vm = vm(a.task(&[b]), robot(), config());
    assert!(vm.run_for(1.0), "every guard fired or was broken");
    assert_eq!(vm.var("new").map(|v| v.value), Some(150.0));
    assert_eq!(vm.var("old").map(|v| v.value), Some(0.0));
}
