//! Bounds on the numbers of a ROBO.INI that are not parameters: device
//! fields, colours, identifiers and parameters the ILMR tools do not know.
//! Known parameters have their own ranges in `params`. Each bound keeps a
//! model from making a tool allocate or loop in proportion to a number in it
//! (issue 12: a scanner of a hundred million readings hung the simulator).

/// Device ids stay below 2^31 so that they convert to `f64` exactly and fit
/// the intermediate process's integer messages.
pub const MAX_DEVICE_ID: i64 = i32::MAX as i64;

/// Most readings one device delivers at a time. Scanners of the kind the
/// dissertation's robots carry give 181-1141 (SICK LMS 291: 361); the
/// simulator casts a beam and the trace stores a number per reading.
pub const MAX_READINGS: u32 = 4096;

/// Most entries one section holds (devices, objects, colours, identifiers,
/// parameters): the simulated robot reads every device each tick and the
/// recognisers try every object on each scan. The shipped robots have 7 to
/// 14 devices and at most 33 parameters.
pub const MAX_SECTION_ENTRIES: usize = 1024;

/// Largest magnitude of a device's minimum and maximum reading, of a colour
/// or identifier value, and of a parameter the tools do not know: far past
/// any reading in device units (the scanner reads 0..30000 mm), and small
/// enough that arithmetic on it stays exact to the millimetre.
pub const MAX_MAGNITUDE: f64 = 1e9;

/// A number as a message quotes it: as written when short, in exponent form
/// when `{}` would print hundreds of digits (`1e308`).
pub(crate) fn shown(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-6..1e9).contains(&a) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

/// `name: value out of range (expected ...)`, the form of every range
/// message of a model.
pub(crate) fn out_of_range(name: &str, value: &str, expected: &str) -> String {
    format!("{name}: {value} out of range (expected {expected})")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_and_tiny_numbers_are_shown_short() {
        assert_eq!(shown(1e308), "1e308");
        assert_eq!(shown(-2.5e12), "-2.5e12");
        assert_eq!(shown(1e-9), "1e-9");
        assert_eq!(shown(0.2), "0.2");
        assert_eq!(shown(30000.0), "30000");
        assert_eq!(shown(0.0), "0");
    }
}
