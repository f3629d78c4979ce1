//! The statistics an experiment reports over its seeds: the mean with a 95 %
//! confidence interval, and the range the runs spread over.

/// Student's t at 97.5 % for 1..=30 degrees of freedom (two-sided 95 %).
const T975: [f64; 30] = [
    12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
    2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
    2.052, 2.048, 2.045, 2.042,
];

/// t at 97.5 % for `df` degrees of freedom; beyond the table, the few points
/// between 30 and the normal's 1.96 (conservatively the smaller df's value).
pub fn t975(df: usize) -> f64 {
    match df {
        0 => f64::INFINITY,
        1..=30 => T975[df - 1],
        31..=40 => 2.042,
        41..=60 => 2.021,
        61..=120 => 2.000,
        _ => 1.980,
    }
}

/// A quantity measured once per seed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spread {
    pub n: usize,
    pub mean: f64,
    /// The 95 % confidence interval of the mean (Student's t).
    pub lo: f64,
    pub hi: f64,
    pub min: f64,
    /// The worst (largest) of the runs.
    pub max: f64,
}

impl Spread {
    pub fn of(xs: &[f64]) -> Spread {
        let n = xs.len();
        let (mean, std) = crate::harness::mean_std(xs);
        let half = if n > 1 {
            t975(n - 1) * std / (n as f64).sqrt()
        } else {
            f64::INFINITY
        };
        Spread {
            n,
            mean,
            lo: mean - half,
            hi: mean + half,
            min: xs.iter().copied().fold(f64::INFINITY, f64::min),
            max: xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        }
    }

    /// How far the mean is from `target`, relative to it.
    pub fn relative_error(&self, target: f64) -> f64 {
        (self.mean - target) / target
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_of_known_numbers() {
        let s = Spread::of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(s.mean, 2.5);
        // std = sqrt(5/3); t(3) = 3.182.
        let half = 3.182 * (5.0f64 / 3.0).sqrt() / 2.0;
        assert!((s.hi - 2.5 - half).abs() < 1e-12 && (2.5 - s.lo - half).abs() < 1e-12);
        assert_eq!((s.min, s.max), (1.0, 4.0));
        assert!((s.relative_error(2.0) - 0.25).abs() < 1e-12);
        assert_eq!(t975(19), 2.093);
        assert!(t975(500) < t975(100) && t975(100) < t975(50));
    }
}
