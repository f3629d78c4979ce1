//! `serve` beyond loopback (issue 19): credentials made by `--init-credentials`, TLS
//! with tokens and client certificates, spoken to by Python's `ssl` module (a client
//! this project did not write); roles, the one-driver lease and its takeover, the
//! audit log; and what a server refuses to start with. Every connection is to
//! 127.0.0.1, bounded in count, and every wait has a deadline.

use std::io::{BufRead, BufReader, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use super::{PATIENCE, Server};

/// A fresh directory of credentials for one test.
fn credentials(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ilmr-creds-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(["serve", "--init-credentials"])
        .arg(&dir)
        .output()
        .expect("run ilmrc");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir
}

fn token(dir: &Path, client: &str) -> String {
    std::fs::read_to_string(dir.join(format!("{client}.token")))
        .expect("a token file")
        .trim()
        .to_string()
}

fn tls_server(dir: &Path) -> Server {
    Server::launch(
        &["--credentials", dir.to_str().expect("UTF-8 path")],
        &["--world", "empty"],
    )
}

/// Python's `ssl` client (tests/serve/tls_client.py), one connection at a time.
struct PyClient {
    child: Child,
    stdin: ChildStdin,
    lines: mpsc::Receiver<String>,
}

impl PyClient {
    /// Connects with the directory's CA, and the client certificate `cert` if given.
    fn connect(server: &Server, dir: &Path, cert: Option<(&Path, &Path)>) -> (PyClient, String) {
        let port = server.addr.rsplit(':').next().expect("a port").to_string();
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/serve/tls_client.py");
        let mut cmd = Command::new("python3");
        cmd.arg(script).arg(port).arg(dir.join("ca.pem"));
        if let Some((pem, key)) = cert {
            cmd.arg(pem).arg(key);
        }
        let mut child = cmd
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("python3 runs");
        let stdin = child.stdin.take().expect("piped stdin");
        let stdout = child.stdout.take().expect("piped stdout");
        let (tx, lines) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().take(1000) {
                let Ok(line) = line else { return };
                if tx.send(line).is_err() {
                    return;
                }
            }
        });
        let mut client = PyClient {
            child,
            stdin,
            lines,
        };
        let said = client.command("@connect");
        (client, said)
    }

    fn command(&mut self, line: &str) -> String {
        writeln!(self.stdin, "{line}").expect("write to the client");
        self.stdin.flush().expect("flush");
        self.lines
            .recv_timeout(PATIENCE + Duration::from_secs(5))
            .expect("the client answers in time")
    }

    /// A request's answer, as JSON.
    fn ask(&mut self, request: &Value) -> Value {
        let said = self.command(&request.to_string());
        serde_json::from_str(&said).unwrap_or_else(|_| panic!("not an answer: {said}"))
    }
}

