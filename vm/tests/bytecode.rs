//! The module format: the opcode table of docs/bytecode.md, serialisation, validation
//! of untrusted files, the builder's errors and the disassembler.

mod common;

use common::{A, Asm, X, config, robot, vm};
use ilmr_stdlib::{Command, VarKind};
use ilmr_vm::bytecode::{BuildError, ExprOp, ModuleError, Op, Opcode, disassemble};
use ilmr_vm::{Module, ModuleBuilder};

#[test]
fn docs_table_matches_opcodes() {
    let doc = include_str!("../../docs/bytecode.md");
    let section = doc
        .split("## Instructions")
        .nth(1)
        .and_then(|s| s.split("\n## ").next())
        .expect("an Instructions section");
    let documented: Vec<&str> = section
        .lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .filter_map(|l| l.split('`').next())
        .collect();
    let opcodes: Vec<&str> = Opcode::ALL.iter().map(|o| o.mnemonic()).collect();
    assert_eq!(documented, opcodes);
    for (i, op) in Opcode::ALL.iter().enumerate() {
        assert_eq!(*op as usize, i, "ALL is in discriminant order");
    }
}

/// Figure 27 of the dissertation, in part.
fn figure_27() -> Module {
    let mut a = Asm::new();
    let clap = a.skill("clap_hands");
    let cb = vec![a.cmd(
        "actuator(hands,on)",
        Command::Actuator,
        &[A::W("hands"), A::W("on")],
        None,
    )];
    let cb = a.block(cb);
    a.define(clap, &[cb]);
    a.blank();
    let code = vec![
        a.cmd("obsavoid(on)", Command::ObsAvoid, &[A::W("on")], None),
        a.cmd(
            "d=followwall(middle)",
            Command::FollowWall,
            &[A::W("middle")],
            Some("d"),
        ),
        a.assign("cnt=0", "cnt", &[X::N(0.0)]),
        a.while_(
            "while(cnt<5)",
            &[X::V("cnt"), X::N(5.0), X::Op(ExprOp::Lt)],
            None,
            |a| {
                vec![
                    a.cmd(
                        "door=findtarget(scanner,door)",
                        Command::FindTarget,
                        &[A::W("scanner"), A::W("door")],
                        Some("door"),
                    ),
                    a.if_("if(door)", &[X::St("door")], |a| {
                        vec![
                            a.assign(
                                "cnt=cnt+1",
                                "cnt",
                                &[X::V("cnt"), X::N(1.0), X::Op(ExprOp::Add)],
                            ),
                            a.call("clap_hands", clap, None),
                        ]
                    }),
                ]
            },
        ),
        a.if_(
            "if(cnt==5)",
            &[X::V("cnt"), X::N(5.0), X::Op(ExprOp::Eq)],
            |a| {
                vec![
                    a.brk("break(followw)", "followw"),
                    a.brk("break(while(c))", "while(c"),
                ]
            },
        ),
        a.cmd(
            "ready=gotoxy(door)",
            Command::GotoXY,
            &[A::V("door")],
            Some("ready"),
        ),
        a.wait_var("wait(ready)", "ready"),
    ];
    let b1 = a.block(code);
    a.blank();
    let code = vec![
        a.cmd(
            "battery=sensor(battery)",
            Command::Sensor,
            &[A::W("battery")],
            Some("battery"),
        ),
        a.if_(
            "if(battery<24)",
            &[X::V("battery"), X::N(24.0), X::Op(ExprOp::Lt)],
            |a| {
                vec![
                    a.op("priority=highest", Op::Priority),
                    a.op("stop", Op::Stop),
                ]
            },
        ),
    ];
    let b2 = a.block(code);
    a.task(&[b1, b2])
}

#[test]
fn disassembly_lists_every_block_with_its_source() {
    insta::assert_snapshot!(disassemble(&figure_27()));
}

#[test]
fn modules_round_trip_through_bytes() {
    let m = figure_27();
    let bytes = m.to_bytes();
    assert_eq!(Module::from_bytes(&bytes), Ok(m));
}

