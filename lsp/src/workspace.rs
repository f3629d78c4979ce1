//! The files the server knows: the task, skill and robot-model files found under the
//! workspace roots, with the editor's text in place of the disk's for open documents.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use tower_lsp_server::ls_types::{TextDocumentContentChangeEvent, Uri};

use crate::line_index::LineIndex;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A task (`.ilmr`) or skill (`.ilms`) file.
    Program,
    /// A `ROBO.INI` robot model.
    RobotModel,
}

impl FileKind {
    /// What a path holds, judged by its name; `None` for files the server ignores.
    pub fn of(path: &str) -> Option<FileKind> {
        let name = path.rsplit(['/', '\\']).next().unwrap_or(path);
        let ext = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("ilmr" | "ilms") => Some(FileKind::Program),
            _ if name.eq_ignore_ascii_case("robo.ini") => Some(FileKind::RobotModel),
            _ => None,
        }
    }
}

#[derive(Debug, Clone)]
pub struct Document {
    pub uri: Uri,
    pub kind: FileKind,
    pub text: String,
    pub index: LineIndex,
    /// The editor's version while the document is open; `None` for the disk's copy.
    pub version: Option<i32>,
}

impl Document {
    fn new(uri: Uri, kind: FileKind, text: String, version: Option<i32>) -> Document {
        Document {
            uri,
            kind,
            index: LineIndex::new(&text),
            text,
            version,
        }
    }

    pub fn is_open(&self) -> bool {
        self.version.is_some()
    }
}

/// Directories never holding a project's own files, skipped by the scan.
const SKIPPED_DIRS: &[&str] = &["node_modules", "target", ".git"];
/// Deep enough for any project layout, shallow enough that a root of `/` stays cheap.
pub const MAX_DEPTH: usize = 6;
/// A scan stops after this many files, so that opening a huge folder cannot stall the
/// server; open documents are always known.
pub const MAX_FILES: usize = 2_000;
/// A scan stops reading once the files read hold this many bytes: every change
/// re-checks them all, and they stay in memory.
pub const MAX_SCAN_BYTES: usize = 64 * 1024 * 1024;
/// A scan stops after looking at this many directory entries, so that a root of `/`
/// or a folder of millions of files costs a bounded time.
pub const MAX_SCANNED_ENTRIES: usize = 100_000;

#[derive(Debug, Default)]
pub struct Workspace {
    roots: Vec<PathBuf>,
    /// Keyed by URI text, so that iteration (and so file order in the analysis) is stable.
    docs: BTreeMap<String, Document>,
}

impl Workspace {
    pub fn new(roots: Vec<PathBuf>) -> Workspace {
        let mut ws = Workspace {
            roots,
            docs: BTreeMap::new(),
        };
        ws.scan();
        ws
    }

    pub fn roots(&self) -> &[PathBuf] {
        &self.roots
    }

    /// Reads every task, skill and model file under the roots; open documents keep the
    /// editor's text.
    pub fn scan(&mut self) {
        self.docs.retain(|_, d| d.is_open());
        let mut found = Vec::new();
        let mut seen = 0;
        for root in &self.roots {
            walk(root, 0, &mut found, &mut seen);
        }
        found.sort();
        let mut held = 0;
        for path in found.into_iter().take(MAX_FILES) {
            if held >= MAX_SCAN_BYTES {
                break;
            }
            self.read_from_disk(&path);
            let uri = Uri::from_file_path(&path);
            held += uri
                .and_then(|u| self.docs.get(u.as_str()))
                .map_or(0, |d| d.text.len());
        }
    }

    fn read_from_disk(&mut self, path: &Path) {
        let Some(uri) = Uri::from_file_path(path) else {
            return;
        };
        let Some(kind) = FileKind::of(&path.to_string_lossy()) else {
            return;
        };
        if self.docs.get(uri.as_str()).is_some_and(Document::is_open) {
            return;
        }
        let limit = match kind {
            FileKind::Program => ilmr_files::Kind::Source,
            FileKind::RobotModel => ilmr_files::Kind::RobotModel,
        };
        match ilmr_files::read(path, limit) {
            Ok(bytes) => {
                let text = String::from_utf8_lossy(&bytes).into_owned();
                self.docs.insert(
                    uri.as_str().to_string(),
                    Document::new(uri, kind, text, None),
                );
            }
            Err(_) => {
                self.docs.remove(uri.as_str());
            }
        }
    }

    /// A file changed, appeared or vanished on disk. Returns whether the server's view
    /// changed (an open document keeps the editor's text).
    pub fn disk_changed(&mut self, uri: &Uri) -> bool {
        if self.docs.get(uri.as_str()).is_some_and(Document::is_open) {
            return false;
        }
        let Some(path) = uri.to_file_path() else {
            return false;
        };
        if FileKind::of(uri.as_str()).is_none() || !self.under_roots(&path) {
            return false;
        }
        self.read_from_disk(&path);
        true
    }

    fn under_roots(&self, path: &Path) -> bool {
        self.roots.iter().any(|r| path.starts_with(r))
    }

    /// Returns whether the document is one the server reads.
    pub fn open(&mut self, uri: Uri, version: i32, text: String) -> bool {
        let Some(kind) = FileKind::of(uri.as_str()) else {
            return false;
        };
        self.docs.insert(
            uri.as_str().to_string(),
            Document::new(uri, kind, text, Some(version)),
        );
        true
    }

