//! Errors from loading a world file. Each names the file, the 1-based line,
//! and where it can the entry and field at fault.

use std::fmt;

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WorldError {
    /// File name, or `<name>` for an embedded world.
    pub source: String,
    /// 1-based line; 0 when the file could not be read at all.
    pub line: usize,
    /// The entry and field at fault, such as `door #2 width`.
    pub field: Option<String>,
    pub message: String,
}

impl fmt::Display for WorldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: ", self.source, self.line)?;
        if let Some(field) = &self.field {
            write!(f, "{field}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for WorldError {}

pub(crate) use ilmr_files::line_of;

/// The line on which `key` is set inside the entry whose header starts at
/// `entry_start`, or the header's own line when the key is not written there
/// (a missing field, or an inline table). Serde does not keep spans of plain
/// fields, so this finds the key in the text instead.
pub(crate) fn field_line(text: &str, entry_start: usize, key: &str) -> usize {
    let header_line = line_of(text, entry_start);
    let rest = text.get(entry_start..).unwrap_or("");
    for (i, line) in rest.lines().enumerate() {
        let t = line.trim_start();
        if i > 0 && t.starts_with('[') {
            break;
        }
        let Some(after) = t.strip_prefix(key) else {
            continue;
        };
        if after.trim_start().starts_with('=') {
            return header_line + i;
        }
    }
    header_line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_line_finds_key_inside_entry_only() {
        let text = "[[door]]\nwall = \"a\"\nwidth = 1\n\n[[door]]\nwidth = 2\n";
        assert_eq!(field_line(text, 0, "width"), 3);
        assert_eq!(field_line(text, 0, "at"), 1);
        let second = text.find("[[door]]\nwidth = 2").unwrap_or(0);
        assert_eq!(field_line(text, second, "width"), 6);
        // `wall` is a prefix of no other key here, but `widths` must not match `width`.
        assert_eq!(field_line("[[x]]\nwidths = 1\n", 0, "width"), 1);
    }
}
