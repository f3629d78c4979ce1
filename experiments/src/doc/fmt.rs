//! Numbers as the report writes them.

/// Fixed decimals, as measured values are compared.
pub fn f(x: f64, decimals: usize) -> String {
    format!("{x:.decimals$}")
}

/// A setting or a bar: up to four decimals, without trailing zeros (0.27, 2, 0.75).
pub fn n(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// A list of numbers joined with ", ".
pub fn list(xs: &[f64]) -> String {
    xs.iter().map(|x| n(*x)).collect::<Vec<_>>().join(", ")
}

/// "no contact" or how many.
pub fn contacts(count: u64) -> String {
    match count {
        0 => "no contact".into(),
        1 => "1 contact".into(),
        k => format!("{k} contacts"),
    }
}

/// How a statement ended, or that it did not.
pub fn how(how: Option<&str>) -> String {
    how.unwrap_or("did not end").to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_drop_trailing_zeros_only() {
        assert_eq!(n(0.22 + 0.05), "0.27");
        assert_eq!(n(2.0), "2");
        assert_eq!(n(1.0 / 0.75), "1.3333");
        assert_eq!(n(10.0), "10");
        assert_eq!(n(-0.00001), "0");
        assert_eq!(f(0.00149, 4), "0.0015");
    }
}
