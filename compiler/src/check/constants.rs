//! The robot model's constants (`[PARAMETERS]` with their documented defaults,
//! `[IDENTIFIERS]`, `[COLORS]`), indexed once per check: every name in every expression
//! is looked up here.

use std::cell::RefCell;

use ilmr_model::{PARAMETER_SPECS, RobotModel};

use crate::check::fold::FoldMap;

#[derive(Debug, Default)]
pub struct Constants {
    values: FoldMap<f64>,
    /// `parameter_or_default` of the parameters ranges have asked for, under the name
    /// asked: ranges ask for every constant argument and the model answers by scanning
    /// its lists, while an interactive line, checked alone, asks for one or none.
    bounds: RefCell<Vec<(String, Option<f64>)>>,
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
        let mut values = FoldMap::with_capacity(
            model.parameters.len()
                + PARAMETER_SPECS.len()
                + model.identifiers.len()
                + model.colors.len(),
        );
        let mut buf = String::new();
        // The file's values first; then the documented default of every known parameter
        // the file lacks; then identifiers and colours. An earlier entry wins, the same
        // precedence as `parameter_or_default`, identifier, colour. (Asking the model
        // `parameter_or_default` for every known name scans its lists each time: that
        // was three quarters of the cost of an interactive line.)
        for p in &model.parameters {
            values.get_or_insert_with(key(&p.name, &mut buf), || p.value);
        }
        for spec in PARAMETER_SPECS {
            if values.get(key(spec.name, &mut buf)).is_none()
                && let Some(v) = model.parameter_or_default(spec.name)
            {
                values.get_or_insert_with(&buf, || v);
            }
        }
        for entry in model.identifiers.iter().chain(&model.colors) {
            values.get_or_insert_with(key(&entry.name, &mut buf), || entry.value);
        }
        Constants {
            values,
            bounds: RefCell::default(),
        }
    }

    /// Exactly `model.parameter_or_default(name)`, for the model these constants are of.
    pub fn parameter_or_default(&self, name: &str, model: &RobotModel) -> Option<f64> {
        let mut bounds = self.bounds.borrow_mut();
        if let Some(&(_, value)) = bounds.iter().find(|(n, _)| n == name) {
            return value;
        }
        let value = model.parameter_or_default(name);
        bounds.push((name.to_string(), value));
        value
    }

    pub fn len(&self) -> usize {
        self.values.len()
    }

    pub fn is_empty(&self) -> bool {
        self.values.len() == 0
    }

    /// Every constant under its lower-cased key, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, f64)> {
        self.values.iter().map(|(k, v)| (k, *v))
    }

    pub fn get(&self, name: &str, buf: &mut String) -> Option<f64> {
        if name.is_ascii() {
            return self.values.get(name).copied();
        }
        self.values.get(key(name, buf)).copied()
    }
}
