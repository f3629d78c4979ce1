//! What an experiment's runs cost on this machine: the simulated seconds the harness
//! ticked on this thread and the thread's CPU time, for a real-time factor. The
//! binary prints them; the report never holds them, because the report must be the
//! same on every machine and CPU time is not.

use std::cell::Cell;
use std::time::Duration;

thread_local! {
    /// Simulated seconds ticked on this thread so far. Per thread, because
    /// `run_all` runs the experiments side by side and each is measured alone.
    static SIMULATED: Cell<f64> = const { Cell::new(0.0) };
}

/// Counts one tick of `period` seconds (the harness calls this on every tick).
pub(crate) fn ticked(period: f64) {
    SIMULATED.with(|s| s.set(s.get() + period));
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cost {
    /// Simulated seconds, summed over the runs.
    pub simulated: f64,
    /// CPU time of the thread that ran them; `None` where the platform has no
    /// per-thread clock.
    pub cpu: Option<Duration>,
}

impl Cost {
    /// Simulated seconds per CPU second.
    pub fn real_time_factor(&self) -> Option<f64> {
        self.cpu
            .map(|c| c.as_secs_f64())
            .filter(|&c| c > 0.0)
            .map(|c| self.simulated / c)
    }
}

/// `f` run on this thread, and what it cost.
pub fn measure<T>(f: impl FnOnce() -> T) -> (T, Cost) {
    let simulated = SIMULATED.with(Cell::get);
    let cpu = thread_cpu();
    let out = f();
    let cost = Cost {
        simulated: SIMULATED.with(Cell::get) - simulated,
        cpu: cpu.zip(thread_cpu()).map(|(a, b)| b.saturating_sub(a)),
    };
    (out, cost)
}

#[cfg(unix)]
fn thread_cpu() -> Option<Duration> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec for the call's duration.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    (rc == 0).then(|| Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32))
}

#[cfg(not(unix))]
fn thread_cpu() -> Option<Duration> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_only_what_ran_inside_and_on_this_thread() {
        ticked(1.0);
        let ((), cost) = measure(|| {
            ticked(0.01);
            ticked(0.01);
            std::thread::spawn(|| ticked(5.0)).join().expect("joined");
            // Busy enough for a clock with coarse steps to move.
            let mut x = 0u64;
            for i in 0..2_000_000u64 {
                x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(i));
            }
        });
        assert!((cost.simulated - 0.02).abs() < 1e-12, "{cost:?}");
        if cfg!(unix) {
            let cpu = cost.cpu.expect("a thread clock on unix");
            assert!(cpu > Duration::ZERO, "{cost:?}");
            assert!(cost.real_time_factor().is_some());
        }
    }
}