/// Where the payload's length and the payload start in `bytes` (the toolchain's name
/// has its length before it).
fn payload_at(bytes: &[u8]) -> usize {
    8 + 4 + 1 + bytes[12] as usize
}

/// `bytes` with its payload replaced, the length and the checksum made right again, so
/// that the change reaches the decoder.
fn with_payload(bytes: &[u8], payload: &[u8]) -> Vec<u8> {
    let at = payload_at(bytes);
    let mut out = bytes[..at].to_vec();
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(payload);
    ilmr_vm::bytecode::file::seal(&mut out);
    out
}

#[test]
fn foreign_files_are_rejected_before_they_run() {
    let good = figure_27().to_bytes();
    assert_eq!(&good[..8], &ilmr_vm::bytecode::file::MAGIC);

    for foreign in [
        &b""[..],
        b"\x00\x01garbage",
        b"\x7fELF\x02\x01\x01\x00rest",
        b"ILMB",
    ] {
        assert_eq!(Module::from_bytes(foreign), Err(ModuleError::NotModule));
    }
    // A module of the JSON format before this one says its version.
    assert_eq!(
        Module::from_bytes(br#"{"header":{"magic":"ILMB","version":1},"files":[]}"#),
        Err(ModuleError::Version {
            found: 1,
            expected: ilmr_vm::bytecode::VERSION
        })
    );

    let mut newer = good.clone();
    newer[8..12].copy_from_slice(&99u32.to_le_bytes());
    assert!(matches!(
        Module::from_bytes(&newer),
        Err(ModuleError::Version { found: 99, .. })
    ));

    let mut longer = good.clone();
    longer.push(0);
    assert!(matches!(
        Module::from_bytes(&longer),
        Err(ModuleError::Length { .. })
    ));

    let mut flipped = good.clone();
    let last_payload = good.len() - 5;
    flipped[last_payload] ^= 1;
    assert!(matches!(
        Module::from_bytes(&flipped),
        Err(ModuleError::Checksum { .. })
    ));

    let mut m = figure_27();
    m.blocks[0].len = 100_000;
    assert!(matches!(
        Module::from_bytes(&m.to_bytes()),
        Err(ModuleError::Index { .. })
    ));

    let mut m = figure_27();
    m.expr_code[0] = ExprOp::Add;
    assert!(matches!(
        Module::from_bytes(&m.to_bytes()),
        Err(ModuleError::Expr { .. })
    ));
}

/// Every prefix of a file is refused, with its length as the reason once the magic is
/// whole.
#[test]
fn a_file_cut_anywhere_is_refused() {
    let good = figure_27().to_bytes();
    for n in 0..good.len() {
        match Module::from_bytes(&good[..n]) {
            Err(ModuleError::NotModule) => assert!(n < 8, "cut at {n}"),
            Err(ModuleError::Length { found, .. }) => assert_eq!(found, n as u64),
            other => panic!("cut at {n}: {other:?}"),
        }
    }
    assert!(Module::from_bytes(&good).is_ok());
}

/// Every single bit flipped is caught, by the magic, the version, the length or the
/// checksum; flipped and resealed, it reaches the decoder and the validator, and
/// whatever loads runs.
#[test]
fn every_bit_flip_is_caught_and_none_panics() {
    let good = figure_27().to_bytes();
    let mut loaded = 0;
    for byte in 0..good.len() {
        for bit in 0..8 {
            let mut bad = good.clone();
            bad[byte] ^= 1 << bit;
            assert!(
                Module::from_bytes(&bad).is_err(),
                "bit {bit} of byte {byte}"
            );
            ilmr_vm::bytecode::file::reseal(&mut bad);
            if let Ok(module) = Module::from_bytes(&bad) {
                loaded += 1;
                if (byte + bit) % 7 == 0 {
                    vm(module, robot(), config()).run_for(0.3);
                }
            }
        }
    }
    assert!(loaded > 0, "some flips in the payload still make a module");
}

/// A table that claims four billion entries in a file of a few bytes is refused at
/// once: nothing is allocated for entries whose bytes are not there
/// (`tests/ilmb_alloc.rs` counts the bytes).
#[test]
fn a_length_past_the_file_is_refused_without_allocating_for_it() {
    let good = figure_27().to_bytes();
    // postcard's varint of 4,000,000,000, then nothing.
    let huge = [0x80, 0xd0, 0xac, 0xf3, 0x0e];
    let bad = with_payload(&good, &huge);
    assert!(matches!(
        Module::from_bytes(&bad),
        Err(ModuleError::Decode(_))
    ));
    // The same claim on the statements, after an empty file table.
    let mut payload = vec![0];
    payload.extend_from_slice(&huge);
    payload.extend_from_slice(&[1, 2, 3]);
    assert!(matches!(
        Module::from_bytes(&with_payload(&good, &payload)),
        Err(ModuleError::Decode(_))
    ));
    // A header that promises more payload than the file holds.
    let mut lying = good.clone();
    let at = payload_at(&good);
    lying[at..at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
    assert!(matches!(
        Module::from_bytes(&lying),
        Err(ModuleError::Length { .. })
    ));
}

/// A seeded loop of random damage (bits, bytes, cuts, insertions, splices from another
/// module), most of it resealed so that it reaches the decoder: no input panics, every
/// error says something, and whatever loads validates and runs.
#[test]
fn the_loader_survives_random_damage() {
    let seeds = [figure_27().to_bytes(), empty_task().to_bytes()];
    let mut rng = ilmr_geometry::SplitMix64::new(0x1a2b_3c4d_5e6f_7788);
    let mut next = move |n: usize| (rng.next_u64() % n.max(1) as u64) as usize;
    let (mut loaded, mut refused) = (0, 0);
    for i in 0..20_000 {
        let mut bytes = seeds[i % 2].clone();
        for _ in 0..1 + next(4) {
            let at = next(bytes.len());
            match next(6) {
                0 => bytes[at] ^= 1 << next(8),
                1 => bytes[at] = next(256) as u8,
                2 => bytes.truncate(at),
                3 => bytes.insert(at, next(256) as u8),
                4 => {
                    let other = &seeds[(i + 1) % 2];
                    let from = next(other.len());
                    let len = next(16).min(other.len() - from);
                    let end = (at + len).min(bytes.len());
                    bytes.splice(at..end, other[from..from + len].iter().copied());
                }
                _ => bytes[at] = bytes[at].wrapping_add(1),
            }
            if bytes.is_empty() {
                bytes = seeds[0].clone();
            }
        }
        if next(10) < 8 && bytes.len() > 25 {
            // Make the length and the checksum right again.
            let at = payload_at(&bytes).min(bytes.len() - 12);
            let payload_len = (bytes.len() - at - 8 - 4) as u64;
            bytes[at..at + 8].copy_from_slice(&payload_len.to_le_bytes());
            ilmr_vm::bytecode::file::reseal(&mut bytes);
        }
        match Module::from_bytes(&bytes) {
            Ok(module) => {
                loaded += 1;
                assert!(module.validate().is_ok());
                if i % 50 == 0 {
                    vm(module, robot(), config()).run_for(0.2);
                }
            }
            Err(e) => {
                refused += 1;
                assert!(!e.to_string().is_empty());
            }
        }
    }
    assert!(
        loaded > 0 && refused > 0,
        "{loaded} loaded, {refused} refused"
    );
}

/// A task of one empty block: the smallest module.
fn empty_task() -> Module {
    let mut b = ModuleBuilder::new();
    let main = b.declare_unit("task", false).expect("unit");
    let blk = b.block(&[]).expect("block");
    b.define_unit(main, &[blk]);
    b.finish().expect("valid")
}

/// Every number of a valid module nudged, one at a time, in its JSON form, then
/// written as a file: loading never panics, and whatever loads also runs.
#[test]
fn mutated_files_never_panic() {
    let m = figure_27();
    let json = serde_json::to_value(&m).expect("json");
    let mut paths = Vec::new();
    collect_numbers(&json, &mut Vec::new(), &mut paths);
    assert!(paths.len() > 100);
    let mut loaded = 0;
    for (i, path) in paths.iter().enumerate() {
        for delta in [1i64, 7, -1, 1 << 20] {
            let mut v = json.clone();
            let slot = path.iter().fold(&mut v, |v, k| match k {
                Key::I(i) => &mut v[*i],
                Key::S(s) => &mut v[s.as_str()],
            });
            let n = slot.as_i64().unwrap_or(0).saturating_add(delta);
            *slot = n.into();
            let Ok(changed) = serde_json::from_value::<Module>(v) else {
                continue;
            };
            if let Ok(module) = Module::from_bytes(&changed.to_bytes()) {
                loaded += 1;
                if i % 5 == 0 {
                    let mut vm = vm(module, robot(), config());
                    vm.run_for(0.3);
                }
            }
        }
    }
    assert!(loaded > 0);
}

enum Key {
    I(usize),
    S(String),
}

fn collect_numbers(v: &serde_json::Value, at: &mut Vec<Key>, out: &mut Vec<Vec<Key>>) {
    let clone = |at: &Vec<Key>| {
        at.iter()
            .map(|k| match k {
                Key::I(i) => Key::I(*i),
                Key::S(s) => Key::S(s.clone()),
            })
            .collect::<Vec<_>>()
    };
    match v {
        serde_json::Value::Number(n) if n.is_u64() => out.push(clone(at)),
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                at.push(Key::I(i));
                collect_numbers(x, at, out);
                at.pop();
            }
        }
        serde_json::Value::Object(o) => {
            for (k, x) in o {
                at.push(Key::S(k.clone()));
                collect_numbers(x, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

#[test]
fn the_builder_refuses_what_the_vm_could_not_run() {
    let mut b = ModuleBuilder::new();
    b.global("door", VarKind::Position).expect("new");
    assert!(matches!(
        b.global("DOOR", VarKind::Number),
        Err(BuildError::KindConflict { .. })
    ));
    assert_eq!(
        b.global("Door", VarKind::Position),
        b.global("door", VarKind::Position)
    );

    let mut a = Asm::new();
    let code = vec![
        a.assign("x=1", "x", &[X::N(1.0)]),
        a.op("priority=highest", Op::Priority),
    ];
    let blk = a.block(code);
    let main = a.b.declare_unit("task", false).expect("unit");
    a.b.define_unit(main, &[blk]);
    a.b.set_main(main);
    assert!(matches!(
        a.b.finish(),
        Err(BuildError::Invalid(ModuleError::PriorityNotFirst { .. }))
    ));

    let mut a = Asm::new();
    let stmt =
        a.b.stmt(ilmr_vm::bytecode::FileId(0), 1, (0, 4), "wait")
            .expect("stmt");
    let args = a.b.args(&[]).expect("args");
    let blk =
        a.b.block(&[ilmr_vm::bytecode::Instr::new(
            Op::Issue {
                command: Command::Wait,
                args,
                bind: None,
            },
            stmt,
        )])
        .expect("block");
    let main = a.b.declare_unit("task", false).expect("unit");
    a.b.define_unit(main, &[blk]);
    assert_eq!(
        a.b.finish(),
        Err(BuildError::Invalid(ModuleError::NotIssuable(Command::Wait)))
    );
}

/// Each file, name, constant, variable and unit is interned once, variables and units
/// in any letter case; a builder lent a live module finds what the module holds and
/// indexes what it adds.
#[test]
fn the_builder_interns_each_value_once() {
    let mut b = ModuleBuilder::new();
    let x = b.global("Count", VarKind::Number).expect("new");
    let vars: Vec<_> = (0..1000)
        .map(|i| b.global(&format!("v{i}"), VarKind::Number).expect("new"))
        .collect();
    assert_eq!(b.find_global("COUNT"), Some(x));
    assert_eq!(b.find_global("V999"), Some(vars[999]));
    assert_eq!(b.find_global("v1000"), None);
    let zero = b.constant(0.0).expect("constant");
    assert_ne!(b.constant(-0.0).expect("constant"), zero);
    assert_eq!(b.constant(0.0).expect("constant"), zero);
    let word = b.name("Left").expect("name");
    assert_ne!(b.name("left").expect("name"), word, "names keep their case");
    assert_eq!(b.name("Left").expect("name"), word);
    let file = b.file("a.ilmr").expect("file");
    assert_eq!(b.file("a.ilmr").expect("file"), file);
    let unit = b.declare_unit("Task", false).expect("unit");
    assert_eq!(b.find_unit("task"), Some(unit));
    assert_eq!(
        b.declare_unit("TASK", true),
        Err(BuildError::DuplicateUnit("TASK".into()))
    );
    let blk = b.block(&[]).expect("block");
    b.define_unit(unit, &[blk]);
    let live = b.finish().expect("valid");

    let mut lent = ModuleBuilder::extending(&live);
    assert_eq!(lent.find_global("count"), Some(x));
    assert_eq!(lent.global("v500", VarKind::Number), Ok(vars[500]));
    let y = lent.global("y", VarKind::Number).expect("new");
    assert_eq!(y.0 as usize, live.globals.len());
    assert_eq!(lent.find_global("Y"), Some(y));
    assert_eq!(lent.constant(0.0), Ok(zero));
    let one = lent.constant(1.0).expect("new");
    assert_eq!(lent.constant(1.0), Ok(one));
    assert_eq!(lent.name("Left"), Ok(word));
    assert_eq!(lent.file("a.ilmr"), Ok(file));
    assert_eq!(lent.find_unit("TASK"), Some(unit));
    let fragment = lent.finish_fragment(&[]).expect("valid");
    assert_eq!(fragment.added.globals.len(), 1);
    assert_eq!(fragment.added.consts, [1.0]);
}

/// The format stands on its own: a loader or disassembler needs the bytecode module
/// alone, so nothing in it reaches into the runtime (docs/bytecode.md).
#[test]
fn the_bytecode_does_not_import_the_runtime() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/bytecode");
    let mut files = 0;
    for entry in std::fs::read_dir(&dir).expect("vm/src/bytecode") {
        let path = entry.expect("entry").path();
        let text = std::fs::read_to_string(&path).expect("source");
        files += 1;
        for needle in ["runtime::", "crate::Vm", "super::super::"] {
            assert!(
                !text.contains(needle),
                "{} mentions `{needle}`",
                path.display()
            );
        }
    }
    assert!(files > 5);
}

/// A writer that fails part way (a full disk) makes `file::write` return its error;
/// one that takes everything gets the bytes `to_bytes` gives.
#[test]
fn writing_a_file_reports_the_writers_error() {
    struct Full {
        room: usize,
        inner: std::io::Cursor<Vec<u8>>,
    }
    impl std::io::Write for Full {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if buf.len() > self.room {
                return Err(std::io::Error::other("no space left"));
            }
            self.room -= buf.len();
            self.inner.write(buf)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    impl std::io::Seek for Full {
        fn seek(&mut self, to: std::io::SeekFrom) -> std::io::Result<u64> {
            self.inner.seek(to)
        }
    }
    let m = figure_27();
    let whole = m.to_bytes();
    for room in [0, 10, whole.len() / 2, whole.len() - 1] {
        let mut out = Full {
            room,
            inner: std::io::Cursor::new(Vec::new()),
        };
        let e = ilmr_vm::bytecode::file::write(&m, &mut out).expect_err("the disk is full");
        assert!(e.to_string().contains("no space left"), "{room}: {e}");
    }
    let mut out = Full {
        room: usize::MAX,
        inner: std::io::Cursor::new(Vec::new()),
    };
    let len = ilmr_vm::bytecode::file::write(&m, &mut out).expect("written");
    assert_eq!(len as usize, whole.len());
    assert_eq!(out.inner.into_inner(), whole);
}
