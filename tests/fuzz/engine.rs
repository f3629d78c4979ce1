//! The fuzzing loop: a seeded PRNG, a budget (fixed for CI, longer on request), and
//! a runner that feeds a target first its regression inputs and seed corpus, then
//! mutations, catching a panic and saving the input that caused it.
//!
//! Stable Rust has no coverage-guided engine without extra tooling (cargo-fuzz needs
//! nightly, afl.rs needs `cargo afl` and AFL++ built on the machine), so this is a
//! structure-aware mutational loop: it knows the inputs' shapes (lines, tokens,
//! commands, INI sections, JSON tables) and is deterministic for a given seed.

use ilmr_geometry::SplitMix64;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Runs a target where the tools compile: on a thread with the compiler's stack
/// (`ilmr_compiler::limits::COMPILER_STACK`; a test thread has 2 MiB, less than an
/// unoptimised compiler needs at its nesting limits).
pub fn on_compiler_stack<T: Send>(target: impl FnOnce() -> T + Send) -> T {
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(ilmr_compiler::limits::COMPILER_STACK)
            .spawn_scoped(s, target)
            .expect("start the target's thread")
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

/// SplitMix64 (ilmr-geometry's), so that a seed means the same input on every machine.
#[derive(Debug, Clone)]
pub struct Rng(SplitMix64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(SplitMix64::new(seed ^ 0x9E37_79B9_7F4A_7C15))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `0..n`; 0 when `n` is 0.
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next_u64() % n as u64) as usize
        }
    }

    pub fn chance(&mut self, percent: u64) -> bool {
        self.next_u64() % 100 < percent
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> Option<&'a T> {
        items.get(self.below(items.len()))
    }
}

/// How long each target runs. CI gets a fixed number of iterations; a person who
/// wants more sets `ILMR_FUZZ_SECS` (seconds per target) and, for a fresh sequence,
/// `ILMR_FUZZ_SEED`.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    pub seed: u64,
    pub iterations: u64,
    pub time: Option<Duration>,
}

impl Budget {
    /// `iterations` is the CI default for this target.
    pub fn from_env(iterations: u64) -> Budget {
        let seed = env_u64("ILMR_FUZZ_SEED").unwrap_or(0);
        match env_u64("ILMR_FUZZ_SECS") {
            Some(secs) => Budget {
                seed,
                iterations: u64::MAX,
                time: Some(Duration::from_secs(secs)),
            },
            None => Budget {
                seed,
                iterations: env_u64("ILMR_FUZZ_ITERS").unwrap_or(iterations),
                time: None,
            },
        }
    }
}

fn env_u64(name: &str) -> Option<u64> {
    let text = std::env::var(name).ok()?;
    match text.trim().parse() {
        Ok(v) => Some(v),
        Err(_) => panic!("{name}={text:?} is not a whole number"),
    }
}

/// What a run did, for the test's output and the report.
#[derive(Debug, Clone, Copy, Default)]
pub struct Stats {
    pub inputs: u64,
    pub corpus: usize,
    pub regressions: usize,
}

/// Runs `target` on every regression input of `name`, every corpus entry, then on
/// mutations of corpus entries (`mutate` makes one from a base and the rng) until the
/// budget is spent. A panic fails the test naming the seed, the iteration and a file
/// holding the input (under `target/fuzz-crashes/`); copying that file into
/// `tests/fuzz/regressions/NAME/` keeps it as a test case.
pub fn run<T, M, F>(name: &str, corpus: &[T], budget: Budget, mut mutate: M, target: F) -> Stats
where
    T: AsRef<[u8]>,
    M: FnMut(&[u8], &mut Rng) -> Vec<u8>,
    F: Fn(&[u8]),
{
    assert!(!corpus.is_empty(), "{name}: empty seed corpus");
    let regressions = regression_inputs(name);
    for (path, input) in &regressions {
        if let Err(message) = attempt(&target, input) {
            panic!(
                "{name}: regression input {} panics again: {message}",
                path.display()
            );
        }
    }
    for (i, input) in corpus.iter().enumerate() {
        if let Err(message) = attempt(&target, input.as_ref()) {
            let saved = save_crash(name, &format!("corpus-{i}"), input.as_ref());
            panic!("{name}: corpus entry {i} panics: {message}\n  input saved to {saved}");
        }
    }
    let mut rng = Rng::new(budget.seed ^ fnv(name));
    let started = Instant::now();
    let mut inputs = 0;
    while inputs < budget.iterations && budget.time.is_none_or(|t| started.elapsed() < t) {
        let base = corpus[rng.below(corpus.len())].as_ref();
        let input = mutate(base, &mut rng);
        if let Err(message) = attempt(&target, &input) {
            let saved = save_crash(name, &format!("seed{}-iter{inputs}", budget.seed), &input);
            panic!(
                "{name}: input {inputs} (ILMR_FUZZ_SEED={}) panics: {message}\n  input saved to {saved}",
                budget.seed
            );
        }
        inputs += 1;
    }
    let stats = Stats {
        inputs,
        corpus: corpus.len(),
        regressions: regressions.len(),
    };
    eprintln!(
        "fuzz {name}: {} regression, {} corpus, {} mutated inputs in {:.1} s",
        stats.regressions,
        stats.corpus,
        stats.inputs,
        started.elapsed().as_secs_f64()
    );
    stats
}

fn attempt<F: Fn(&[u8])>(target: &F, input: &[u8]) -> Result<(), String> {
    catch_unwind(AssertUnwindSafe(|| target(input))).map_err(|payload| {
        payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "a panic without a message".into())
    })
}

fn fnv(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The repository. This file is compiled into the root package's tests and into the
/// AFL++ targets' package, `fuzz/`, one level down.
pub fn root() -> PathBuf {
    let package = Path::new(env!("CARGO_MANIFEST_DIR"));
    match package.parent() {
        Some(up) if !package.join("tests/fuzz").is_dir() => up.to_path_buf(),
        _ => package.to_path_buf(),
    }
}

/// Inputs that once crashed a target, sorted by name so the order is fixed.
pub fn regression_inputs(name: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = root().join("tests/fuzz/regressions").join(name);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file())
        .collect();
    paths.sort();
    paths
        .into_iter()
        .filter_map(|p| std::fs::read(&p).ok().map(|bytes| (p, bytes)))
        .collect()
}

fn save_crash(name: &str, tag: &str, input: &[u8]) -> String {
    let target_dir = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("target"));
    let dir = target_dir.join("fuzz-crashes");
    let path = dir.join(format!("{name}-{tag}"));
    match std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&path, input)) {
        Ok(()) => path.display().to_string(),
        Err(e) => format!("(not saved: {e}) {:?}", String::from_utf8_lossy(input)),
    }
}

/// Reads every file under `dir` (relative to the repository) whose name ends with one
/// of `exts`, sorted by path.
pub fn files(dir: &str, exts: &[&str]) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    collect(&root().join(dir), exts, &mut out);
    out.sort();
    out
}

fn collect(dir: &Path, exts: &[&str], out: &mut Vec<(String, Vec<u8>)>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(&path, exts, out);
        } else if exts
            .iter()
            .any(|e| path.extension().is_some_and(|x| x == *e))
            && let Ok(bytes) = std::fs::read(&path)
        {
            out.push((path.display().to_string(), bytes));
        }
    }
}
