//! Time sources. The VM's time is logical (tick count times the period), so runs are
//! deterministic; a clock only decides how fast ticks follow each other in wall time.

use std::time::{Duration, Instant};

pub trait Clock {
    /// Called at the start of tick `tick`; may wait until that tick is due.
    fn begin_tick(&mut self, tick: u64, period: f64);
}

/// Runs ticks as fast as possible.
#[derive(Debug, Clone, Copy, Default)]
pub struct SimClock;

impl Clock for SimClock {
    fn begin_tick(&mut self, _tick: u64, _period: f64) {}
}

/// How late ticks started compared with their schedule.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Jitter {
    pub ticks: u64,
    /// Seconds.
    pub max_late: f64,
    pub total_late: f64,
    /// Ticks that started a whole period or more late.
    pub missed: u64,
}

impl Jitter {
    pub fn mean_late(&self) -> f64 {
        if self.ticks == 0 {
            0.0
        } else {
            self.total_late / self.ticks as f64
        }
    }
}

/// Keeps the period in wall time: tick `n` starts at `start + n * period`.
#[derive(Debug, Clone)]
pub struct RealClock {
    start: Option<Instant>,
    jitter: Jitter,
}

impl Default for RealClock {
    fn default() -> Self {
        Self::new()
    }
}

impl RealClock {
    pub fn new() -> RealClock {
        RealClock {
            start: None,
            jitter: Jitter::default(),
        }
    }

    pub fn jitter(&self) -> Jitter {
        self.jitter
    }
}

impl Clock for RealClock {
    fn begin_tick(&mut self, tick: u64, period: f64) {
        let start = *self.start.get_or_insert_with(Instant::now);
        let due = start + Duration::from_secs_f64((tick as f64 * period).max(0.0));
        let now = Instant::now();
        if now < due {
            std::thread::sleep(due - now);
        }
        let late = Instant::now().saturating_duration_since(due).as_secs_f64();
        self.jitter.ticks += 1;
        self.jitter.total_late += late;
        self.jitter.max_late = self.jitter.max_late.max(late);
        if late >= period {
            self.jitter.missed += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_real_clock_keeps_the_period_and_records_lateness() {
        let mut clock = RealClock::new();
        let start = Instant::now();
        for tick in 0..5 {
            clock.begin_tick(tick, 0.01);
        }
        assert!(start.elapsed() >= Duration::from_millis(40));
        let j = clock.jitter();
        assert_eq!(j.ticks, 5);
        assert!(j.max_late >= 0.0 && j.mean_late() <= j.max_late);
    }
}
