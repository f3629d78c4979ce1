//! `ilmrc serve` driven over real loopback TCP connections: answers, diagnostics,
//! garbage, several clients, the event stream, and clients that go away mid-line.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde_json::{Value, json};

/// Every wait in these tests ends by this deadline.
const PATIENCE: Duration = Duration::from_secs(20);
/// Lines read while looking for one: a bound on every reading loop.
const MAX_LINES: usize = 20_000;

/// A server on a free loopback port, killed when dropped.
struct Server {
    child: Child,
    addr: String,
}

impl Server {
    /// A server of plain TCP that asks nobody who they are.
    fn start(extra: &[&str]) -> Server {
        Server::launch(&["--no-tls"], extra)
    }

    /// A server with these security flags (`--no-tls`, `--credentials DIR`, ...).
    fn launch(security: &[&str], extra: &[&str]) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
            .args(["serve", "--listen", "127.0.0.1:0"])
            .args(security)
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start ilmrc serve");
        let stdout = child.stdout.take().expect("piped stdout");
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().take(100) {
                let Ok(line) = line else { return };
                if let Some(rest) = line.strip_prefix("listening on ") {
                    let addr = rest.split_whitespace().next().unwrap_or("").to_string();
                    let _ = tx.send(addr);
                }
            }
        });
        let Ok(addr) = rx.recv_timeout(PATIENCE) else {
            let _ = child.kill();
            panic!("the server did not print its address");
        };
        assert!(addr.starts_with("127.0.0.1:"), "{addr}");
        Server { child, addr }
    }

    fn connect(&self) -> Client {
        let stream = TcpStream::connect(&self.addr).expect("connect to the server");
        stream
            .set_read_timeout(Some(Duration::from_millis(200)))
            .expect("read timeout");
        Client {
            reader: BufReader::new(stream.try_clone().expect("clone the stream")),
            stream,
            events: Vec::new(),
        }
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

struct Client {
    stream: TcpStream,
    reader: BufReader<TcpStream>,
    /// Event lines read while waiting for answers.
    events: Vec<Value>,
}

impl Client {
    fn send_raw(&mut self, bytes: &[u8]) {
        self.stream.write_all(bytes).expect("send");
        self.stream.flush().expect("flush");
    }

    /// The next line within the deadline, as JSON.
    fn next_line(&mut self, deadline: Instant) -> Option<Value> {
        let mut line = String::new();
        while Instant::now() < deadline {
            match self.reader.read_line(&mut line) {
                Ok(0) => return None,
                Ok(_) if line.ends_with('\n') => {
                    return Some(serde_json::from_str(&line).expect("every line is JSON"));
                }
                // A timeout may leave a partial line in `line`; keep reading onto it.
                Ok(_) | Err(_) => {}
            }
        }
        None
    }

    /// Sends a request and returns its answer; events on the way are kept.
    fn ask(&mut self, request: &str) -> Value {
        self.send_raw(format!("{request}\n").as_bytes());
        let deadline = Instant::now() + PATIENCE;
        for _ in 0..MAX_LINES {
            let line = self.next_line(deadline).expect("an answer in time");
            if line.get("event").is_some() {
                self.events.push(line);
            } else {
                return line;
            }
        }
        panic!("no answer among {MAX_LINES} lines");
    }

    /// Reads events until one satisfies `found` (it is returned) or the deadline.
    fn event_where(&mut self, found: impl Fn(&Value) -> bool) -> Option<Value> {
        if let Some(e) = self.events.iter().find(|e| found(e)) {
            return Some(e.clone());
        }
        let deadline = Instant::now() + PATIENCE;
        for _ in 0..MAX_LINES {
            let line = self.next_line(deadline)?;
            let hit = found(&line);
            self.events.push(line);
            if hit {
                return self.events.last().cloned();
            }
        }
        None
    }
}

#[test]
fn a_good_line_is_accepted_and_a_bad_one_rejected_with_codes() {
    let server = Server::start(&[]);
    let mut c = server.connect();
    let good = c.ask(r#"{"ilmr": "goahead(1)", "id": 1}"#);
    assert_eq!(good["ok"], json!(true), "{good}");
    assert_eq!(good["id"], json!(1));
    assert!(good["t"].is_number());

    let bad = c.ask(r#"{"ilmr": "goahed(1)", "id": "two"}"#);
    assert_eq!(bad["ok"], json!(false), "{bad}");
    assert_eq!(bad["id"], json!("two"));
    let diagnostics = bad["diagnostics"].as_array().expect("diagnostics");
    assert!(!diagnostics.is_empty());
    let d = &diagnostics[0];
    let code = d["code"].as_str().expect("a code");
    assert!(code.starts_with('E') && code.len() == 5, "{code}");
    assert_eq!(d["severity"], json!("error"));
    assert_eq!(
        (d["file"].as_str(), d["line"].as_u64()),
        (Some("<line>"), Some(1))
    );

    // A block of several lines is one request.
    let block = c.ask(&json!({"ilmr": "speed(0.2)\ngoahead(0.5)"}).to_string());
    assert_eq!(block["ok"], json!(true), "{block}");

    let stopped = c.ask(r#"{"stop": true}"#);
    assert_eq!(stopped["ok"], json!(true), "{stopped}");
    let resumed = c.ask(r#"{"cont": true}"#);
    assert_eq!(resumed["ok"], json!(true), "{resumed}");
}

#[test]
fn garbage_is_answered_and_the_connection_stays_usable() {
    let server = Server::start(&[]);
    let mut c = server.connect();
    let not_json = c.ask("this is not json");
    assert_eq!(not_json["ok"], json!(false));
    assert!(
        not_json["error"]
            .as_str()
            .is_some_and(|e| e.starts_with("not JSON")),
        "{not_json}"
    );
    for garbage in [r#"[1, 2]"#, r#"{"fly": true}"#, r#"{"ilmr": 3}"#, "{}"] {
        let answer = c.ask(garbage);
        assert_eq!(answer["ok"], json!(false), "{garbage}: {answer}");
        assert!(answer["error"].is_string(), "{garbage}: {answer}");
    }
    c.send_raw(b"\xff\xfe\n");
    let deadline = Instant::now() + PATIENCE;
    let not_utf8 = c.next_line(deadline).expect("an answer to bytes");
    assert_eq!(not_utf8["error"], json!("not UTF-8"));

    let status = c.ask(r#"{"status": true}"#);
    assert_eq!(status["ok"], json!(true), "{status}");
    assert!(status["pose"]["x"].is_number() && status["pose"]["h"].is_number());
    assert_eq!(status["activity"]["robot_at_rest"], json!(true));
    assert_eq!(status["activity"]["running_commands"], json!(0));
}

#[test]
fn a_subscriber_sees_the_movement_another_client_starts() {
    let server = Server::start(&["--robot", "moro", "--world", "office", "--seed", "3"]);
    let mut watcher = server.connect();
    let mut driver = server.connect();
    let subscribed = watcher.ask(r#"{"subscribe": "events", "id": 9}"#);
    assert_eq!(
        subscribed,
        json!({"ok": true, "t": subscribed["t"], "id": 9})
    );

    let before = driver.ask(r#"{"status": true}"#);
    let x0 = before["pose"]["x"].as_f64().expect("x");
    assert_eq!(driver.ask(r#"{"ilmr": "goahead(1)"}"#)["ok"], json!(true));

    let joined = watcher
        .event_where(|e| e["event"] == json!("line"))
        .expect("the line event");
    assert_eq!(joined["text"], json!("goahead(1)"));
    assert_eq!(joined["accepted"], json!(true));
    let started = watcher
        .event_where(|e| e["event"] == json!("start") && e["text"] == json!("goahead(1)"))
        .expect("the movement starts");
    assert!(started["t"].as_f64() >= joined["t"].as_f64());
    let moved = watcher
        .event_where(|e| e["event"] == json!("pose") && e["x"].as_f64() > Some(x0 + 0.1))
        .expect("the robot moves in the stream");
    assert_eq!(moved["source"], json!("true"));
    let ended = watcher
        .event_where(|e| e["event"] == json!("end") && e["text"] == json!("goahead(1)"))
        .expect("the movement ends");
    assert_eq!(ended["how"], json!("completed"), "{ended}");

    // The driver, who did not subscribe, got answers only.
    assert!(driver.events.is_empty());
    let after = driver.ask(r#"{"status": true}"#);
    let x1 = after["pose"]["x"].as_f64().expect("x");
    assert!((x1 - x0 - 1.0).abs() < 0.1, "went from {x0} to {x1}");
    assert!(after["t"].as_f64() > before["t"].as_f64());

    // A rejected line reaches the stream with its codes.
    assert_eq!(driver.ask(r#"{"ilmr": "goahed(1)"}"#)["ok"], json!(false));
    let refused = watcher
        .event_where(|e| e["event"] == json!("line") && e["accepted"] == json!(false))
        .expect("the rejected line");
    assert!(
        refused["codes"][0]
            .as_str()
            .is_some_and(|c| c.starts_with('E'))
    );
}

#[test]
fn the_status_names_the_supervisor_hold_in_force() {
    // The scanner goes dark a second in: the supervisor holds the robot.
    let world = std::env::temp_dir().join(format!("ilmr-serve-dark-{}.toml", std::process::id()));
    let empty = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/robots/worlds/empty.toml"
    ))
    .expect("the empty world");
    std::fs::write(
        &world,
        format!("{empty}\n[[fault]]\nkind = \"scanner_dropout\"\nstart = 1.0\n"),
    )
    .expect("a world file");
    let server = Server::start(&["--world", world.to_str().unwrap()]);
    let mut c = server.connect();
    let deadline = Instant::now() + PATIENCE;
    let held = loop {
        let status = c.ask(r#"{"status": true}"#);
        if status["faults"].as_array().is_some_and(|f| !f.is_empty()) {
            break status;
        }
        assert!(Instant::now() < deadline, "no fault in {status}");
        std::thread::sleep(Duration::from_millis(100));
    };
    let _ = std::fs::remove_file(&world);
    let fault = &held["faults"][0];
    assert_eq!(fault["fault"], json!("scanner_lost"), "{held}");
    assert_eq!(fault["code"], json!("R0202"), "{held}");
    assert_eq!(fault["reaction"], json!("hold"), "{held}");
    assert!(fault["help"].is_string(), "{held}");
}

#[test]
fn a_client_leaving_mid_line_disturbs_neither_robot_nor_others() {
    let server = Server::start(&[]);
    let mut watcher = server.connect();
    assert_eq!(watcher.ask(r#"{"subscribe": "events"}"#)["ok"], json!(true));
    {
        let mut leaver = server.connect();
        leaver.send_raw(br#"{"ilmr": "goahead(5)"}"#);
        // Gone without the newline that would have ended the request.
    }
    {
        let mut subscriber = server.connect();
        assert_eq!(
            subscriber.ask(r#"{"subscribe": "events"}"#)["ok"],
            json!(true)
        );
        subscriber.send_raw(b"{\"ilmr\": \"goahe");
    }
    // Both are gone; the watcher still gets answers, and nothing was joined.
    std::thread::sleep(Duration::from_millis(300));
    let status = watcher.ask(r#"{"status": true}"#);
    assert_eq!(status["ok"], json!(true));
    assert_eq!(status["activity"]["running_commands"], json!(0), "{status}");
    assert_eq!(status["activity"]["queued_movements"], json!(0), "{status}");
    assert!(
        !watcher.events.iter().any(|e| e["event"] == json!("line")),
        "{:?}",
        watcher.events
    );
    assert_eq!(
        watcher.ask(r#"{"ilmr": "goahead(0.2)"}"#)["ok"],
        json!(true)
    );
    assert!(
        watcher
            .event_where(|e| e["event"] == json!("start"))
            .is_some()
    );
}

#[test]
fn several_clients_are_answered_at_once() {
    let server = Server::start(&[]);
    let mut clients: Vec<Client> = (0..4).map(|_| server.connect()).collect();
    for (i, c) in clients.iter_mut().enumerate() {
        c.send_raw(format!("{{\"status\": true, \"id\": {i}}}\n").as_bytes());
    }
    for (i, c) in clients.iter_mut().enumerate() {
        let deadline = Instant::now() + PATIENCE;
        let answer = c.next_line(deadline).expect("an answer");
        assert_eq!(
            (answer["ok"].clone(), answer["id"].clone()),
            (json!(true), json!(i))
        );
    }
}

#[test]
fn a_port_in_use_or_a_bad_address_is_a_usage_error() {
    let server = Server::start(&[]);
    for (listen, says) in [
        (server.addr.as_str(), "in use"),
        ("192.0.2.1:7878", "loopback"),
        ("localhost", "expected an address and port"),
    ] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
            .args(["serve", "--no-tls", "--listen", listen])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start ilmrc serve");
        let deadline = Instant::now() + PATIENCE;
        let status = loop {
            if let Some(status) = child.try_wait().expect("wait") {
                break status;
            }
            if Instant::now() > deadline {
                let _ = child.kill();
                panic!("`serve --listen {listen}` did not exit");
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let mut stderr = String::new();
        let _ = child
            .stderr
            .take()
            .expect("piped stderr")
            .read_to_string(&mut stderr);
        assert_eq!(status.code(), Some(2), "{listen}: {stderr}");
        assert!(stderr.contains(says), "{listen}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// The operator's stop is above the task: a running `priority = highest` block, which
/// holds every other line back, does not hold it back.
#[test]
fn the_emergency_stop_halts_a_robot_driven_by_a_priority_block() {
    let dir = std::env::temp_dir().join(format!("ilmr-serve-priority-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let task = dir.join("priority.ilmr");
    std::fs::write(&task, "priority = highest\nspeed(0.4)\ngoahead(20)\n").expect("write task");
    let server = Server::start(&["--world", "empty", "--task", task.to_str().expect("utf-8")]);
    let mut c = server.connect();
    let speed = |c: &mut Client| {
        c.ask(r#"{"status": true}"#)["speed"]
            .as_f64()
            .unwrap_or(0.0)
    };
    let deadline = Instant::now() + PATIENCE;
    while speed(&mut c) < 0.3 {
        assert!(Instant::now() < deadline, "the task did not get going");
        std::thread::sleep(Duration::from_millis(50));
    }
    let stopped = c.ask(r#"{"stop": true}"#);
    assert_eq!(stopped["ok"], json!(true), "{stopped}");
    let deadline = Instant::now() + PATIENCE;
    while speed(&mut c) > 0.0 {
        assert!(Instant::now() < deadline, "the robot did not stop");
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_task_starts_with_the_server_and_a_bad_one_is_refused() {
    let dir = std::env::temp_dir().join(format!("ilmr-serve-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let good = dir.join("good.ilmr");
    let bad = dir.join("bad.ilmr");
    std::fs::write(&good, "m = goahead(0.5)\n").expect("write task");
    std::fs::write(&bad, "goahed(1)\n").expect("write task");

    let server = Server::start(&["--task", good.to_str().expect("utf-8 path")]);
    let mut c = server.connect();
    // The task's variable is there for lines to use.
    assert_eq!(
        c.ask(r#"{"ilmr": "wait(m)\ngoahead(0.2)"}"#)["ok"],
        json!(true)
    );
    let status = c.ask(r#"{"status": true}"#);
    let live = &status["activity"];
    assert!(
        live["running_commands"].as_u64() >= Some(1)
            || live["queued_movements"].as_u64() >= Some(1),
        "{status}"
    );
    drop(server);

    let out = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(["serve", "--no-tls", "--listen", "127.0.0.1:0", "--task"])
        .arg(&bad)
        .output()
        .expect("run ilmrc serve");
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("E0301"), "{stdout}");
    assert!(!stdout.contains("listening"), "{stdout}");
}

/// A line may call a parameterized skill of `--skills` with arguments the task never
/// gave (issue 17 item 6); a bad argument is rejected with the code `check` gives.
#[test]
fn a_line_calls_a_parameterized_skill_with_new_arguments() {
    let dir = std::env::temp_dir().join(format!("ilmr-serve-params-{}", std::process::id()));
    let skills = dir.join("skills");
    std::fs::create_dir_all(&skills).expect("temp dir");
    std::fs::write(
        skills.join("corner.ilms"),
        "Corner(d, side=left/right):\nm = goahead(d)\nwait(m)\nturn(side)\n",
    )
    .expect("write skills");
    let task = dir.join("task.ilmr");
    std::fs::write(&task, "Corner(0.5, left)\n").expect("write task");
    let server = Server::start(&[
        "--task",
        task.to_str().expect("utf-8 path"),
        "--skills",
        skills.to_str().expect("utf-8 path"),
    ]);
    let mut c = server.connect();
    let joined = c.ask(r#"{"ilmr": "Corner(1.5, right)"}"#);
    assert_eq!(joined["ok"], json!(true), "{joined}");
    let again = c.ask(r#"{"ilmr": "Corner(0.5, left)"}"#);
    assert_eq!(again["ok"], json!(true), "{again}");
    let status = c.ask(r#"{"status": true}"#);
    let live = &status["activity"];
    assert!(
        live["running_commands"].as_u64() >= Some(1)
            || live["queued_movements"].as_u64() >= Some(1),
        "{status}"
    );
    let bad = c.ask(r#"{"ilmr": "Corner(1.5, up)"}"#);
    assert!(rejected_with(&bad, "E0304"), "{bad}");
    let short = c.ask(r#"{"ilmr": "Corner(1.5)"}"#);
    assert!(rejected_with(&short, "E0302"), "{short}");
    drop(server);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_accepted_line_brings_its_warnings() {
    let server = Server::start(&[]);
    let mut c = server.connect();
    let warned = c.ask(r#"{"ilmr": "turn(d=90,c=2)", "id": 4}"#);
    assert_eq!(warned["ok"], json!(true), "{warned}");
    let warnings = warned["warnings"].as_array().expect("warnings");
    assert_eq!(warnings.len(), 1, "{warned}");
    assert_eq!(warnings[0]["code"], json!("W0405"));
    assert_eq!(warnings[0]["severity"], json!("warning"));
    assert_eq!(
        (warnings[0]["file"].as_str(), warnings[0]["column"].as_u64()),
        (Some("<line>"), Some(13))
    );
    // A clean line's answer has no `warnings`.
    let clean = c.ask(r#"{"ilmr": "speed(0.2)"}"#);
    assert_eq!(clean["ok"], json!(true));
    assert!(clean.get("warnings").is_none(), "{clean}");
}

// Garbage request lines over TCP, through this file's `Server` and `Client`.
#[path = "fuzz/serve_garbage.rs"]
mod serve_garbage;

#[path = "serve/flood.rs"]
mod flood;

#[path = "serve/exhaustion.rs"]
mod exhaustion;

#[path = "serve/secure.rs"]
mod secure;

#[test]
fn a_blank_line_is_answered_so_a_planner_never_waits_for_nothing() {
    let server = Server::start(&[]);
    let mut c = server.connect();
    for blank in ["", "   ", "\r"] {
        let answer = c.ask(blank);
        assert_eq!(answer["ok"], json!(false), "{blank:?}: {answer}");
        assert_eq!(
            answer["error"],
            json!("empty line: send one JSON object per line"),
            "{blank:?}"
        );
    }
    assert_eq!(c.ask(r#"{"status": true, "id": 4}"#)["id"], json!(4));
}

/// `x = ((...1...))` with `depth` parentheses.
fn nested_parens(depth: usize) -> String {
    format!("x = {}1{}", "(".repeat(depth), ")".repeat(depth))
}

/// `x = 1+1+...` with `terms` terms.
fn plus_chain(terms: usize) -> String {
    format!("x = 1{}", "+1".repeat(terms.saturating_sub(1)))
}

/// `depth` `if` blocks, one inside the other.
fn nested_ifs(depth: usize) -> String {
    format!(
        "n = 1\n{}n = 2\n{}",
        "if(n>0)\n".repeat(depth),
        "endif\n".repeat(depth)
    )
}

/// A rejected answer whose diagnostics include the error `code`.
fn rejected_with(answer: &Value, code: &str) -> bool {
    answer["ok"] == json!(false)
        && answer["diagnostics"].as_array().is_some_and(|d| {
            d.iter()
                .any(|d| d["severity"] == json!("error") && d["code"] == json!(code))
        })
}

#[test]
fn a_line_nested_past_the_limits_is_answered_and_everyone_else_goes_on() {
    let server = Server::start(&[]);
    let mut other = server.connect();
    assert_eq!(
        other.ask(r#"{"ilmr": "m = goahead(0.3)"}"#)["ok"],
        json!(true)
    );
    // Each just under the 1 MiB request limit, so the compiler sees it whole.
    // E0104: more than 256 operators and parentheses on a line; E0210: more than 256
    // nested blocks (docs/diagnostics.md).
    for (what, text, code) in [
        ("parentheses", nested_parens(400_000), "E0104"),
        ("a + chain", plus_chain(400_000), "E0104"),
        ("nested ifs", nested_ifs(50_000), "E0210"),
        ("parentheses", nested_parens(3_000), "E0104"),
        ("nested ifs", nested_ifs(3_000), "E0210"),
    ] {
        let mut c = server.connect();
        let answer = c.ask(&json!({ "ilmr": text, "id": what }).to_string());
        assert!(rejected_with(&answer, code), "{what}: {answer}");
        assert_eq!(answer["id"], json!(what));
        // The same connection, another client and the running task go on.
        assert_eq!(c.ask(r#"{"ilmr": "k = 1"}"#)["ok"], json!(true), "{what}");
        let status = other.ask(r#"{"status": true}"#);
        assert_eq!(status["ok"], json!(true), "{what}: {status}");
    }
    // Past the request limit: refused before the compiler, this connection closed.
    for text in [nested_parens(1_000_000), plus_chain(1_000_000)] {
        let mut c = server.connect();
        let answer = c.ask(&json!({ "ilmr": text }).to_string());
        assert_eq!(answer["ok"], json!(false), "{answer}");
        assert!(
            answer["error"]
                .as_str()
                .is_some_and(|e| e.starts_with("request line longer than")),
            "{answer}"
        );
    }
    let status = other.ask(r#"{"status": true}"#);
    assert!(status["ticks"].as_u64() > Some(0), "{status}");
    assert_eq!(other.ask(r#"{"ilmr": "wait(m)"}"#)["ok"], json!(true));
}

#[test]
fn a_task_nested_past_the_limits_is_a_clear_error_before_listening() {
    let dir = std::env::temp_dir().join(format!("ilmr-serve-deep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    // 3,000 and 500,000 levels reach the compiler; 1,000,000 (14 MB) is over the
    // source file limit and is refused unread.
    for (depth, code, says) in [
        (3_000, 1, "E0210"),
        (500_000, 1, "E0210"),
        (1_000_000, 2, "the limit for a task or skill file"),
    ] {
        let task = dir.join(format!("deep{depth}.ilmr"));
        std::fs::write(&task, nested_ifs(depth)).expect("write task");
        let mut child = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
            .args(["serve", "--no-tls", "--listen", "127.0.0.1:0", "--task"])
            .arg(&task)
            .env("NO_COLOR", "1")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start ilmrc serve");
        let deadline = Instant::now() + Duration::from_secs(120);
        let status = loop {
            if let Some(status) = child.try_wait().expect("wait") {
                break status;
            }
            if Instant::now() > deadline {
                let _ = child.kill();
                panic!("serve --task with {depth} nested ifs did not end");
            }
            std::thread::sleep(Duration::from_millis(50));
        };
        let mut out = String::new();
        let mut err = String::new();
        let _ = child.stdout.take().map(|mut s| s.read_to_string(&mut out));
        let _ = child.stderr.take().map(|mut s| s.read_to_string(&mut err));
        assert_eq!(status.code(), Some(code), "{depth}: {out}{err}");
        assert!(!out.contains("listening"), "{depth}: {out}");
        assert!(format!("{out}{err}").contains(says), "{depth}: {out}{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A fleet file of two simulated robots in the empty world, in a scratch directory.
fn two_robot_fleet(test: &str) -> std::path::PathBuf {
    let fleet = std::env::temp_dir().join(format!(
        "ilmr-serve-fleet-{}-{test}.toml",
        std::process::id()
    ));
    std::fs::write(
        &fleet,
        "[[robot]]\nname = \"a\"\nrobot = \"moro\"\nworld = \"empty\"\nstart = \"0,0,0\"\n\n\
         [[robot]]\nname = \"b\"\nrobot = \"moro\"\nworld = \"empty\"\nstart = \"0,5,0\"\n",
    )
    .unwrap();
    fleet
}

#[test]
fn a_fleet_server_routes_each_request_to_the_robot_it_names() {
    let fleet = two_robot_fleet("route");
    let server = Server::start(&["--fleet", fleet.to_str().unwrap()]);
    let mut c = server.connect();
    let to_b = c.ask(r#"{"robot": "b", "ilmr": "goahead(1)", "id": 1}"#);
    assert_eq!(to_b["ok"], json!(true), "{to_b}");
    assert_eq!((&to_b["robot"], &to_b["id"]), (&json!("b"), &json!(1)));
    // Only b moves.
    let deadline = Instant::now() + PATIENCE;
    loop {
        let all = c.ask(r#"{"status": true}"#);
        let (a, b) = (&all["robots"]["a"], &all["robots"]["b"]);
        assert!(a["ok"] == json!(true) && b["ok"] == json!(true), "{all}");
        if b["speed"].as_f64().unwrap() > 0.05 {
            assert_eq!(a["speed"].as_f64().unwrap(), 0.0, "{all}");
            break;
        }
        assert!(Instant::now() < deadline, "b never moved: {all}");
        std::thread::sleep(Duration::from_millis(100));
    }
    let one = c.ask(r#"{"robot": "a", "status": true}"#);
    assert_eq!(one["robot"], json!("a"));
    assert!(one["pose"].is_object(), "{one}");
    for (request, says) in [
        (r#"{"ilmr": "goahead(1)"}"#, "name the robot"),
        (r#"{"robot": "c", "ilmr": "goahead(1)"}"#, "no robot `c`"),
        (r#"{"robot": 7, "status": true}"#, "robot's name"),
    ] {
        let e = c.ask(request);
        assert_eq!(e["ok"], json!(false), "{request}: {e}");
        assert!(
            e["error"].as_str().unwrap().contains(says),
            "{request}: {e}"
        );
    }
    let _ = std::fs::remove_file(&fleet);
}

#[test]
fn a_fleet_stop_without_a_name_stops_every_robot_and_with_one_that_robot() {
    let fleet = two_robot_fleet("stop");
    let server = Server::start(&["--fleet", fleet.to_str().unwrap()]);
    let mut c = server.connect();
    for robot in ["a", "b"] {
        let go = c.ask(&json!({"robot": robot, "ilmr": "speed(0.3)\ngoahead(100)"}).to_string());
        assert_eq!(go["ok"], json!(true), "{go}");
    }
    let speeds = |c: &mut Client| {
        let all = c.ask(r#"{"status": true}"#);
        ["a", "b"].map(|r| all["robots"][r]["speed"].as_f64().unwrap_or(f64::NAN))
    };
    let until = |c: &mut Client, what: &str, done: &dyn Fn([f64; 2]) -> bool| {
        let deadline = Instant::now() + PATIENCE;
        loop {
            let v = speeds(c);
            if done(v) {
                return;
            }
            assert!(Instant::now() < deadline, "{what}: {v:?}");
            std::thread::sleep(Duration::from_millis(50));
        }
    };
    until(&mut c, "both drive", &|v| v.iter().all(|s| *s > 0.2));
    let one = c.ask(r#"{"robot": "a", "stop": true, "id": 1}"#);
    assert_eq!(
        (&one["ok"], &one["robot"], &one["id"]),
        (&json!(true), &json!("a"), &json!(1)),
        "{one}"
    );
    until(&mut c, "a halts, b drives on", &|v| {
        v[0].abs() < 1e-3 && v[1] > 0.2
    });
    let all = c.ask(r#"{"stop": true}"#);
    assert_eq!(all["ok"], json!(true), "{all}");
    for robot in ["a", "b"] {
        assert_eq!(all["robots"][robot]["ok"], json!(true), "{all}");
        assert!(all["robots"][robot]["t"].is_number(), "{all}");
    }
    until(&mut c, "both halt", &|v| v.iter().all(|s| s.abs() < 1e-3));
    let _ = std::fs::remove_file(&fleet);
}

#[test]
fn a_fleet_subscriber_gets_every_robots_events_each_named() {
    let fleet = two_robot_fleet("subscribe");
    let server = Server::start(&["--fleet", fleet.to_str().unwrap()]);
    let mut c = server.connect();
    let sub = c.ask(r#"{"subscribe": "events"}"#);
    assert_eq!(sub["robots"], json!(["a", "b"]), "{sub}");
    let mut planner = server.connect();
    for robot in ["a", "b"] {
        let ok = planner.ask(&format!(
            r#"{{"robot": "{robot}", "ilmr": "goahead(0.5)"}}"#
        ));
        assert_eq!(ok["ok"], json!(true), "{ok}");
    }
    for robot in ["a", "b"] {
        let started = c.event_where(|e| e["event"] == "start" && e["robot"] == robot);
        assert!(
            started.is_some(),
            "no start event of {robot}: {:?}",
            c.events
        );
    }
    let _ = std::fs::remove_file(&fleet);
}

#[test]
fn a_single_robot_server_refuses_a_robots_name_and_fleet_with_robot_options() {
    let server = Server::start(&[]);
    let mut c = server.connect();
    let e = c.ask(r#"{"robot": "a", "status": true}"#);
    assert!(e["error"].as_str().unwrap().contains("one robot"), "{e}");
    let out = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args([
            "serve",
            "--no-tls",
            "--listen",
            "127.0.0.1:0",
            "--fleet",
            "x.toml",
            "--robot",
            "moro",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot be used with"));
}
