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
        // The file's values first; then the documented default of every known parameter
        // the file lacks; then identifiers and colours. An earlier entry wins, the same
        // precedence as `parameter_or_default`, identifier, colour. (Asking the model
        // `parameter_or_default` for every known name scans its lists each time: that
        // was three quarters of the cost of an interactive line.)
        for p in &model.parameters {
            values
                .entry(key(&p.name, &mut buf).to_string())
                .or_insert(p.value);
        }
        for spec in PARAMETER_SPECS {
            if !values.contains_key(key(spec.name, &mut buf)) {
                if let Some(v) = model.parameter_or_default(spec.name) {
                    values.insert(buf.clone(), v);
                }
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
