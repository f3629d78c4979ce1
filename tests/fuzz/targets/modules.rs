//! `.ilmb` files through `Module::from_bytes` (what `ilmrc disasm` does with a file
//! from anywhere), the disassembler and, when a module validates, the VM: a module
//! that passes validation must run without a panic.

use ilmr_compiler::check::Source;
use ilmr_vm::Module;
use ilmr_vm::bytecode::{ModuleError, disassemble};

use super::corpus::{self, ROBOTS};
use crate::engine::{self, Budget, Rng, Stats};
use crate::{mutate, pipeline};

/// Every corpus task that lowers, on either robot, as module bytes.
pub fn modules() -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for robot in ROBOTS {
        let model = corpus::model(robot);
        for task in corpus::tasks() {
            let mut sources = vec![Source::new("task.ilmr", String::from_utf8_lossy(task))];
            sources.extend(corpus::library().iter().cloned());
            if let Some(module) = pipeline::compile(&sources, &model) {
                out.push(module.to_bytes());
            }
        }
    }
    out
}

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = modules();
    engine::run(
        "module",
        &corpus,
        budget,
        |base, rng: &mut Rng| {
            // Structure-aware: a node of the module's JSON form changes and the module
            // is written again as a file, so that the change reaches the validator
            // rather than the checksum.
            let as_json = Module::from_bytes(base)
                .ok()
                .and_then(|m| serde_json::to_vec(&m).ok());
            if let Some(json) = as_json.filter(|_| rng.chance(90)) {
                let changed = mutate::json(&json, rng);
                if let Ok(m) = serde_json::from_slice::<Module>(&changed) {
                    return m.to_bytes();
                }
            }
            let mut bytes = mutate::bytes(base.to_vec(), rng);
            if rng.chance(50) {
                ilmr_vm::bytecode::file::reseal(&mut bytes);
            }
            bytes
        },
        feed,
    )
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/module.rs`):
/// the bytes as they are, then framed again (see [`reframe`]).
pub fn feed(input: &[u8]) {
    load_and_run(input);
    if let Some(framed) = reframe(input).filter(|f| f != input) {
        load_and_run(&framed);
    }
}

fn load_and_run(input: &[u8]) {
    let module = match Module::from_bytes(input) {
        Ok(m) => m,
        Err(e) => {
            assert!(!e.to_string().is_empty());
            return;
        }
    };
    let listing = disassemble(&module);
    assert!(module.code.is_empty() || !listing.is_empty());
    let Some(mut vm) = pipeline::vm(module) else {
        panic!("Vm::new refused a module that from_bytes accepted");
    };
    for _ in 0..pipeline::TICKS {
        vm.tick();
    }
}

/// `bytes` with the payload's length and the checksum set to what the bytes hold, when
/// they start like a module. A mutation inside the tables (AFL++ knows nothing of the
/// format) would otherwise fail the length or checksum test, and never reach the
/// tables' decoder or the validator.
pub fn reframe(bytes: &[u8]) -> Option<Vec<u8>> {
    const VERSION_END: usize = ilmr_vm::bytecode::file::MAGIC.len() + 4;
    if !bytes.starts_with(&ilmr_vm::bytecode::file::MAGIC) {
        return None;
    }
    let name = usize::from(*bytes.get(VERSION_END)?);
    let length_at = VERSION_END + 1 + name;
    let payload = bytes.len().checked_sub(length_at + 8 + 4)?;
    let mut framed = bytes.to_vec();
    framed[length_at..length_at + 8].copy_from_slice(&(payload as u64).to_le_bytes());
    ilmr_vm::bytecode::file::reseal(&mut framed);
    Some(framed)
}

/// Hand-made bad modules: each is refused with the error that names the problem.
pub fn errors_are_clear() {
    let good = corpus::live_module("workpartner");
    let encode = |m: &Module| m.to_bytes();
    let refuse = |bytes: &[u8]| match Module::from_bytes(bytes) {
        Ok(_) => panic!("accepted {}", String::from_utf8_lossy(bytes)),
        Err(e) => e,
    };

    assert!(matches!(refuse(b""), ModuleError::NotModule));
    assert!(matches!(refuse(b"\xff\xfe"), ModuleError::NotModule));
    assert!(matches!(
        refuse(br#"{"header":{"magic":"ILMX","version":1}}"#),
        ModuleError::NotModule
    ));
    assert!(matches!(
        refuse(br#"{"header":{"magic":"ILMB","version":1}}"#),
        ModuleError::Version { found: 1, .. }
    ));
    let mut newer = encode(&good);
    newer[8..12].copy_from_slice(&99u32.to_le_bytes());
    assert!(matches!(
        refuse(&newer),
        ModuleError::Version { found: 99, .. }
    ));
    let whole = encode(&good);
    assert!(matches!(
        refuse(&whole[..whole.len() - 1]),
        ModuleError::Length { .. }
    ));
    let mut damaged = whole.clone();
    damaged[whole.len() - 5] ^= 0x40;
    assert!(matches!(refuse(&damaged), ModuleError::Checksum { .. }));

    let mut m = good.clone();
    m.main = ilmr_vm::bytecode::UnitId(m.units.len() as u32);
    assert!(matches!(
        refuse(&encode(&m)),
        ModuleError::Index {
            what: "main unit",
            ..
        }
    ));

    let mut m = good.clone();
    if let Some(b) = m.blocks.first_mut() {
        b.len = u32::MAX;
    }
    let e = refuse(&encode(&m));
    assert!(e.to_string().contains("out of range"), "{e}");

    let mut m = good.clone();
    m.expr_code.clear();
    let e = refuse(&encode(&m));
    assert!(e.to_string().contains("expression"), "{e}");
}
