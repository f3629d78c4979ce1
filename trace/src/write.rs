//! Writing lines: serde_json with the trace's numbers ([`Short`]), straight into the
//! caller's buffer or file; the recorded inputs with every digit (serde_json's own
//! shortest round trip), since a replay feeds them back to the VM.

use std::io;

use serde::Serialize;

use crate::{Record, Short};

/// Writes `record` as one line of JSON, without the newline. Into memory it cannot
/// fail: every key of the schema is a string.
pub fn write_line<W: io::Write>(out: W, record: &Record<'_>) -> serde_json::Result<()> {
    if record.event.is_exact() {
        return record.serialize(&mut serde_json::Serializer::new(out));
    }
    let mut ser = serde_json::Serializer::with_formatter(out, Short);
    record.serialize(&mut ser)
}

/// `record` as one line of JSON, without the newline.
pub fn to_line(record: &Record<'_>) -> String {
    let mut out = Vec::with_capacity(96);
    // Into a Vec the write cannot fail (see `write_line`), and serde_json writes UTF-8.
    let _ = write_line(&mut out, record);
    String::from_utf8(out).unwrap_or_default()
}
