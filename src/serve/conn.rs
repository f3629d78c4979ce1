//! One client connection: a reader that turns request lines into jobs for the VM
//! thread and waits for each answer, and a writer that owns the socket's sending side
//! (answers and, once subscribed, events, in the order they were queued).

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::sync::Arc;
use std::sync::mpsc::{self, Sender, SyncSender};
use std::time::Duration;

use serde_json::{Map, Value};

use super::protocol::{self, Parsed, Request};
use super::reply;
use crate::live::Robots;
use crate::live::engine::Job;
use crate::live::guard::guarded;

use crate::live::MAX_LINE_BYTES as MAX_LINE;

/// Lines queued for a connection before a subscriber that does not read is dropped.
const OUT_QUEUE: usize = 4096;

/// The VM thread answers between two ticks; this is only a guard against it having
/// stopped.
const ANSWER_WAIT: Duration = Duration::from_secs(10);

/// Serves one client until it closes the connection, sends a line that is too long,
/// or the socket fails. Never touches a robot except through its jobs.
pub fn serve(stream: TcpStream, conn: u64, robots: Arc<Robots>) {
    let _ = stream.set_nodelay(true);
    let Ok(send_side) = stream.try_clone() else {
        return;
    };
    let (out, queued) = mpsc::sync_channel::<String>(OUT_QUEUE);
    let writer = std::thread::spawn(move || write_lines(send_side, queued));
    read_requests(stream, conn, &robots, &out);
    for (_, live) in robots.all() {
        let _ = live.jobs.send(Job::Unsubscribe { conn });
    }
    // The writer ends once every sender is gone: this one, and the engine's clone
    // (dropped on `Unsubscribe`), after flushing what was queued.
    drop(out);
    let _ = writer.join();
}

fn write_lines(mut stream: TcpStream, queued: mpsc::Receiver<String>) {
    for mut line in queued {
        line.push('\n');
        if stream.write_all(line.as_bytes()).is_err() || stream.flush().is_err() {
            // The client is gone; the reader sees that too and ends the connection.
            let _ = stream.shutdown(std::net::Shutdown::Both);
            return;
        }
    }
}

fn read_requests(stream: TcpStream, conn: u64, robots: &Robots, out: &SyncSender<String>) {
    let mut reader = BufReader::new(stream);
    let mut buf = Vec::new();
    loop {
        buf.clear();
        let read = (&mut reader)
            .take(MAX_LINE as u64 + 1)
            .read_until(b'\n', &mut buf);
        match read {
            Ok(0) | Err(_) => return,
            Ok(_) => {}
        }
        if buf.last() != Some(&b'\n') {
            if buf.len() > MAX_LINE {
                let message = format!("request line longer than {MAX_LINE} bytes");
                let _ = out.send(protocol::answer(protocol::error(&message), None));
            }
            // Otherwise the client went away mid-line: half a request is not run.
            return;
        }
        let line = match std::str::from_utf8(&buf) {
            Ok(text) => text.trim(),
            Err(_) => {
                let answer = protocol::error("not UTF-8");
                if out.send(protocol::answer(answer, None)).is_err() {
                    return;
                }
                continue;
            }
        };
        // A planner that waits for one answer per line it sent must not wait forever
        // for a blank one.
        if line.is_empty() {
            let answer = protocol::error("empty line: send one JSON object per line");
            if out.send(protocol::answer(answer, None)).is_err() {
                return;
            }
            continue;
        }
        // Parsing the request and rendering its answer happen on this thread; a panic
        // there is this request's error, not the end of the connection.
        let answered = guarded("answering the request", || {
            let parsed = protocol::parse(line);
            ask(&parsed, conn, robots, out).map(|mut a| {
                if let (true, Some(name)) = (robots.is_fleet(), &parsed.robot) {
                    a.insert("robot".into(), Value::String(name.clone()));
                }
                protocol::answer(a, parsed.id.as_ref())
            })
        });
        let answer = match answered {
            Ok(Some(answer)) => answer,
            Ok(None) => continue,
            Err(why) => protocol::answer(protocol::error(&why), None),
        };
        if out.send(answer).is_err() {
            return;
        }
    }
}

