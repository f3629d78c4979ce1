//! Reading lines back, with the schema version checked first.

use std::fmt;

use serde::Deserialize;

use crate::{Event, Record, SCHEMA_VERSION};

/// Why a trace cannot be read: each with a stable code (docs/run.md, "Trace").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Code {
    /// A line that is not JSON, not an event of the schema, or an event with a key
    /// missing or of the wrong type.
    NotALine,
    /// The first line is not the `trace` line with the schema version (a trace
    /// written before traces had one, or not a trace).
    NoVersion,
    /// A schema version this reader does not read.
    UnknownVersion,
}

impl Code {
    /// Every code, for the table in docs/run.md.
    pub const ALL: [Code; 3] = [Code::NotALine, Code::NoVersion, Code::UnknownVersion];

    pub fn code(self) -> &'static str {
        match self {
            Code::NotALine => "T0101",
            Code::NoVersion => "T0102",
            Code::UnknownVersion => "T0103",
        }
    }
}

/// A line of a trace that could not be read: where, why, and the [`Code`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TraceError {
    pub code: Code,
    /// The line's number, from 1.
    pub line: usize,
    pub message: String,
}

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "line {}: {} {}",
            self.line,
            self.code.code(),
            self.message
        )
    }
}

impl std::error::Error for TraceError {}

/// Reads a trace line by line: the first line must be the `trace` line of
/// [`SCHEMA_VERSION`], every other a [`Record`] of the schema.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Reader {
    /// Lines taken so far.
    lines: usize,
    /// The version line has been read.
    versioned: bool,
}

/// Just enough of a line to tell its version, whatever else a newer schema put in it.
#[derive(Deserialize)]
struct Head<'a> {
    #[serde(borrow, default)]
    event: Option<&'a str>,
    #[serde(default)]
    version: Option<u64>,
}

impl Reader {
    /// The next line of the trace; `None` for a blank line.
    pub fn read<'a>(&mut self, line: &'a str) -> Result<Option<Record<'a>>, TraceError> {
        self.lines += 1;
        if line.trim().is_empty() {
            return Ok(None);
        }
        let fail = |code: Code, message: String| TraceError {
            code,
            line: self.lines,
            message,
        };
        if !self.versioned {
            let head: Head = serde_json::from_str(line)
                .map_err(|e| fail(Code::NotALine, format!("not a JSON object: {e}")))?;
            if head.event != Some("trace") {
                return Err(fail(
                    Code::NoVersion,
                    "the first line is not `{\"t\":0,\"event\":\"trace\",\"version\":N}`: \
                     a trace written before traces carried their schema version, or not a trace"
                        .into(),
                ));
            }
        }
        let record: Record = serde_json::from_str(line).map_err(|e| {
            let version = serde_json::from_str::<Head>(line)
                .ok()
                .filter(|h| h.event == Some("trace"))
                .and_then(|h| h.version);
            match version {
                Some(v) if v != u64::from(SCHEMA_VERSION) => unknown_version(v, self.lines),
                _ => fail(Code::NotALine, e.to_string()),
            }
        })?;
        if let Event::Trace(v) = &record.event {
            if v.version != SCHEMA_VERSION {
                return Err(unknown_version(u64::from(v.version), self.lines));
            }
            self.versioned = true;
        }
        Ok(Some(record))
    }
}

fn unknown_version(found: u64, line: usize) -> TraceError {
    TraceError {
        code: Code::UnknownVersion,
        line,
        message: format!(
            "the trace has schema version {found}; this ilmrc reads version {SCHEMA_VERSION} \
             (docs/trace-schema.json): read it with the ilmrc that wrote it, or run the task again"
        ),
    }
}

/// The records of a whole trace, blank lines skipped (a caller stops at the first
/// error: a trace without its version line fails on every line).
pub fn records(text: &str) -> impl Iterator<Item = Result<Record<'_>, TraceError>> {
    let mut reader = Reader::default();
    text.lines()
        .filter_map(move |line| reader.read(line).transpose())
}
