//! The `[[fault]]` entries of a world file:
//!
//! ```toml
//! [[fault]]
//! kind = "obstacle_appears"   # one of faults::KIND_NAMES
//! start = 6.0                 # s, default 0
//! duration = 4.0              # s, default: to the end of the run
//! distance = 1.5              # obstacle_appears: gap ahead of the robot's front, m
//! radius = 0.25               # obstacle_appears: m
//! # slip = 0.3                # odometry_slip: 0 < slip <= 0.9
//! # bias = 0.05               # odometry_bias: -0.5..0.5
//! # actuator = "brake"        # actuator_dead: `drive` (default) or a model actuator
//! ```
//!
//! The world's checker turns each into a [`FaultSpec`] with [`spec`], and
//! reports a fault at the key it names, like every other entry.

use super::{FaultKind, FaultSpec, KIND_NAMES};
use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaultDef {
    pub kind: String,
    #[serde(default)]
    pub start: f64,
    pub duration: Option<f64>,
    pub slip: Option<f64>,
    pub bias: Option<f64>,
    pub actuator: Option<String>,
    pub distance: Option<f64>,
    pub radius: Option<f64>,
}

/// The spec an entry describes, or the key at fault and what is wrong with it.
pub fn spec(def: &FaultDef) -> Result<FaultSpec, (&'static str, String)> {
    let mut kind = FaultKind::named(&def.kind).ok_or_else(|| {
        (
            "kind",
            format!(
                "unknown fault `{}`, expected one of {}",
                def.kind,
                KIND_NAMES.join(", ")
            ),
        )
    })?;
    let given: [(&'static str, bool); 5] = [
        ("slip", def.slip.is_some()),
        ("bias", def.bias.is_some()),
        ("actuator", def.actuator.is_some()),
        ("distance", def.distance.is_some()),
        ("radius", def.radius.is_some()),
    ];
    let takes: &[&str] = match &mut kind {
        FaultKind::OdometrySlip { slip } => {
            *slip = def.slip.unwrap_or(*slip);
            &["slip"]
        }
        FaultKind::OdometryBias { bias } => {
            *bias = def.bias.unwrap_or(*bias);
            &["bias"]
        }
        FaultKind::ActuatorDead { actuator } => {
            if let Some(a) = &def.actuator {
                a.clone_into(actuator);
            }
            &["actuator"]
        }
        FaultKind::ObstacleAppears { distance, radius } => {
            *distance = def.distance.unwrap_or(*distance);
            *radius = def.radius.unwrap_or(*radius);
            &["distance", "radius"]
        }
        _ => &[],
    };
    if let Some((key, _)) = given.iter().find(|(k, set)| *set && !takes.contains(k)) {
        return Err((key, format!("`{}` takes no `{key}`", def.kind)));
    }
    let spec = FaultSpec::new(kind, def.start, def.duration);
    spec.check().map_err(|m| (key_of(&m), m))?;
    Ok(spec)
}

/// Every check message starts with the name of the value it is about.
fn key_of(message: &str) -> &'static str {
    [
        "start", "duration", "slip", "bias", "actuator", "distance", "radius",
    ]
    .into_iter()
    .find(|k| message.starts_with(k))
    .unwrap_or("kind")
}
