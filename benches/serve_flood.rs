//! The emergency stop and the tick under floods (issue 19, docs/performance.md): a
//! real `ilmrc serve` on loopback, the robot driving at 0.4 m/s, and N clients that
//! each send requests as fast as they are answered. For each flood, a new client
//! connects and sends `{"stop": true}` several times (with `cont` between); the
//! figures are the wall time from writing the stop to reading its acknowledgement
//! (sent once the robot has been commanded to brake) and the server's own longest
//! gap between two ticks (`longest_tick_gap` in `status`). A fresh server per flood,
//! so each gap is that flood's.
//!
//! Before the floods: what an idle client costs, and how long an authenticated driver
//! waits over TLS, quiet and behind 1,200 connections that hold places.
//!
//! `cargo bench -p ilmrc --bench serve_flood` (ILMR_FLOOD_SAMPLES, default 5;
//! ILMR_FLOOD_CLIENTS, the large floods' clients, default 63; ILMR_SERVE_BIN, another
//! `ilmrc` to measure, e.g. one built from an older commit).

use std::io::{BufRead, BufReader, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use rustls::pki_types::pem::PemObject;
use serde_json::Value;

struct Server {
    child: Child,
    addr: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn exe() -> String {
    std::env::var("ILMR_SERVE_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_ilmrc").into())
}

fn start() -> Server {
    start_with(&["--no-tls"])
}

fn start_with(security: &[&str]) -> Server {
    let mut child = Command::new(exe())
        .args(["serve", "--listen", "127.0.0.1:0", "--world", "empty"])
        .args(security)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start ilmrc serve");
    let mut first = String::new();
    BufReader::new(child.stdout.take().expect("stdout"))
        .read_line(&mut first)
        .expect("the address line");
    let addr = first
        .strip_prefix("listening on ")
        .and_then(|r| r.split_whitespace().next())
        .expect("listening on ADDR")
        .to_string();
    Server { child, addr }
}

struct Client {
    stream: TcpStream,
    reader: BufReader<TcpStream>,
}

impl Client {
    fn connect(addr: &str) -> Client {
        let stream = TcpStream::connect(addr).expect("connect");
        stream.set_nodelay(true).expect("nodelay");
        stream
            .set_read_timeout(Some(Duration::from_secs(120)))
            .expect("timeout");
        Client {
            reader: BufReader::new(stream.try_clone().expect("clone")),
            stream,
        }
    }

    fn ask(&mut self, request: &str) -> Value {
        self.try_ask(request)
            .expect("an answer before the server closes the connection")
    }

    /// The answer, or `None` once the server has closed the connection.
    fn try_ask(&mut self, request: &str) -> Option<Value> {
        self.stream
            .write_all(format!("{request}\n").as_bytes())
            .ok()?;
        loop {
            let mut line = String::new();
            if self.reader.read_line(&mut line).ok()? == 0 {
                return None;
            }
            let v: Value = serde_json::from_str(&line).expect("JSON");
            if v.get("event").is_none() {
                return Some(v);
            }
        }
    }

    fn speed(&mut self) -> f64 {
        self.ask(r#"{"status": true}"#)["speed"]
            .as_f64()
            .unwrap_or(f64::NAN)
    }

    fn wait_for(&mut self, ok: impl Fn(f64) -> bool) {
        let deadline = Instant::now() + Duration::from_secs(300);
        while !ok(self.speed()) {
            assert!(Instant::now() < deadline, "the robot did not get there");
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

struct Flood {
    name: &'static str,
    clients: usize,
    request: String,
}

/// The large floods' clients: 63 (ILMR_FLOOD_CLIENTS), which with the driver fill
/// the 64 places, so the operator's stop comes to a full server.
fn flood_clients() -> usize {
    std::env::var("ILMR_FLOOD_CLIENTS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(63)
}

fn heavy_line(terms: usize) -> String {
    let sum = vec!["1"; terms].join("+");
    format!(r#"{{"ilmr": "x={sum}"}}"#)
}

struct Figures {
    /// Why the operator's stop was not taken, if it was not.
    refused: Option<String>,
    stops_ms: Vec<f64>,
    longest_gap_ms: f64,
    answered: u64,
    sim_per_wall: f64,
}

fn measure(flood: &Flood, samples: usize) -> Figures {
    let server = start();
    let mut driver = Client::connect(&server.addr);
    assert_eq!(
        driver.ask(r#"{"ilmr": "speed(0.4)\ngoahead(1000)"}"#)["ok"],
        true
    );
    driver.wait_for(|v| v > 0.3);
    let running = Arc::new(AtomicBool::new(true));
    let answered = Arc::new(AtomicU64::new(0));
    let flooders: Vec<_> = (0..flood.clients)
        .map(|_| {
            let mut c = Client::connect(&server.addr);
            let (running, answered) = (Arc::clone(&running), Arc::clone(&answered));
            let request = flood.request.clone();
            std::thread::spawn(move || {
                while running.load(Ordering::SeqCst) && c.try_ask(&request).is_some() {
                    answered.fetch_add(1, Ordering::SeqCst);
                }
            })
        })
        .collect();
    std::thread::sleep(Duration::from_secs(1));
    let t0 = driver.ask(r#"{"status": true}"#)["t"]
        .as_f64()
        .unwrap_or(0.0);
    let wall0 = Instant::now();
    let mut stops_ms = Vec::new();
    let mut refused = None;
    for _ in 0..samples {
        // An operator's new connection, as in an emergency.
        let mut operator = Client::connect(&server.addr);
        let sent = Instant::now();
        let ack = operator.ask(r#"{"stop": true}"#);
        stops_ms.push(sent.elapsed().as_secs_f64() * 1e3);
        if ack["ok"] != true {
            refused = Some(ack.to_string());
            break;
        }
        driver.wait_for(|v| v.abs() < 1e-3);
        assert_eq!(driver.ask(r#"{"cont": true}"#)["ok"], true);
        driver.wait_for(|v| v > 0.3);
    }
    let status = driver.ask(r#"{"status": true}"#);
    let sim = status["t"].as_f64().unwrap_or(0.0) - t0;
    let sim_per_wall = sim / wall0.elapsed().as_secs_f64();
    running.store(false, Ordering::SeqCst);
    drop(server);
    for f in flooders {
        let _ = f.join();
    }
    Figures {
        refused,
        stops_ms,
        longest_gap_ms: status["longest_tick_gap"].as_f64().unwrap_or(f64::NAN) * 1e3,
        answered: answered.load(Ordering::SeqCst),
        sim_per_wall,
    }
}

/// The server's resident memory, KiB.
fn rss_kib(server: &Server) -> u64 {
    std::fs::read_to_string(format!("/proc/{}/status", server.child.id()))
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("VmRSS:"))
                .and_then(|v| v.split_whitespace().next()?.parse().ok())
        })
        .unwrap_or(0)
}

/// What a client that spoke once and then idles costs the server (64 of them, the
/// places there are), and how long a newcomer waits after 1,000 silent connections.
fn places() {
    let server = start();
    Client::connect(&server.addr).ask(r#"{"status": true}"#);
    std::thread::sleep(Duration::from_millis(200));
    let before = rss_kib(&server);
    let idle: Vec<Client> = (0..64)
        .map(|_| {
            let mut c = Client::connect(&server.addr);
            c.ask(r#"{"status": true}"#);
            c
        })
        .collect();
    std::thread::sleep(Duration::from_millis(200));
    let grown = rss_kib(&server).saturating_sub(before);
    drop(idle);
    let silent: Vec<TcpStream> = (0..1000)
        .map(|_| TcpStream::connect(&server.addr).expect("connect"))
        .collect();
    let asked = Instant::now();
    let answer = Client::connect(&server.addr).ask(r#"{"status": true}"#);
    let newcomer_ms = asked.elapsed().as_secs_f64() * 1e3;
    drop(silent);
    println!(
        "resident memory of 64 idle clients: {grown} KiB; a newcomer after 1,000 \
         silent connections answered in {newcomer_ms:.1} ms ({})",
        answer.get("error").unwrap_or(&answer["ok"])
    );
}

/// A driver's wall time from connecting to the answer of its first `status` over
/// TLS: the TCP connection, the handshake (rustls, the server's CA), `{"auth": TOKEN}`
/// and `status`. Quiet, then with 1,000 silent connections and 200 that sent bytes
/// that are not TLS held open.
fn tls_drivers(samples: usize) {
    let dir = std::env::temp_dir().join(format!("ilmr-bench-creds-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let made = Command::new(exe())
        .args(["serve", "--init-credentials"])
        .arg(&dir)
        .output()
        .expect("run ilmrc");
    assert!(made.status.success(), "--init-credentials failed");
    let server = start_with(&["--credentials", dir.to_str().expect("UTF-8 path")]);
    let token = std::fs::read_to_string(dir.join("planner.token")).expect("a token");
    let mut roots = rustls::RootCertStore::empty();
    for cert in rustls::pki_types::CertificateDer::pem_file_iter(dir.join("ca.pem"))
        .expect("ca.pem")
        .flatten()
    {
        roots.add(cert).expect("a CA certificate");
    }
    let provider = Arc::new(rustls::crypto::ring::default_provider());
    let config = Arc::new(
        rustls::ClientConfig::builder_with_provider(provider)
            .with_safe_default_protocol_versions()
            .expect("TLS versions")
            .with_root_certificates(roots)
            .with_no_client_auth(),
    );
    let drive = || {
        let asked = Instant::now();
        let tcp = TcpStream::connect(&server.addr).expect("connect");
        tcp.set_nodelay(true).expect("nodelay");
        let name = rustls::pki_types::ServerName::try_from("localhost").expect("a name");
        let conn = rustls::ClientConnection::new(Arc::clone(&config), name).expect("TLS");
        let mut tls = rustls::StreamOwned::new(conn, tcp);
        let request = format!("{{\"auth\": \"{}\"}}\n{{\"status\": true}}\n", token.trim());
        tls.write_all(request.as_bytes()).expect("send");
        let mut reader = BufReader::new(tls);
        let mut line = String::new();
        for _ in 0..2 {
            line.clear();
            reader.read_line(&mut line).expect("an answer");
        }
        let status: Value = serde_json::from_str(&line).expect("JSON");
        assert_eq!(status["you"]["role"], "driver", "{status}");
        asked.elapsed().as_secs_f64() * 1e3
    };
    let figures = |label: &str, drive: &dyn Fn() -> f64| {
        let mut ms: Vec<f64> = (0..samples).map(|_| drive()).collect();
        ms.sort_by(f64::total_cmp);
        println!(
            "| TLS driver served (connect, handshake, auth, status), {label} | {:.1} / {:.1} ms |",
            ms[ms.len() / 2],
            ms[ms.len() - 1]
        );
    };
    println!("| newcomer | median / max of {samples} |");
    println!("| --- | ---: |");
    figures("quiet", &drive);
    let mut held: Vec<TcpStream> = (0..1000)
        .map(|_| TcpStream::connect(&server.addr).expect("connect"))
        .collect();
    for _ in 0..200 {
        let mut s = TcpStream::connect(&server.addr).expect("connect");
        let _ = s.write_all(b"GET / HTTP/1.1\r\n\r\n\x16\x03\x01\xff\xff");
        held.push(s);
    }
    figures("after 1,000 silent and 200 garbage connections", &drive);
    drop(held);
    let _ = std::fs::remove_dir_all(&dir);
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is taken.
    let samples: usize = std::env::var("ILMR_FLOOD_SAMPLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let floods = [
        Flood {
            name: "none",
            clients: 0,
            request: String::new(),
        },
        Flood {
            name: "8 clients, 20 KB lines of 5,000 terms",
            clients: 8,
            request: heavy_line(5000),
        },
        Flood {
            name: "63 (or N) clients, 20 KB lines of 5,000 terms",
            clients: flood_clients(),
            request: heavy_line(5000),
        },
        Flood {
            name: "63 (or N) clients, accepted lines (`y = 1`)",
            clients: flood_clients(),
            request: r#"{"ilmr": "y = 1"}"#.into(),
        },
        Flood {
            name: "63 (or N) clients, status",
            clients: flood_clients(),
            request: r#"{"status": true}"#.into(),
        },
    ];
    places();
    tls_drivers(samples.max(5));
    println!(
        "| flood | stop acknowledged, ms (median / max of {samples}) | longest tick gap, ms | flood answers | simulated s per wall s |"
    );
    println!("| --- | ---: | ---: | ---: | ---: |");
    for flood in &floods {
        let mut f = measure(flood, samples);
        if let Some(why) = f.refused {
            println!("| {} | refused: {why} | | {} | |", flood.name, f.answered);
            continue;
        }
        f.stops_ms.sort_by(f64::total_cmp);
        let median = f.stops_ms[f.stops_ms.len() / 2];
        let max = f.stops_ms.last().copied().unwrap_or(f64::NAN);
        println!(
            "| {} | {median:.1} / {max:.1} | {:.1} | {} | {:.3} |",
            flood.name, f.longest_gap_ms, f.answered, f.sim_per_wall
        );
    }
}
