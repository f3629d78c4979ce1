//! How many seeds the statistical experiments run over. The report
//! (`cargo run --release -p ilmr-experiments`) always runs [`FULL`]; `cargo test`
//! runs the fast subset of [`FAST`] seeds unless [`ENV`] is `full`, so that CI
//! stays quick while the full set runs on demand:
//!
//! ```sh
//! ILMR_EXPERIMENTS=full cargo test --release -p ilmr-experiments
//! ```
//!
//! Every run `i` of an experiment uses seed `FIRST + i`, so the fast subset is the
//! first [`FAST`] runs of the full set, and both modes assert the same bounds.

/// Seeds of the full set (issue 15: at least 20).
pub const FULL: usize = 20;

/// Seeds of the fast subset `cargo test` runs by default.
pub const FAST: usize = 3;

/// The environment variable that asks the tests for the full set: `full`.
pub const ENV: &str = "ILMR_EXPERIMENTS";

/// The first seed; run `i` uses `FIRST + i` (apart from Test 1's seeds).
pub const FIRST: u64 = 1001;

/// Whether [`ENV`] asks for the full set.
pub fn full() -> bool {
    std::env::var(ENV).is_ok_and(|v| v == "full")
}

/// The seeds the tests run: [`FULL`] when [`full`], else [`FAST`].
pub fn for_tests() -> usize {
    if full() { FULL } else { FAST }
}

/// The first `n` seeds.
pub fn first(n: usize) -> impl Iterator<Item = u64> {
    (0..n as u64).map(|i| FIRST + i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fast_subset_is_the_start_of_the_full_set() {
        let fast: Vec<u64> = first(FAST).collect();
        let full: Vec<u64> = first(FULL).collect();
        assert_eq!(fast[..], full[..FAST]);
        const { assert!(FULL >= 20 && FAST < FULL) };
        assert_eq!(full.last(), Some(&(FIRST + FULL as u64 - 1)));
    }
}
