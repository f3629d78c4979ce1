//! The one angle wrap: every heading of a pose, a bearing or a turn is folded into
//! (-pi, pi] by [`wrap_angle`].

use std::f64::consts::{PI, TAU};

/// An angle folded into (-pi, pi].
///
/// An angle already in range comes back bit for bit (folding through
/// `rem_euclid` would round a small negative angle to the spacing of values near
/// 2 pi), so wrapping a wrapped heading again changes nothing. -pi becomes pi,
/// -0.0 stays -0.0, and a non-finite angle (NaN, an infinity) comes back as it
/// came: it has no direction to fold, and its caller's finiteness check sees it.
pub fn wrap_angle(a: f64) -> f64 {
    if (a > -PI && a <= PI) || !a.is_finite() {
        return a;
    }
    let r = a.rem_euclid(TAU);
    if r > PI { r - TAU } else { r }
}

/// Signed smallest rotation that takes heading `from` to heading `to`.
pub fn angle_diff(to: f64, from: f64) -> f64 {
    wrap_angle(to - from)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_in_range_come_back_bit_for_bit() {
        for a in [PI, -PI + 1e-15, -1e-300, -0.1, -3.0, 0.1, 3.0, 1e-300] {
            assert_eq!(wrap_angle(a).to_bits(), a.to_bits(), "{a}");
        }
        assert_eq!(wrap_angle(-0.0).to_bits(), (-0.0f64).to_bits());
        assert_eq!(wrap_angle(0.0).to_bits(), 0.0f64.to_bits());
    }

    #[test]
    fn the_range_is_half_open_at_minus_pi() {
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
        assert_eq!(wrap_angle(3.0 * PI), PI);
        assert_eq!(wrap_angle(-3.0 * PI), PI);
    }

    #[test]
    fn multiples_of_a_turn_fold_to_zero() {
        // Whole turns that are exact in binary fold to exactly zero; others (5 TAU
        // is not 5 times TAU once rounded) to within their rounding.
        for k in [1.0, 2.0, 4.0, -1.0, -2.0, -8.0] {
            assert_eq!(wrap_angle(k * TAU), 0.0, "{k} turns");
        }
        for k in [3.0, -5.0, 1000.0] {
            assert!(wrap_angle(k * TAU).abs() < 1e-12, "{k} turns");
        }
    }

    #[test]
    fn angles_out_of_range_fold_by_whole_turns() {
        assert!((wrap_angle(1.5 * PI) + 0.5 * PI).abs() < 1e-12);
        assert!((wrap_angle(7.0) - (7.0 - TAU)).abs() < 1e-12);
        assert!((wrap_angle(-5.0 * TAU + 0.25) - 0.25).abs() < 1e-9);
        assert!((wrap_angle(-4.0) - (TAU - 4.0)).abs() < 1e-12);
        for a in [-100.0, -7.0, -PI, 4.0, 1e6] {
            let w = wrap_angle(a);
            assert!(w > -PI && w <= PI, "{a} -> {w}");
        }
    }

    #[test]
    fn non_finite_angles_pass_through() {
        assert!(wrap_angle(f64::NAN).is_nan());
        assert_eq!(wrap_angle(f64::INFINITY), f64::INFINITY);
        assert_eq!(wrap_angle(f64::NEG_INFINITY), f64::NEG_INFINITY);
    }

    #[test]
    fn angle_diff_takes_the_short_way_round() {
        let d = angle_diff((-170.0f64).to_radians(), 170.0f64.to_radians());
        assert!((d - 20.0f64.to_radians()).abs() < 1e-12);
        assert_eq!(angle_diff(0.5, 0.5), 0.0);
    }
}