impl Drop for PyClient {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn error_of(answer: &Value) -> &str {
    assert_eq!(answer["ok"], json!(false), "{answer}");
    answer["error"].as_str().unwrap_or("")
}

#[cfg(unix)]
#[test]
fn credentials_are_made_once_with_the_secrets_for_the_owner_only() {
    use std::os::unix::fs::PermissionsExt;
    let dir = credentials("made");
    for (file, mode) in [
        ("ca.pem", 0o644),
        ("ca.key", 0o600),
        ("server.pem", 0o644),
        ("server.key", 0o600),
        ("access.toml", 0o600),
        ("planner.token", 0o600),
        ("observer.token", 0o600),
        ("operator.pem", 0o644),
        ("operator.key", 0o600),
    ] {
        let meta = std::fs::metadata(dir.join(file)).expect(file);
        // The umask may take from the public files, never add to the secret ones.
        let have = meta.permissions().mode() & 0o777;
        assert_eq!(have & !mode, 0, "{file}: {have:o}");
    }
    assert_eq!(token(&dir, "planner").len(), 64);
    assert_ne!(token(&dir, "planner"), token(&dir, "observer"));
    let again = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(["serve", "--init-credentials"])
        .arg(&dir)
        .output()
        .expect("run ilmrc");
    assert_eq!(again.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&again.stderr).contains("exists already"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn over_tls_a_token_names_the_client_and_its_role_decides_what_it_may_do() {
    let dir = credentials("tokens");
    let server = tls_server(&dir);
    // Without a token: one answer, then closed.
    let (mut stranger, said) = PyClient::connect(&server, &dir, None);
    assert!(said.starts_with("@connected TLS"), "{said}");
    let first = stranger.ask(&json!({"status": true}));
    assert!(error_of(&first).contains("authenticate first"), "{first}");
    assert_eq!(stranger.command("@read"), "@closed");
    // A wrong token: refused, closed.
    let (mut guesser, _) = PyClient::connect(&server, &dir, None);
    let wrong = guesser.ask(&json!({"auth": "0".repeat(64)}));
    assert!(error_of(&wrong).contains("unknown token"), "{wrong}");
    assert_eq!(guesser.command("@read"), "@closed");
    // The planner drives.
    let (mut planner, _) = PyClient::connect(&server, &dir, None);
    let hello = planner.ask(&json!({"auth": token(&dir, "planner"), "id": 1}));
    assert_eq!(
        hello,
        json!({"ok": true, "client": "planner", "role": "driver", "id": 1})
    );
    let line = planner.ask(&json!({"ilmr": "speed(0.2)"}));
    assert_eq!(line["ok"], json!(true), "{line}");
    let again = planner.ask(&json!({"auth": token(&dir, "planner")}));
    assert!(error_of(&again).contains("already authenticated as `planner`"));
    // The observer watches and may stop the robot, but not drive it.
    let (mut observer, _) = PyClient::connect(&server, &dir, None);
    observer.ask(&json!({"auth": token(&dir, "observer")}));
    let refused = observer.ask(&json!({"ilmr": "goahead(1)"}));
    assert!(error_of(&refused).contains("is an observer"), "{refused}");
    let refused = observer.ask(&json!({"cont": true}));
    assert!(error_of(&refused).contains("is an observer"), "{refused}");
    let status = observer.ask(&json!({"status": true}));
    assert_eq!(
        (&status["you"], &status["lease"]["holder"]),
        (
            &json!({"client": "observer", "role": "observer"}),
            &json!("planner")
        ),
        "{status}"
    );
    let stopped = observer.ask(&json!({"stop": true}));
    assert_eq!(stopped["ok"], json!(true), "{stopped}");
    drop((planner, observer));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_client_certificate_signed_by_the_ca_is_known_without_a_token() {
    let dir = credentials("mtls");
    let other = credentials("mtls-other-ca");
    let server = tls_server(&dir);
    let cert = (dir.join("operator.pem"), dir.join("operator.key"));
    let (mut operator, said) = PyClient::connect(&server, &dir, Some((&cert.0, &cert.1)));
    assert!(said.starts_with("@connected"), "{said}");
    let status = operator.ask(&json!({"status": true}));
    assert_eq!(
        status["you"],
        json!({"client": "operator", "role": "driver"}),
        "{status}"
    );
    let line = operator.ask(&json!({"ilmr": "speed(0.2)"}));
    assert_eq!(line["ok"], json!(true), "{line}");
    // The same name, from another CA: the handshake fails.
    let forged = (other.join("operator.pem"), other.join("operator.key"));
    let (mut forger, said) = PyClient::connect(&server, &dir, Some((&forged.0, &forged.1)));
    let refused = if said.starts_with("@refused") {
        said
    } else {
        forger.command(&json!({"status": true}).to_string())
    };
    assert!(
        refused.starts_with("@refused") || refused == "@closed",
        "{refused}"
    );
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&other);
}

/// Bytes that are not TLS, half a handshake, and silent connections do not keep an
/// authenticated driver out.
#[test]
fn tls_garbage_and_stalled_handshakes_do_not_keep_a_driver_out() {
    let dir = credentials("garbage");
    let server = Server::launch(
        &[
            "--credentials",
            dir.to_str().expect("UTF-8 path"),
            "--request-timeout",
            "1",
        ],
        &["--world", "empty"],
    );
    let mut held = Vec::new();
    let mut seed: u64 = 0x1f2e_3d4c_5b6a_7988;
    for i in 0..200 {
        let mut s = TcpStream::connect(&server.addr).expect("connect");
        let bytes: Vec<u8> = match i % 4 {
            // Plain JSON, as a client that forgot TLS would send.
            0 => b"{\"stop\": true}\n".to_vec(),
            // A TLS record header that promises more than comes.
            1 => vec![0x16, 0x03, 0x01, 0x40, 0x00, 0x01, 0x00],
            // Random bytes.
            2 => (0..512)
                .map(|_| {
                    seed ^= seed << 13;
                    seed ^= seed >> 7;
                    seed ^= seed << 17;
                    seed.to_le_bytes()[0]
                })
                .collect(),
            // Nothing at all.
            _ => Vec::new(),
        };
        let _ = s.write_all(&bytes);
        held.push(s);
    }
    let asked = Instant::now();
    let (mut planner, said) = PyClient::connect(&server, &dir, None);
    assert!(said.starts_with("@connected"), "{said}");
    let hello = planner.ask(&json!({"auth": token(&dir, "planner")}));
    assert_eq!(hello["ok"], json!(true), "{hello}");
    let took = asked.elapsed();
    assert!(took < Duration::from_secs(5), "the driver waited {took:?}");
    // The plain-JSON `stop` among the garbage stopped nothing: it never authenticated.
    let status = planner.ask(&json!({"status": true}));
    assert_eq!(status["ok"], json!(true), "{status}");
    drop(held);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Plain TCP on loopback with an access file: the same roles, one driver at a time,
/// a takeover the first driver sees, and every line in the audit log.
#[test]
fn one_driver_holds_the_robot_and_a_takeover_is_seen_and_audited() {
    let dir = credentials("lease");
    let access = dir.join("access.toml");
    let audit = dir.join("audit-test.jsonl");
    let server = Server::launch(
        &[
            "--no-tls",
            "--access",
            access.to_str().expect("UTF-8 path"),
            "--audit",
            audit.to_str().expect("UTF-8 path"),
        ],
        &["--world", "empty"],
    );
    let mut planner = server.connect();
    planner.ask(&json!({"auth": token(&dir, "planner")}).to_string());
    let mut second = server.connect();
    // A second driver, by the planner's own token: another connection all the same.
    second.ask(&json!({"auth": token(&dir, "planner")}).to_string());
    assert_eq!(planner.ask(r#"{"ilmr": "speed(0.2)"}"#)["ok"], json!(true));
    let refused = second.ask(r#"{"ilmr": "speed(0.3)"}"#);
    let why = error_of(&refused);
    assert!(
        why.contains("driven by `planner` (connection 1;") && why.contains("takeover"),
        "{why}"
    );
    let taken = second.ask(r#"{"lease": "takeover"}"#);
    assert_eq!(
        (&taken["ok"], &taken["lease"], &taken["from"]),
        (&json!(true), &json!("held"), &json!("planner")),
        "{taken}"
    );
    assert_eq!(second.ask(r#"{"ilmr": "speed(0.3)"}"#)["ok"], json!(true));
    let told = planner
        .event_where(|e| e["event"] == json!("lease"))
        .expect("the planner is told");
    assert_eq!(
        told,
        json!({"event": "lease", "lease": "taken over", "by": "planner"})
    );
    let lost = planner.ask(r#"{"ilmr": "speed(0.1)"}"#);
    assert!(error_of(&lost).contains("takeover"), "{lost}");
    assert_eq!(
        second.ask(r#"{"lease": "release"}"#)["lease"],
        json!("released")
    );
    assert_eq!(planner.ask(r#"{"ilmr": "speed(0.1)"}"#)["ok"], json!(true));
    drop((planner, second));
    let log = std::fs::read_to_string(&audit).expect("the audit log");
    let entries: Vec<Value> = log
        .lines()
        .map(|l| serde_json::from_str(l).expect("JSON lines"))
        .collect();
    let what: Vec<&str> = entries.iter().filter_map(|e| e["what"].as_str()).collect();
    for expected in [
        "auth",
        "lease taken",
        "line",
        "lease taken over",
        "lease released",
    ] {
        assert!(what.contains(&expected), "no `{expected}` in {what:?}");
    }
    let lines: Vec<&Value> = entries
        .iter()
        .filter(|e| e["what"] == json!("line"))
        .collect();
    assert_eq!(lines.len(), 5, "{lines:?}");
    assert!(lines.iter().all(|e| {
        e["client"] == json!("planner")
            && e["proof"] == json!("token")
            && e["peer"]
                .as_str()
                .is_some_and(|p| p.starts_with("127.0.0.1:"))
            && e["time"].as_str().is_some_and(|t| t.ends_with('Z'))
    }));
    assert_eq!(
        lines.iter().map(|e| e["ok"].clone()).collect::<Vec<_>>(),
        [
            json!(true),
            json!(false),
            json!(true),
            json!(false),
            json!(true)
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// What a server refuses to start with: exit 2 and why.
#[test]
fn a_server_without_credentials_or_with_readable_secrets_does_not_start() {
    let dir = credentials("refusals");
    let access = dir.join("access.toml");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["--listen".into(), "127.0.0.1:0".into()], "--no-tls"),
        (
            vec!["--listen".into(), "0.0.0.0:0".into(), "--no-tls".into()],
            "loopback addresses only",
        ),
        (
            vec![
                "--listen".into(),
                "127.0.0.1:0".into(),
                "--credentials".into(),
                dir.join("missing").display().to_string(),
            ],
            "cannot read",
        ),
    ];
    for (args, says) in cases {
        expect_refusal(&args, says);
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&access, std::fs::Permissions::from_mode(0o644)).expect("chmod");
        let args = vec![
            "--listen".into(),
            "127.0.0.1:0".into(),
            "--credentials".into(),
            dir.display().to_string(),
        ];
        expect_refusal(&args, "chmod 600");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn expect_refusal(args: &[String], says: &str) {
    let out = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .arg("serve")
        .args(args)
        .args(["--world", "empty"])
        .stdin(Stdio::null())
        .output()
        .expect("run ilmrc");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(stderr.contains(says), "{args:?}: {stderr}");
}