    /// Applies the editor's changes in order; a change without a range replaces the text.
    pub fn change(
        &mut self,
        uri: &Uri,
        version: i32,
        changes: Vec<TextDocumentContentChangeEvent>,
    ) -> bool {
        let Some(doc) = self.docs.get_mut(uri.as_str()) else {
            return false;
        };
        doc.index.apply(&mut doc.text, changes);
        doc.version = Some(version);
        true
    }

    /// The editor let go of a document: the disk's copy takes its place when the file is
    /// part of the workspace, else the server forgets it.
    pub fn close(&mut self, uri: &Uri) {
        self.docs.remove(uri.as_str());
        if let Some(path) = uri.to_file_path()
            && self.under_roots(&path)
        {
            self.read_from_disk(&path);
        }
    }

    pub fn get(&self, uri: &Uri) -> Option<&Document> {
        self.docs.get(uri.as_str())
    }

    pub fn get_str(&self, uri: &str) -> Option<&Document> {
        self.docs.get(uri)
    }

    pub fn documents(&self) -> impl Iterator<Item = &Document> {
        self.docs.values()
    }

    pub fn programs(&self) -> impl Iterator<Item = &Document> {
        self.docs.values().filter(|d| d.kind == FileKind::Program)
    }

    /// The workspace's ROBO.INI: the shallowest one under the roots, or an open one.
    pub fn robot_model(&self) -> Option<&Document> {
        self.docs
            .values()
            .filter(|d| d.kind == FileKind::RobotModel)
            .min_by_key(|d| {
                (
                    d.uri.as_str().matches('/').count(),
                    d.uri.as_str().to_string(),
                )
            })
    }
}

/// `seen` counts the directory entries looked at, against `MAX_SCANNED_ENTRIES`.
fn walk(dir: &Path, depth: usize, found: &mut Vec<PathBuf>, seen: &mut usize) {
    if depth > MAX_DEPTH || found.len() >= MAX_FILES {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<_> = entries
        .filter_map(Result::ok)
        .take(MAX_SCANNED_ENTRIES.saturating_sub(*seen))
        .collect();
    *seen += entries.len();
    entries.sort_by_key(|e| e.file_name());
    for entry in entries {
        if *seen >= MAX_SCANNED_ENTRIES {
            return;
        }
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if kind.is_dir() {
            if !name.starts_with('.') && !SKIPPED_DIRS.contains(&name.as_ref()) {
                walk(&path, depth + 1, found, seen);
            }
        } else if FileKind::of(&name).is_some() {
            found.push(path);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tower_lsp_server::ls_types::{Position, Range};

    #[test]
    fn file_kinds_by_name() {
        assert_eq!(FileKind::of("/a/task.ILMR"), Some(FileKind::Program));
        assert_eq!(
            FileKind::of("file:///a/turns.ilms"),
            Some(FileKind::Program)
        );
        assert_eq!(FileKind::of("/a/Robo.ini"), Some(FileKind::RobotModel));
        assert_eq!(FileKind::of("/a/other.ini"), None);
    }

    #[test]
    fn a_scan_stops_reading_at_its_byte_budget() {
        let root = std::env::temp_dir().join(format!("ilmr-lsp-scan-{}", std::process::id()));
        std::fs::create_dir_all(&root).unwrap();
        // Files as large as `ilmrc` reads one, more of them than the budget holds.
        let size = ilmr_files::MAX_SOURCE_BYTES as usize;
        let big = "x = 1\n".repeat(size / 6);
        let fit = MAX_SCAN_BYTES.div_ceil(big.len());
        for i in 0..fit + 2 {
            std::fs::write(root.join(format!("{i:03}.ilmr")), &big).unwrap();
        }
        let read = Workspace::new(vec![root.clone()]).documents().count();
        std::fs::remove_dir_all(&root).unwrap();
        assert_eq!(read, fit);
    }

    #[test]
    fn a_scan_stops_at_its_entry_budget() {
        let root = std::env::temp_dir().join(format!("ilmr-lsp-entries-{}", std::process::id()));
        let many = root.join("a-many");
        std::fs::create_dir_all(&many).unwrap();
        std::fs::write(root.join("b.ilmr"), "wait(1)\n").unwrap();
        let before = Workspace::new(vec![root.clone()]).documents().count();
        for i in 0..MAX_SCANNED_ENTRIES {
            std::fs::write(many.join(i.to_string()), "").unwrap();
        }
        let after = Workspace::new(vec![root.clone()]).documents().count();
        std::fs::remove_dir_all(&root).unwrap();
        assert_eq!((before, after), (1, 0));
    }

    #[test]
    fn partial_edits_apply_in_utf16_columns() {
        let mut ws = Workspace::default();
        let uri: Uri = "file:///w/t.ilmr".parse().unwrap();
        assert!(ws.open(uri.clone(), 1, "käännös=turn(left)\n".into()));
        let change = TextDocumentContentChangeEvent {
            range: Some(Range::new(Position::new(0, 13), Position::new(0, 17))),
            range_length: None,
            text: "right".into(),
        };
        assert!(ws.change(&uri, 2, vec![change]));
        let doc = ws.get(&uri).unwrap();
        assert_eq!(doc.text, "käännös=turn(right)\n");
        assert_eq!(doc.version, Some(2));
    }
}
