//! The robot model's constants (`[PARAMETERS]` with their documented defaults,
//! `[IDENTIFIERS]`, `[COLORS]`), indexed once per check: every name in every expression
//! is looked up here.

use ilmr_model::{PARAMETER_SPECS, RobotModel};
use rustc_hash::FxHashMap;

#[derive(Debug, Default)]
pub struct Constants {
    values: FxHashMap<String, f64>,
}

/// Lower-cases `name` into `buf` (reused, so a lookup allocates nothing).
pub fn key<'b>(name: &str, buf: &'b mut String) -> &'b str {
    buf.clear();
    if name.is_ascii() {
        buf.push_str(name);
        buf.make_ascii_lowercase();
    } else {
        buf.extend(name.chars().flat_map(char::to_lowercase));
    }
    buf
}

impl Constants {
    pub fn new(model: &RobotModel) -> Constants {
        let mut values = FxHashMap::default();
        let mut buf = String::new();
        // Later inserts lose: parameters come before identifiers, identifiers before
        // colours, the same precedence as the lookups they replace.
        let params = PARAMETER_SPECS
            .iter()
            .map(|s| s.name)
            .chain(model.parameters.iter().map(|p| p.name.as_str()));
        for name in params {
            if let Some(v) = model.parameter_or_default(name) {
                values.entry(key(name, &mut buf).to_string()).or_insert(v);
            }
        }
        for entry in model.identifiers.iter().chain(&model.colors) {
            values
                .entry(key(&entry.name, &mut buf).to_string())
                .or_insert(entry.value);
        }
        Constants { values }
    }

    pub fn get(&self, name: &str, buf: &mut String) -> Option<f64> {
        self.values.get(key(name, buf)).copied()
    }
}
