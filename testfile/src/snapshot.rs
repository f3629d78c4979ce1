//! Where a test's trace snapshot is kept and how it is made (the comparison is
//! `ilmrc test`'s): `snapshots/` beside the test file, named by the file and the test.

use std::ops::Range;
use std::path::{Path, PathBuf};

/// A snapshot's precision when the test gives none: a millimetre (and a milliradian,
/// a millimetre a second).
pub const PRECISION: f64 = 0.001;

/// A test's snapshot: how it is made, and where it is kept.
#[derive(Debug, Clone)]
pub struct Snapshot {
    pub precision: f64,
    pub scans: bool,
    /// The `snapshot` key's value in the test file.
    pub span: Range<usize>,
    /// The stored file of seed N is this with `__seedN.jsonl` added.
    pub stem: PathBuf,
}

impl Snapshot {
    pub fn path(&self, seed: u64) -> PathBuf {
        let mut name = self.stem.file_name().unwrap_or_default().to_os_string();
        name.push(format!("__seed{seed}.jsonl"));
        self.stem.with_file_name(name)
    }
}

/// Where a test file's snapshots live: `snapshots/` beside it, named by the file and
/// the test.
pub fn stem(test_file: &Path, test: &str) -> PathBuf {
    let dir = test_file
        .parent()
        .unwrap_or(Path::new("."))
        .join("snapshots");
    dir.join(format!("{}__{}", file_stem(test_file), slug(test)))
}

pub fn file_stem(test_file: &Path) -> String {
    let name = test_file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    name.strip_suffix(crate::SUFFIX)
        .unwrap_or(&name)
        .to_string()
}

/// A test's name as a file name: letters and digits, `_` between words.
fn slug(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    out.trim_matches('_').to_string()
}