/// The answer to one request: from the VM thread, or an error object; `None` when
/// the engine has queued it itself (a subscription).
fn ask(
    parsed: &Parsed,
    conn: u64,
    robots: &Robots,
    out: &SyncSender<String>,
) -> Option<Map<String, Value>> {
    if let Request::Invalid(why) = &parsed.request {
        return Some(protocol::error(why));
    }
    // A fleet's status and events without a robot's name are the whole fleet's.
    if robots.is_fleet() && parsed.robot.is_none() {
        match &parsed.request {
            Request::Status => return Some(fleet_status(robots)),
            Request::Subscribe => return Some(subscribe_all(conn, robots, out)),
            _ => {}
        }
    }
    let jobs = match robots.route(parsed.robot.as_deref()) {
        Ok(live) => &live.jobs,
        Err(why) => return Some(protocol::error(&why)),
    };
    match &parsed.request {
        Request::Invalid(why) => Some(protocol::error(why)),
        Request::Ilmr(text) => {
            let (reply, answer) = mpsc::channel();
            let job = Job::Line {
                text: text.clone(),
                reply,
            };
            Some(await_answer(jobs, job, &answer).map_or_else(|e| e, |a| reply::line(&a, text)))
        }
        Request::Status => {
            let (reply, answer) = mpsc::channel();
            let job = Job::Status { reply };
            Some(await_answer(jobs, job, &answer).map_or_else(|e| e, |s| reply::status(&s)))
        }
        Request::Subscribe => subscribe(conn, parsed.id.clone(), jobs, out),
    }
}

/// Sends `job` and waits for what it answers on `answer`; an error object when the VM
/// thread is gone or silent.
fn await_answer<T>(
    jobs: &Sender<Job>,
    job: Job,
    answer: &mpsc::Receiver<T>,
) -> Result<T, Map<String, Value>> {
    if jobs.send(job).is_err() {
        return Err(protocol::error("the robot has stopped"));
    }
    answer
        .recv_timeout(ANSWER_WAIT)
        .map_err(|_| protocol::error("the robot did not answer"))
}

/// Subscribes this connection; the engine queues the answer itself (so it comes
/// before the first event), hence `None` once it has.
fn subscribe(
    conn: u64,
    id: Option<Value>,
    jobs: &Sender<Job>,
    out: &SyncSender<String>,
) -> Option<Map<String, Value>> {
    let (done, acknowledged) = mpsc::channel();
    let job = Job::Subscribe {
        conn,
        out: out.clone(),
        first: Some(Box::new(move |t| {
            protocol::answer(reply::subscribed(t), id.as_ref())
        })),
        done,
    };
    if jobs.send(job).is_err() {
        return Some(protocol::error("the robot has stopped"));
    }
    match acknowledged.recv_timeout(ANSWER_WAIT) {
        Ok(()) => None,
        Err(_) => Some(protocol::error("the robot did not answer")),
    }
}

/// `{"ok": true, "robots": {NAME: status, ...}}`: every robot's, asked at once.
fn fleet_status(robots: &Robots) -> Map<String, Value> {
    let mut each = Map::new();
    for (name, status) in robots.statuses(ANSWER_WAIT) {
        let status = status.map_or_else(protocol::error, |s| reply::status(&s));
        each.insert(name.to_string(), Value::Object(status));
    }
    let mut m = Map::new();
    m.insert("ok".into(), Value::Bool(true));
    m.insert("robots".into(), Value::Object(each));
    m
}

/// Subscribes this connection to every robot of the fleet. Each robot's events name
/// it; they may come before this answer, which is sent once every robot has taken the
/// subscription.
fn subscribe_all(conn: u64, robots: &Robots, out: &SyncSender<String>) -> Map<String, Value> {
    let mut waiting = Vec::new();
    for (name, live) in robots.all() {
        let (done, acknowledged) = mpsc::channel();
        let job = Job::Subscribe {
            conn,
            out: out.clone(),
            first: None,
            done,
        };
        if live.jobs.send(job).is_err() {
            return protocol::error(&format!("robot `{name}` has stopped"));
        }
        waiting.push((name, acknowledged));
    }
    for (name, acknowledged) in waiting {
        if acknowledged.recv_timeout(ANSWER_WAIT).is_err() {
            return protocol::error(&format!("robot `{name}` did not answer"));
        }
    }
    let mut m = Map::new();
    m.insert("ok".into(), Value::Bool(true));
    m.insert("subscribed".into(), Value::String("events".into()));
    m.insert(
        "robots".into(),
        Value::Array(robots.names().map(|n| Value::String(n.into())).collect()),
    );
    m
}
