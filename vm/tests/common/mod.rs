//! A hand assembler for tests: statements are written with their source text and get
//! consecutive line numbers, as the compiler's lowering would produce them.
#![allow(dead_code)]

use ilmr_hal::{Limits, ScriptedRobot};
use ilmr_stdlib::{Command, Field, VarKind};
use ilmr_vm::bytecode::{Arg, BlockId, ExprId, ExprOp, FileId, Fragment, Instr, Op, UnitId};
use ilmr_vm::{Config, Module, ModuleBuilder, SimClock, TraceLevel, Vm};

/// An argument as written.
pub enum A<'a> {
    N(f64),
    W(&'a str),
    S(&'a str, f64),
    V(&'a str),
    /// A computed number (`gotoxy(x,0)` with `x` a number variable).
    E(ExprId),
}

/// An expression term in postfix.
pub enum X<'a> {
    N(f64),
    /// A variable's numeric field (by its kind), or status for status variables.
    V(&'a str),
    /// A variable's status (a bare variable in a condition).
    St(&'a str),
    F(&'a str, Field),
    At(&'a str, &'a str),
    Op(ExprOp),
}

pub struct Asm {
    pub b: ModuleBuilder,
    file: FileId,
    line: u32,
    offset: u32,
}

impl Asm {
    pub fn new() -> Asm {
        let mut b = ModuleBuilder::new();
        let file = b.file("test.ilmr").expect("file");
        Asm {
            b,
            file,
            line: 0,
            offset: 0,
        }
    }

    /// Continues numbering lines after `live`'s last statement (interactive lines).
    pub fn extending(live: &Module, file: &str) -> Asm {
        let mut b = ModuleBuilder::extending(live);
        let file = b.file(file).expect("file");
        Asm {
            b,
            file,
            line: 0,
            offset: 0,
        }
    }

    pub fn var(&mut self, name: &str, kind: VarKind) -> ilmr_vm::bytecode::VarId {
        self.b.global(name, kind).expect("one kind per variable")
    }

    fn vid(&mut self, name: &str) -> ilmr_vm::bytecode::VarId {
        match self.b.find_global(name) {
            Some(v) => v,
            None => self.var(name, VarKind::Number),
        }
    }

    fn stmt(&mut self, text: &str) -> ilmr_vm::bytecode::StmtId {
        self.line += 1;
        let start = self.offset;
        self.offset += text.len() as u32 + 1;
        self.b
            .stmt(
                self.file,
                self.line,
                (start, start + text.len() as u32),
                text,
            )
            .expect("stmt")
    }

    /// An empty line between blocks.
    pub fn blank(&mut self) {
        self.line += 1;
        self.offset += 1;
    }

    pub fn expr(&mut self, terms: &[X]) -> ExprId {
        let mut ops = Vec::new();
        for t in terms {
            ops.push(match *t {
                X::N(n) => ExprOp::Const(self.b.constant(n).expect("const")),
                X::V(name) => {
                    let v = self.vid(name);
                    let kind = self.b.module().globals[v.index()].kind;
                    ExprOp::Field(v, kind.numeric_field().unwrap_or(Field::Status))
                }
                X::St(name) => ExprOp::Field(self.vid(name), Field::Status),
                X::F(name, f) => ExprOp::Field(self.vid(name), f),
                X::At(a, b) => ExprOp::PosEq(self.vid(a), self.vid(b)),
                X::Op(op) => op,
            });
        }
        self.b.expr(&ops).expect("expr")
    }

    pub fn cmd(&mut self, text: &str, command: Command, args: &[A], bind: Option<&str>) -> Instr {
        let stmt = self.stmt(text);
        let mut list = Vec::new();
        for a in args {
            list.push(match *a {
                A::N(n) => Arg::Num(self.b.num(n).expect("num")),
                A::W(w) => Arg::Word(self.b.name(w).expect("name")),
                A::S(k, v) => Arg::Setting {
                    key: self.b.name(k).expect("name"),
                    value: self.b.num(v).expect("num"),
                },
                A::V(name) => Arg::Var(self.vid(name)),
                A::E(e) => Arg::Num(e),
            });
        }
        let args = self.b.args(&list).expect("args");
        let bind = bind.map(|name| {
            let form = command.spec().forms.first().map(|f| f.produces);
            let kind = match (command, args.len) {
                (Command::Sensor, n) if n >= 2 && matches!(list[1], Arg::Word(w) if !command.spec().has_keyword(self.b.module().name(w))) => VarKind::Position,
                (Command::Sensor, _) => VarKind::Reading,
                _ => form.unwrap_or(VarKind::Status),
            };
            self.var(name, kind)
        });
        Instr::new(
            Op::Issue {
                command,
                args,
                bind,
            },
            stmt,
        )
    }

    pub fn assign(&mut self, text: &str, var: &str, terms: &[X]) -> Instr {
        let stmt = self.stmt(text);
        let var = self.vid(var);
        let expr = self.expr(terms);
        Instr::new(Op::Assign { var, expr }, stmt)
    }

    pub fn op(&mut self, text: &str, op: Op) -> Instr {
        let stmt = self.stmt(text);
        Instr::new(op, stmt)
    }

    pub fn wait(&mut self, text: &str, seconds: f64) -> Instr {
        let stmt = self.stmt(text);
        let seconds = self.b.num(seconds).expect("num");
        Instr::new(
            Op::WaitTime {
                seconds,
                bind: None,
            },
            stmt,
        )
    }

    /// `var=wait(seconds)`.
    pub fn wait_bound(&mut self, text: &str, seconds: f64, var: &str) -> Instr {
        let stmt = self.stmt(text);
        let seconds = self.b.num(seconds).expect("num");
        let bind = Some(self.vid(var));
        Instr::new(Op::WaitTime { seconds, bind }, stmt)
    }

    pub fn wait_var(&mut self, text: &str, var: &str) -> Instr {
        let stmt = self.stmt(text);
        let var = self.vid(var);
        Instr::new(Op::WaitVar { var, bind: None }, stmt)
    }

    pub fn brk(&mut self, text: &str, pattern: &str) -> Instr {
        let stmt = self.stmt(text);
        let pattern = self.b.name(pattern).expect("name");
        Instr::new(Op::Break { pattern }, stmt)
    }

    pub fn clear(&mut self, text: &str, var: &str) -> Instr {
        let stmt = self.stmt(text);
        let var = self.vid(var);
        Instr::new(Op::Clear { var }, stmt)
    }

    pub fn call(&mut self, text: &str, unit: UnitId, bind: Option<&str>) -> Instr {
        let stmt = self.stmt(text);
        let bind = bind.map(|n| self.var(n, VarKind::Status));
        Instr::new(Op::Call { unit, bind }, stmt)
    }

    /// `if(cond)` with the body written by `body`, then `endif`.
    pub fn if_(
        &mut self,
        text: &str,
        cond: &[X],
        body: impl FnOnce(&mut Asm) -> Vec<Instr>,
    ) -> Instr {
        let stmt = self.stmt(text);
        let cond = self.expr(cond);
        let code = body(self);
        self.line += 1;
        let body = self.b.block(&code).expect("block");
        Instr::new(
            Op::If {
                cond,
                body,
                bind: None,
            },
            stmt,
        )
    }

    pub fn while_(
        &mut self,
        text: &str,
        cond: &[X],
        bind: Option<&str>,
        body: impl FnOnce(&mut Asm) -> Vec<Instr>,
    ) -> Instr {
        let stmt = self.stmt(text);
        let cond = self.expr(cond);
        let bind = bind.map(|n| self.var(n, VarKind::Status));
        let code = body(self);
        self.line += 1;
        let body = self.b.block(&code).expect("block");
        Instr::new(Op::While { cond, body, bind }, stmt)
    }

    pub fn block(&mut self, code: Vec<Instr>) -> BlockId {
        self.b.block(&code).expect("block")
    }

    pub fn skill(&mut self, name: &str) -> UnitId {
        self.b.declare_unit(name, true).expect("unit")
    }

    pub fn define(&mut self, unit: UnitId, blocks: &[BlockId]) {
        self.b.define_unit(unit, blocks);
    }

    /// Finishes with `blocks` as the task's top-level blocks.
    pub fn task(mut self, blocks: &[BlockId]) -> Module {
        let main = self.b.declare_unit("task", false).expect("unit");
        self.b.define_unit(main, blocks);
        self.b.set_main(main);
        self.b.finish().expect("valid module")
    }

    pub fn fragment(self, blocks: &[BlockId]) -> Fragment {
        self.b.finish_fragment(blocks).expect("valid fragment")
    }
}

pub fn config() -> Config {
    Config {
        trace: TraceLevel::Commands,
        ..Config::default()
    }
}

pub fn robot() -> ScriptedRobot {
    ScriptedRobot::new(Limits::default())
}

pub type TestVm = Vm<ScriptedRobot, SimClock>;

pub fn vm(module: Module, robot: ScriptedRobot, cfg: Config) -> TestVm {
    Vm::new(module, robot, SimClock, cfg).expect("valid module")
}

/// The trace as JSON Lines.
pub fn trace(vm: &TestVm) -> String {
    ilmr_vm::to_jsonl(vm.module(), vm.events())
}

/// Time of the first event of `kind` for the statement with `text`.
pub fn when(vm: &TestVm, kind: &str, text: &str) -> Option<f64> {
    vm.events().iter().find_map(|e| {
        let s = e.stmt.and_then(|s| vm.module().stmt(s))?;
        (e.kind.name() == kind && s.text == text).then_some(e.t)
    })
}

/// `how` of the end event of the statement with `text`.
pub fn ended(vm: &TestVm, text: &str) -> Option<String> {
    vm.events().iter().find_map(|e| {
        let s = e.stmt.and_then(|s| vm.module().stmt(s))?;
        match &e.kind {
            ilmr_vm::EventKind::End { how, .. } if s.text == text => Some(how.name().to_string()),
            _ => None,
        }
    })
}
