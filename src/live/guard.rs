//! What keeps one bad line from taking the robot down: the threads that compile ILMR
//! text (the engine's, for every line, and the one that compiles `--task`) get the
//! stack the compiler's nesting limits need (`ilmr_compiler::limits::COMPILER_STACK`),
//! and a panic while a line is compiled or joined becomes that line's error.

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind};

use ilmr_compiler::limits::COMPILER_STACK;

/// Runs `f`; a panic comes back as a message saying what was being done, which is
/// also logged on stderr (after the panic's own report, with its location).
pub fn guarded<T>(doing: &str, f: impl FnOnce() -> T) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        let message = format!(
            "ilmrc failed while {doing} ({}); the robot goes on. This is a bug in ilmrc: \
             please report the line",
            panic_text(payload.as_ref())
        );
        eprintln!("error: {message}");
        message
    })
}

/// Runs `f` on a thread of its own with [`COMPILER_STACK`] of stack and waits
/// for it; a panic comes back as a message, as from [`guarded`].
pub fn on_compiler_stack<T: Send>(doing: &str, f: impl FnOnce() -> T + Send) -> Result<T, String> {
    std::thread::scope(|s| {
        let worker = std::thread::Builder::new()
            .name("ilmr-compile".into())
            .stack_size(COMPILER_STACK)
            .spawn_scoped(s, || guarded(doing, f))
            .map_err(|e| format!("cannot start a thread for {doing}: {e}"))?;
        worker
            .join()
            .unwrap_or_else(|p| Err(format!("{doing}: {}", panic_text(p.as_ref()))))
    })
}

fn panic_text(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_a_message_that_says_what_was_done() {
        let r: Result<(), String> = guarded("compiling the line", || panic!("boom {}", 7));
        let e = r.err().unwrap_or_default();
        assert!(
            e.starts_with("ilmrc failed while compiling the line (boom 7);"),
            "{e}"
        );
        assert_eq!(guarded("x", || 5), Ok(5));
    }

    #[test]
    fn the_compiler_thread_has_its_stack_and_returns_its_value() {
        // At least 4 MiB of locals: twice what a default thread (2 MiB) has.
        fn deep(n: u32) -> u32 {
            let pad = std::hint::black_box([1u8; 4096]);
            if n == 0 {
                0
            } else {
                deep(n - 1) + u32::from(pad[n as usize % 4096])
            }
        }
        assert_eq!(on_compiler_stack("recursing", || deep(1024)), Ok(1024));
        let r: Result<(), String> = on_compiler_stack("panicking", || panic!("inner"));
        assert!(r.is_err_and(|e| e.contains("panicking (inner)")));
    }
}
