//! The audit log: one JSON line per thing a client did to the robot (authenticated
//! or failed to, took or lost a lease, sent a line, `cont` or `stop`), with the
//! client's identity, its address and the wall-clock time. Bounded: past
//! `MAX_AUDIT_BYTES` the file is moved to `FILE.1` (replacing the one before) and a
//! new one begun.

use std::fs::File;
use std::io::Write;
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};
use std::time::{SystemTime, UNIX_EPOCH};

use serde_json::{Map, Value, json};

use super::access::{Identity, Proof};

/// A log file grows to this before it is rotated; with the one kept, the log holds
/// at most twice this.
pub const MAX_AUDIT_BYTES: u64 = 64 << 20;

pub struct Audit {
    path: PathBuf,
    file: Mutex<Open>,
    limit: u64,
}

struct Open {
    file: Option<File>,
    bytes: u64,
}

/// Who did it.
pub struct Who<'a> {
    pub identity: Option<&'a Identity>,
    pub conn: u64,
    pub peer: Option<SocketAddr>,
}

impl Audit {
    pub fn open(path: &Path) -> Result<Audit, String> {
        Audit::with_limit(path, MAX_AUDIT_BYTES)
    }

    fn with_limit(path: &Path, limit: u64) -> Result<Audit, String> {
        let file = append(path)?;
        let bytes = file.metadata().map(|m| m.len()).unwrap_or(0);
        Ok(Audit {
            path: path.to_path_buf(),
            file: Mutex::new(Open {
                file: Some(file),
                bytes,
            }),
            limit,
        })
    }

    fn open_file(&self) -> MutexGuard<'_, Open> {
        self.file
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Logs what `who` did: `what` names it, `fields` say the rest (the text, the
    /// outcome). A log that cannot be written is said once on stderr, not fatal:
    /// the robot is not stopped for it.
    pub fn record(&self, who: &Who<'_>, what: &str, fields: Map<String, Value>) {
        let mut entry = Map::new();
        entry.insert("time".into(), json!(rfc3339(SystemTime::now())));
        entry.insert("what".into(), json!(what));
        if let Some(id) = who.identity {
            entry.insert("client".into(), json!(id.name));
            entry.insert("role".into(), json!(id.role.name()));
            let proof = match id.proof {
                Proof::Token => "token",
                Proof::Certificate => "certificate",
                Proof::Nothing => "none",
            };
            entry.insert("proof".into(), json!(proof));
        }
        entry.insert("conn".into(), json!(who.conn));
        if let Some(peer) = who.peer {
            entry.insert("peer".into(), json!(peer.to_string()));
        }
        entry.extend(fields);
        let mut line = Value::Object(entry).to_string();
        line.push('\n');
        let mut open = self.open_file();
        if open.bytes > 0 && open.bytes + line.len() as u64 > self.limit {
            self.rotate(&mut open);
        }
        let Some(file) = open.file.as_mut() else {
            return;
        };
        match file.write_all(line.as_bytes()) {
            Ok(()) => open.bytes += line.len() as u64,
            Err(e) => {
                eprintln!(
                    "warning: cannot write the audit log {}: {e}; not logging further",
                    self.path.display()
                );
                open.file = None;
            }
        }
    }

    fn rotate(&self, open: &mut Open) {
        let mut old = self.path.clone().into_os_string();
        old.push(".1");
        open.file = None;
        let reopened = std::fs::rename(&self.path, &old)
            .map_err(|e| e.to_string())
            .and_then(|()| append(&self.path));
        match reopened {
            Ok(f) => {
                open.file = Some(f);
                open.bytes = 0;
            }
            Err(e) => eprintln!(
                "warning: cannot rotate the audit log {}: {e}; not logging further",
                self.path.display()
            ),
        }
    }
}

fn append(path: &Path) -> Result<File, String> {
    let mut options = std::fs::OpenOptions::new();
    options.create(true).append(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // It names clients and holds every line they sent.
        options.mode(0o600);
    }
    options
        .open(path)
        .map_err(|e| format!("cannot open the audit log {}: {e}", path.display()))
}

/// `2026-11-26T02:31:07.123Z`.
fn rfc3339(at: SystemTime) -> String {
    let since = at.duration_since(UNIX_EPOCH).unwrap_or_default();
    let secs = since.as_secs();
    let (days, rest) = (secs / 86_400, secs % 86_400);
    let (y, m, d) = civil_from_days(i64::try_from(days).unwrap_or(0));
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}.{:03}Z",
        rest / 3600,
        rest % 3600 / 60,
        rest % 60,
        since.subsec_millis()
    )
}

/// The proleptic Gregorian date of a day counted from 1970-01-01 (Howard Hinnant's
/// `civil_from_days`).
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = u32::try_from(doy - (153 * mp + 2) / 5 + 1).unwrap_or(1);
    let m = u32::try_from(if mp < 10 { mp + 3 } else { mp - 9 }).unwrap_or(1);
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::serve::access::Role;
    use std::time::Duration;

    #[test]
    fn dates_are_utc_calendar_dates() {
        let at = |s: u64| rfc3339(UNIX_EPOCH + Duration::from_millis(s));
        assert_eq!(at(0), "1970-01-01T00:00:00.000Z");
        assert_eq!(at(951_782_400_000), "2000-02-29T00:00:00.000Z");
        assert_eq!(at(1_795_660_267_123), "2026-11-26T02:31:07.123Z");
    }

    #[test]
    fn entries_name_the_client_and_the_log_rotates_at_its_limit() {
        let dir = std::env::temp_dir().join(format!("ilmr-audit-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("a scratch directory");
        let path = dir.join("audit.jsonl");
        let audit = Audit::with_limit(&path, 400).expect("open");
        let planner = Identity {
            name: "planner".into(),
            role: Role::Driver,
            proof: Proof::Token,
        };
        let who = Who {
            identity: Some(&planner),
            conn: 3,
            peer: "127.0.0.1:4000".parse().ok(),
        };
        for i in 0..6 {
            let mut f = Map::new();
            f.insert("text".into(), json!(format!("goahead({i})")));
            audit.record(&who, "line", f);
        }
        let now = std::fs::read_to_string(&path).expect("the log");
        let old = std::fs::read_to_string(dir.join("audit.jsonl.1")).expect("the rotated log");
        assert!(
            now.len() <= 400 && old.len() <= 400,
            "{} {}",
            now.len(),
            old.len()
        );
        let last: Value = serde_json::from_str(now.lines().last().expect("a line")).expect("JSON");
        assert_eq!(
            (
                &last["client"],
                &last["role"],
                &last["proof"],
                &last["conn"],
                &last["text"]
            ),
            (
                &json!("planner"),
                &json!("driver"),
                &json!("token"),
                &json!(3),
                &json!("goahead(5)")
            )
        );
        assert_eq!(last["peer"], json!("127.0.0.1:4000"));
        assert!(last["time"].as_str().is_some_and(|t| t.ends_with('Z')));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
