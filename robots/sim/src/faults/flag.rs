//! `--fault KIND[@START[+DURATION]][:PARAM]`, as `ilmrc run` takes it:
//! `scanner_dropout@5+3`, `odometry_slip@2:0.4`, `actuator_dead@4+2:brake`,
//! `obstacle_appears@6:1.2`. Without `@` the fault starts at 0; without `+` it
//! lasts to the end of the run. PARAM is the slip, the bias, the actuator's
//! name or the obstacle's distance ahead of the robot, by kind.

use super::{FaultKind, FaultSpec, KIND_NAMES};

/// Parses one flag value; the error says what is wrong and what was expected.
pub fn parse(text: &str) -> Result<FaultSpec, String> {
    let (head, param) = match text.split_once(':') {
        Some((h, p)) => (h, Some(p.trim())),
        None => (text, None),
    };
    let (name, when) = match head.split_once('@') {
        Some((n, w)) => (n.trim(), Some(w.trim())),
        None => (head.trim(), None),
    };
    let mut kind = FaultKind::named(&name.to_ascii_lowercase()).ok_or_else(|| {
        format!(
            "unknown fault `{name}`; expected one of {}",
            KIND_NAMES.join(", ")
        )
    })?;
    let (start, duration) = match when {
        None => (0.0, None),
        Some(w) => match w.split_once('+') {
            Some((s, d)) => (seconds(s, "start")?, Some(seconds(d, "duration")?)),
            None => (seconds(w, "start")?, None),
        },
    };
    if let Some(p) = param {
        set_param(&mut kind, p)?;
    }
    let spec = FaultSpec::new(kind, start, duration);
    spec.check().map_err(|e| format!("fault `{text}`: {e}"))?;
    Ok(spec)
}

fn seconds(text: &str, what: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .map_err(|_| format!("the {what} `{text}` is not a number of seconds"))
}

fn set_param(kind: &mut FaultKind, p: &str) -> Result<(), String> {
    let number = |what: &str| {
        p.parse::<f64>()
            .map_err(|_| format!("the {what} `{p}` is not a number"))
    };
    match kind {
        FaultKind::OdometrySlip { slip } => *slip = number("slip")?,
        FaultKind::OdometryBias { bias } => *bias = number("bias")?,
        FaultKind::ActuatorDead { actuator } => *actuator = p.to_string(),
        FaultKind::ObstacleAppears { distance, .. } => *distance = number("distance")?,
        other => return Err(format!("`{}` takes no parameter, got `:{p}`", other.name())),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_part_is_read() {
        let s = parse("odometry_slip@2.5+4:0.4").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            s,
            FaultSpec::new(FaultKind::OdometrySlip { slip: 0.4 }, 2.5, Some(4.0))
        );
        let s = parse("Scanner_Dropout").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s, FaultSpec::new(FaultKind::ScannerDropout, 0.0, None));
        let s = parse("actuator_dead@1:brake").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            s.kind,
            FaultKind::ActuatorDead {
                actuator: "brake".into()
            }
        );
        let s = parse("obstacle_appears@3").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            s.kind,
            FaultKind::ObstacleAppears {
                distance: super::super::DEFAULT_OBSTACLE_DISTANCE,
                radius: super::super::DEFAULT_OBSTACLE_RADIUS
            }
        );
    }

    #[test]
    fn display_reads_back() {
        for text in [
            "scanner_dropout@5+3",
            "odometry_bias@0:-0.1",
            "actuator_dead@4+2:brake",
            "obstacle_appears@6:1.2",
            "nav_frozen@1.5",
        ] {
            let s = parse(text).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(s.to_string(), text);
        }
    }

    #[test]
    fn bad_values_say_what_is_wrong() {
        let err = |t: &str| parse(t).err().unwrap_or_default();
        assert!(err("smoke").starts_with("unknown fault `smoke`; expected one of scanner_dropout"));
        assert_eq!(
            err("dead_battery@x"),
            "the start `x` is not a number of seconds"
        );
        assert_eq!(
            err("dead_battery@1+0"),
            "fault `dead_battery@1+0`: duration must be a positive time, got 0"
        );
        assert_eq!(
            err("dead_battery@-1"),
            "fault `dead_battery@-1`: start must be a time of 0 s or later, got -1"
        );
        assert_eq!(
            err("dead_battery:3"),
            "`dead_battery` takes no parameter, got `:3`"
        );
        assert_eq!(
            err("odometry_slip:1.5"),
            "fault `odometry_slip:1.5`: slip must be above 0 and at most 0.9, got 1.5"
        );
        assert_eq!(
            err("obstacle_appears:far"),
            "the distance `far` is not a number"
        );
    }
}
