//! Finding things in a model by name, ignoring case.

use std::sync::LazyLock;

use crate::model::{Device, ModelName, NamedValue, Object, RobotModel};

/// The sensor every robot has without declaring it: the VM's supervisor, read as
/// `Fault = sensor(supervisor)`. Its value is the number of the most urgent active
/// fault, 0 when all is well (`docs/reliability.md`).
pub const SUPERVISOR: &str = "supervisor";

/// How many fault numbers the supervisor reads out (its largest value).
pub const SUPERVISOR_FAULTS: u32 = 8;

/// Id -1: it has no number, so `sensor(n)` never names it by accident.
static SUPERVISOR_DEVICE: LazyLock<Device> = LazyLock::new(|| Device {
    name: SUPERVISOR.to_string(),
    id: -1,
    min: 0.0,
    max: f64::from(SUPERVISOR_FAULTS),
    readings: 1,
    line: 0,
});

/// ILMR names are case-insensitive (`LowBattery` is `lowbattery`). Full
/// Unicode lowercasing so that Finnish names (`Ä`, `ö`) compare too.
pub(crate) fn same_name(a: &str, b: &str) -> bool {
    a.eq_ignore_ascii_case(b)
        || (!a.is_ascii() || !b.is_ascii())
            && a.chars()
                .flat_map(char::to_lowercase)
                .eq(b.chars().flat_map(char::to_lowercase))
}

/// The key two names share exactly when `same_name` holds (char-wise
/// lowercasing, unlike `str::to_lowercase`, which special-cases a final
/// sigma).
pub(crate) fn fold(name: &str) -> String {
    name.chars().flat_map(char::to_lowercase).collect()
}

/// A name usable from ILMR: a letter, then letters, digits or `_`
/// (`side_edge`, `max_time_to_search`, `leg1`).
pub(crate) fn is_valid_name(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(char::is_alphabetic) && chars.all(|c| c.is_alphanumeric() || c == '_')
}

fn find_value<'a>(values: &'a [NamedValue], name: &str) -> Option<&'a NamedValue> {
    values.iter().find(|v| same_name(&v.name, name))
}

impl RobotModel {
    /// A sensor or actuator by name. `supervisor` is found in every model (the file's
    /// own entry wins if it has one) but is not among `devices` or `names`, so it is
    /// never written back nor listed as hardware.
    pub fn device(&self, name: &str) -> Option<&Device> {
        self.devices
            .iter()
            .find(|d| same_name(&d.name, name))
            .or_else(|| same_name(SUPERVISOR, name).then(|| &*SUPERVISOR_DEVICE))
    }

    /// A sensor or actuator by its integer id (`sensor(1,0)`).
    pub fn device_by_id(&self, id: i64) -> Option<&Device> {
        self.devices.iter().find(|d| d.id == id)
    }

    /// A recognisable object by name.
    pub fn object(&self, name: &str) -> Option<&Object> {
        self.objects.iter().find(|o| same_name(&o.name, name))
    }

    /// A colour's value by name.
    pub fn color(&self, name: &str) -> Option<f64> {
        find_value(&self.colors, name).map(|v| v.value)
    }

    /// An identifier's value by name (`odo` is 4 in Figure 39).
    pub fn identifier(&self, name: &str) -> Option<f64> {
        find_value(&self.identifiers, name).map(|v| v.value)
    }

    /// A parameter's value, only if the model itself defines it. For the
    /// documented fallback of a known parameter use
    /// [`RobotModel::parameter_or_default`] or the typed accessors.
    pub fn parameter(&self, name: &str) -> Option<f64> {
        find_value(&self.parameters, name).map(|v| v.value)
    }

    /// What a name stands for, looked up in the order devices, objects,
    /// colors, identifiers, parameters: the first section that has it wins,
    /// so `scanner` on Workpartner is the device, not the identifier.
    pub fn lookup(&self, name: &str) -> Option<ModelName<'_>> {
        self.names()
            .find(|(n, _)| same_name(n, name))
            .map(|(_, m)| m)
    }

    /// Every name in the model, in lookup order and file order within a
    /// section. A name in two sections appears twice.
    pub fn names(&self) -> impl Iterator<Item = (&str, ModelName<'_>)> {
        let devices = self.devices.iter().map(ModelName::Device);
        let objects = self.objects.iter().map(ModelName::Object);
        let colors = self.colors.iter().map(ModelName::Color);
        let identifiers = self.identifiers.iter().map(ModelName::Identifier);
        let parameters = self.parameters.iter().map(ModelName::Parameter);
        devices
            .chain(objects)
            .chain(colors)
            .chain(identifiers)
            .chain(parameters)
            .map(|m| (m.name(), m))
    }

    /// The model's names closest to `name` (case-insensitive edit distance, a swap of neighbours counting as one edit),
    /// best first, for "did you mean" hints. At most `limit` names; only
    /// names within a third of their length in edits.
    pub fn similar_names(&self, name: &str, limit: usize) -> Vec<&str> {
        let wanted = fold(name);
        let mut scored: Vec<(usize, usize, &str)> = self
            .names()
            .enumerate()
            .filter_map(|(order, (n, _))| {
                let distance = strsim::osa_distance(&wanted, &fold(n));
                let allowed = (n.chars().count().max(wanted.chars().count()) / 3).max(1);
                (distance <= allowed).then_some((distance, order, n))
            })
            .collect();
        scored.sort_by_key(|&(distance, order, _)| (distance, order));
        let mut out: Vec<&str> = Vec::new();
        for (_, _, n) in scored {
            if !out.iter().any(|o| same_name(o, n)) {
                out.push(n);
            }
            if out.len() == limit {
                break;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_compare_without_case_including_finnish() {
        assert!(same_name("LowBattery", "lowbattery"));
        assert!(same_name("Äänitin", "äänitin"));
        assert!(!same_name("leg1", "leg2"));
        assert!(!same_name("odo", "odom"));
    }

    #[test]
    fn every_model_has_the_supervisor_but_does_not_list_it() {
        let m = RobotModel::parse("[PARAMETERS]\nmax_speed 1\n", "bare").0;
        let d = m.device("Supervisor").expect("virtual device");
        assert_eq!((d.min, d.max, d.readings), (0.0, 8.0, 1));
        assert!(m.devices.iter().all(|d| !same_name(&d.name, SUPERVISOR)));
        assert!(m.lookup(SUPERVISOR).is_none(), "not hardware to list");
        assert!(m.device_by_id(-1).is_none());
    }

    #[test]
    fn valid_names_start_with_a_letter() {
        for ok in ["scanner", "side_edge", "leg1", "LowBattery", "ääni"] {
            assert!(is_valid_name(ok), "{ok}");
        }
        for bad in ["", "1leg", "_x", "max-speed", "a.b", "x;"] {
            assert!(!is_valid_name(bad), "{bad}");
        }
    }
}
