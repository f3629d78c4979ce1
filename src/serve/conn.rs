//! One client connection, as a task (not a thread): a reader that frames request
//! lines under the request timeout, an answerer that takes them in order (one answer
//! outstanding: the next request waits until the last answer was written, which is
//! the backpressure on a client that does not read), a writer that owns the socket's
//! sending side, and a watchdog for the idle timeout and eviction. An emergency stop
//! read while earlier requests still wait takes effect at once (and again in its
//! place, so a `cont` sent before it cannot undo it).

use std::net::SocketAddr;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::Sender;
use std::time::{Duration, Instant};

use serde_json::{Map, Value};
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt, ReadHalf, WriteHalf};
use tokio::sync::{mpsc, oneshot};

use super::Server;
use super::admit::{MAX_CLIENTS, Place};
use super::client::{
    Client, audit_answer, authenticate, hold_lease, lease_answer, may_drive, robot_and_why,
    status_of_client,
};
use super::outbox::Outbox;
use super::protocol::{self, Parsed, Request};
use super::reply;
use crate::live::engine::{Job, LineAnswer};
use crate::live::guard::guarded;
use crate::live::reply::Reply;
use crate::live::{Live, Robots};

use crate::live::MAX_LINE_BYTES as MAX_LINE;

/// The engine answers between two ticks and compiles lines in order on one thread;
/// this bounds a wait for a line behind every other client's (72 at most).
const ANSWER_WAIT: Duration = Duration::from_secs(60);
/// Bytes read from the socket at once; with an empty line buffer this is what an
/// idle client costs besides its task.
const READ_CHUNK: usize = 4096;
/// Requests read ahead of the one being answered, so that a `stop` behind them is
/// seen.
const READ_AHEAD: usize = 4;
/// Bytes of requests waiting to be answered past which no more are read: a client
/// holds at most this, its one line in progress and the one being answered.
const READ_AHEAD_BYTES: usize = 64 << 10;
/// A line buffer larger than this is given back once empty (after a large line).
const KEEP_BUFFER: usize = 64 << 10;
/// How long a closing client's last lines may take to go out.
const GOODBYE_WAIT: Duration = Duration::from_secs(1);

/// The requests read and not yet answered.
#[derive(Default)]
struct Pending {
    requests: AtomicUsize,
    bytes: AtomicUsize,
    answered: tokio::sync::Notify,
}

enum Item {
    Line(Vec<u8>),
    /// The reader ended the connection; say why (in order, after what is pending).
    Close(String),
}

/// Serves one client until it closes, breaks a limit, times out or is evicted.
/// Never touches a robot except through its jobs and its emergency stop. The stream
/// is a TCP socket or a TLS session whose handshake is done.
pub async fn serve<S>(stream: S, place: Arc<Place>, server: Arc<Server>, peer: Option<SocketAddr>)
where
    S: AsyncRead + AsyncWrite + Send + 'static,
{
    let conn = place.conn;
    let robots = &server.robots;
    let (read, write) = tokio::io::split(stream);
    let outbox = Arc::new(Outbox::default());
    let mut writer = tokio::spawn(write_out(write, Arc::clone(&outbox), Arc::clone(&place)));
    let (items, queue) = mpsc::channel(READ_AHEAD);
    let pending = Pending::default();
    let client = Client {
        conn,
        place: &place,
        server: &server,
        outbox: &outbox,
        peer,
    };
    // The answerer ends the connection (a failed authentication, a limit); a reader
    // that ends (the client left) leaves what it read to be answered first.
    let work = async {
        let reader = read_lines(
            read,
            items,
            &pending,
            robots,
            &place,
            server.timeouts.request,
        );
        let answerer = answer_requests(queue, &client, &pending);
        tokio::pin!(reader, answerer);
        tokio::select! {
            () = &mut answerer => {}
            () = &mut reader => answerer.await,
        }
    };
    let ended = tokio::select! {
        () = work => None,
        why = watchdog(&place, server.timeouts.idle) => Some(why),
    };
    if let Some(why) = ended {
        outbox.answer(protocol::answer(protocol::error(&why), None));
    }
    for (_, live) in robots.all() {
        let _ = live.jobs.send(Job::Unsubscribe { conn });
    }
    for robot in server.leases.release(conn, None) {
        client.audit("lease released", robot_and_why(&robot, "left"));
    }
    outbox.close();
    if tokio::time::timeout(GOODBYE_WAIT, &mut writer)
        .await
        .is_err()
    {
        writer.abort();
    }
}

/// Why the connection is closed: idle too long, or asked to make room.
async fn watchdog(place: &Place, idle: Duration) -> String {
    loop {
        let due = place.last_active() + idle;
        tokio::select! {
            () = place.evict.notified() => {
                return format!(
                    "closed to make room for a new client: the server has {MAX_CLIENTS} \
                     clients and this one was the longest silent"
                );
            }
            () = tokio::time::sleep_until(due.into()) => {
                if place.last_active() + idle <= Instant::now() {
                    return format!(
                        "closed: idle for {} s (no request and nothing to send)",
                        fmt_secs(idle)
                    );
                }
            }
        }
    }
}

fn fmt_secs(d: Duration) -> String {
    ilmr_vm::runtime::trace::fmt_num(d.as_secs_f64())
}

/// Frames request lines and hands them on. The first request must end within
/// `request` of connecting and every line within `request` of its first byte.
async fn read_lines<S: AsyncRead>(
    mut read: ReadHalf<S>,
    items: mpsc::Sender<Item>,
    pending: &Pending,
    robots: &Robots,
    place: &Place,
    request: Duration,
) {
    let mut buf: Vec<u8> = Vec::new();
    let mut chunk = [0u8; READ_CHUNK];
    // When the line being read (or, before the first, the connection) began.
    let mut begun = Some(Instant::now());
    loop {
        while let Some(end) = buf.iter().position(|&b| b == b'\n') {
            if end > MAX_LINE {
                break;
            }
            let line: Vec<u8> = buf.drain(..=end).collect();
            begun = (!buf.is_empty()).then(Instant::now);
            place.spoke();
            if pending.requests.fetch_add(1, Ordering::SeqCst) > 0 {
                stop_at_once(&line, robots, place);
            }
            pending.bytes.fetch_add(line.len(), Ordering::SeqCst);
            if items.send(Item::Line(line)).await.is_err() {
                return;
            }
        }
        if buf.len() > MAX_LINE {
            let why = format!("request line longer than {MAX_LINE} bytes");
            let _ = items.send(Item::Close(why)).await;
            return;
        }
        if buf.is_empty() && buf.capacity() > KEEP_BUFFER {
            buf = Vec::new();
        }
        // Between lines, a client whose requests wait is not read further. (Within a
        // line, its timeout runs on.)
        while buf.is_empty() && pending.bytes.load(Ordering::SeqCst) > READ_AHEAD_BYTES {
            pending.answered.notified().await;
        }
        let read_some = read.read(&mut chunk);
        let got = match begun {
            Some(b) => match tokio::time::timeout_at((b + request).into(), read_some).await {
                Ok(got) => got,
                Err(_) => {
                    let why = if place.has_spoken() {
                        format!(
                            "closed: a request line must end within {} s of its first byte",
                            fmt_secs(request)
                        )
                    } else {
                        format!(
                            "closed: no request within {} s of connecting",
                            fmt_secs(request)
                        )
                    };
                    let _ = items.send(Item::Close(why)).await;
                    return;
                }
            },
            None => read_some.await,
        };
        match got {
            // Gone, perhaps halfway through a line: half a request is never run.
            Ok(0) | Err(_) => return,
            Ok(n) => {
                if begun.is_none() {
                    begun = Some(Instant::now());
                }
                buf.extend_from_slice(&chunk[..n]);
            }
        }
    }
}

/// A `stop` read while the client's earlier requests wait: raised now, answered in
/// its place. Only short lines are looked at, so this costs the reader nothing; only
/// a client that has proved who it is may stop the robot.
fn stop_at_once(line: &[u8], robots: &Robots, place: &Place) {
    if line.len() > 256 || place.identity().is_none() {
        return;
    }
    let Ok(text) = std::str::from_utf8(line) else {
        return;
    };
    let parsed = protocol::parse(text.trim());
    if parsed.request == Request::Stop {
        let _ = raise(robots, parsed.robot.as_deref());
    }
}

/// Answers requests in order; each answer is written before the next is taken. A
/// client that has not proved who it is gets one request to do so.
async fn answer_requests(mut queue: mpsc::Receiver<Item>, client: &Client<'_>, pending: &Pending) {
    let outbox = client.outbox;
    while let Some(item) = queue.recv().await {
        match item {
            Item::Line(bytes) => {
                let (answer, go_on) = if client.place.identity().is_some() {
                    (respond(&bytes, client).await, true)
                } else {
                    let (answer, known) = authenticate(&bytes, client);
                    (Some(answer), known)
                };
                if let Some(answer) = answer {
                    outbox.answer(answer);
                }
                while outbox.answers_waiting() > 0 {
                    outbox.until_written().await;
                }
                pending.requests.fetch_sub(1, Ordering::SeqCst);
                pending.bytes.fetch_sub(bytes.len(), Ordering::SeqCst);
                pending.answered.notify_one();
                if !go_on {
                    return;
                }
            }
            Item::Close(why) => {
                outbox.answer(protocol::answer(protocol::error(&why), None));
                return;
            }
        }
    }
}

/// The answer line to one request line; `None` when the engine queued it itself (a
/// subscription's, before its first event).
async fn respond(bytes: &[u8], client: &Client<'_>) -> Option<String> {
    let (conn, robots, outbox) = (client.conn, &*client.server.robots, client.outbox);
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Some(protocol::answer(protocol::error("not UTF-8"), None));
    };
    let line = text.trim();
    // A planner that waits for one answer per line it sent must not wait forever for
    // a blank one.
    if line.is_empty() {
        let why = "empty line: send one JSON object per line";
        return Some(protocol::answer(protocol::error(why), None));
    }
    // A panic while the request is parsed or its answer rendered is this request's
    // error, not the end of the connection.
    let parsed = match guarded("reading the request", || protocol::parse(line)) {
        Ok(p) => p,
        Err(why) => return Some(protocol::answer(protocol::error(&why), None)),
    };
    client.server.leases.renew(conn);
    let answer = ask(&parsed, client).await?;
    let rendered = guarded("answering the request", || {
        let mut a = answer.render();
        if let (true, Some(name)) = (robots.is_fleet(), &parsed.robot) {
            a.insert("robot".into(), Value::String(name.clone()));
        }
        if parsed.request == Request::Status {
            a.insert("dropped_events".into(), Value::from(outbox.dropped()));
            status_of_client(&mut a, client, parsed.robot.as_deref());
        }
        audit_answer(client, &parsed, &a);
        protocol::answer(a, parsed.id.as_ref())
    });
    Some(rendered.unwrap_or_else(|why| protocol::answer(protocol::error(&why), None)))
}

/// An answer from the robots, rendered on the answering side of a panic guard.
enum Answer {
    Ready(Map<String, Value>),
    Line(LineAnswer, String),
    Status(Box<crate::live::engine::Status>),
}

impl Answer {
    fn render(self) -> Map<String, Value> {
        match self {
            Answer::Ready(m) => m,
            Answer::Line(a, text) => reply::line(&a, &text),
            Answer::Status(s) => reply::status(&s),
        }
    }
}

async fn ask(parsed: &Parsed, client: &Client<'_>) -> Option<Answer> {
    let (conn, robots, outbox) = (client.conn, &*client.server.robots, client.outbox);
    let ready = |m| Some(Answer::Ready(m));
    match &parsed.request {
        Request::Invalid(why) => return ready(protocol::error(why)),
        Request::Stop => return ready(stop(robots, parsed.robot.as_deref()).await),
        Request::Auth(_) => {
            let known = client.place.identity().map_or("", |i| i.name.as_str());
            return ready(protocol::error(&format!(
                "already authenticated as `{known}`"
            )));
        }
        // A fleet's status and events without a robot's name are the whole fleet's.
        Request::Status if robots.is_fleet() && parsed.robot.is_none() => {
            return ready(fleet_status(robots).await);
        }
        Request::Subscribe if robots.is_fleet() && parsed.robot.is_none() => {
            return ready(subscribe_all(conn, robots, outbox).await);
        }
        _ => {}
    }
    let live = match robots.route(parsed.robot.as_deref()) {
        Ok(live) => live,
        Err(why) => return ready(protocol::error(&why)),
    };
    let robot = parsed.robot.as_deref().unwrap_or("");
    if let Request::Lease(lease) = parsed.request {
        return ready(match may_drive(client, "lease") {
            Err(why) => protocol::error(&why),
            Ok(()) => lease_answer(client, robot, lease),
        });
    }
    if let Request::Ilmr(_) = parsed.request
        && let Err(why) = may_drive(client, "send lines").and_then(|()| hold_lease(client, robot))
    {
        return ready(protocol::error(&why));
    }
    let answered = match &parsed.request {
        Request::Ilmr(text) => {
            let text = text.clone();
            let job = |reply| Job::Line { text, reply };
            ask_engine(&live.jobs, job)
                .await
                .map(|a| Answer::Line(a, text_of(&parsed.request)))
        }
        Request::Status => ask_engine(&live.jobs, |reply| Job::Status { reply })
            .await
            .map(|s| Answer::Status(Box::new(s))),
        Request::Subscribe => {
            return subscribe(conn, parsed.id.clone(), live, outbox)
                .await
                .map(Answer::Ready);
        }
        Request::Invalid(_) | Request::Stop | Request::Auth(_) | Request::Lease(_) => {
            unreachable_answer()
        }
    };
    Some(answered.unwrap_or_else(Answer::Ready))
}

fn text_of(request: &Request) -> String {
    match request {
        Request::Ilmr(text) => text.clone(),
        _ => String::new(),
    }
}

/// Requests answered before routing do not reach here; answered as an error rather
/// than a panic should that change.
fn unreachable_answer<T>() -> Result<T, Map<String, Value>> {
    Err(protocol::error("this request is answered elsewhere"))
}

/// Sends the job `make` builds and waits for its answer; an error object when the
/// robot's thread is gone or silent.
async fn ask_engine<T: Send + 'static>(
    jobs: &Sender<Job>,
    make: impl FnOnce(Reply<T>) -> Job,
) -> Result<T, Map<String, Value>> {
    let (reply, answer) = oneshot::channel();
    if jobs.send(make(reply.into())).is_err() {
        return Err(protocol::error("the robot has stopped"));
    }
    wait(answer).await
}

async fn wait<T>(answer: oneshot::Receiver<T>) -> Result<T, Map<String, Value>> {
    match tokio::time::timeout(ANSWER_WAIT, answer).await {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(_)) => Err(protocol::error("the robot has stopped")),
        Err(_) => Err(protocol::error(&format!(
            "the robot did not answer within {} s",
            ANSWER_WAIT.as_secs()
        ))),
    }
}

/// Raises the emergency stop of the robot named, of the only robot, or (a fleet's
/// `stop` without a name) of every robot: the acknowledgements to wait for.
fn raise(
    robots: &Robots,
    name: Option<&str>,
) -> Result<Vec<(String, oneshot::Receiver<LineAnswer>)>, String> {
    let targets: Vec<(&str, &Live)> = match (robots.is_fleet(), name) {
        (true, None) => robots.all().collect(),
        _ => vec![("", robots.route(name)?)],
    };
    Ok(targets
        .into_iter()
        .map(|(n, live)| {
            let (reply, acknowledged) = oneshot::channel();
            live.stop.raise(reply.into());
            (n.to_string(), acknowledged)
        })
        .collect())
}

/// `{"stop": true}`: the `stop` line's answer once the robot brakes; a fleet's
/// without a name, every robot's (`{"ok", "robots": {NAME: answer}}`).
async fn stop(robots: &Robots, name: Option<&str>) -> Map<String, Value> {
    let waiting = match raise(robots, name) {
        Ok(w) => w,
        Err(why) => return protocol::error(&why),
    };
    let all = robots.is_fleet() && name.is_none();
    let mut each = Map::new();
    let mut ok = true;
    for (robot, acknowledged) in waiting {
        let answer = match wait(acknowledged).await {
            Ok(a) => reply::line(&a, "stop"),
            Err(e) => e,
        };
        if !all {
            return answer;
        }
        ok &= answer.get("ok") == Some(&Value::Bool(true));
        each.insert(robot, Value::Object(answer));
    }
    let mut m = Map::new();
    m.insert("ok".into(), Value::Bool(ok));
    m.insert("robots".into(), Value::Object(each));
    m
}

/// Subscribes this connection; the engine queues the answer itself (so it comes
/// before the first event), hence `None` once it has.
async fn subscribe(
    conn: u64,
    id: Option<Value>,
    live: &Live,
    outbox: &Arc<Outbox>,
) -> Option<Map<String, Value>> {
    let first: Box<dyn FnOnce(f64) -> String + Send> =
        Box::new(move |t| protocol::answer(reply::subscribed(t), id.as_ref()));
    let out = Box::new(Arc::clone(outbox));
    let job = |done| Job::Subscribe {
        conn,
        out,
        first: Some(first),
        done,
    };
    ask_engine(&live.jobs, job).await.err()
}

/// `{"ok": true, "robots": {NAME: status, ...}}`: every robot's, asked at once.
async fn fleet_status(robots: &Robots) -> Map<String, Value> {
    let asked: Vec<_> = robots
        .all()
        .map(|(name, live)| {
            let (reply, answer) = oneshot::channel();
            let sent = live.jobs.send(Job::Status {
                reply: reply.into(),
            });
            (name, sent.is_ok().then_some(answer))
        })
        .collect();
    let mut each = Map::new();
    for (name, answer) in asked {
        let status = match answer {
            None => protocol::error("the robot has stopped"),
            Some(a) => wait(a).await.map_or_else(|e| e, |s| reply::status(&s)),
        };
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
async fn subscribe_all(conn: u64, robots: &Robots, outbox: &Arc<Outbox>) -> Map<String, Value> {
    let mut waiting = Vec::new();
    for (name, live) in robots.all() {
        let (done, acknowledged) = oneshot::channel();
        let job = Job::Subscribe {
            conn,
            out: Box::new(Arc::clone(outbox)),
            first: None,
            done: done.into(),
        };
        if live.jobs.send(job).is_err() {
            return protocol::error(&format!("robot `{name}` has stopped"));
        }
        waiting.push((name, acknowledged));
    }
    for (name, acknowledged) in waiting {
        if wait(acknowledged).await.is_err() {
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

/// Writes what the outbox holds, in order, until it is closed and empty or the
/// client is gone. Every line written is a sign the client uses its place.
async fn write_out<S: AsyncWrite>(
    mut socket: WriteHalf<S>,
    outbox: Arc<Outbox>,
    place: Arc<Place>,
) {
    let mut bytes: Vec<u8> = Vec::new();
    loop {
        let Some(batch) = outbox.take() else {
            let _ = socket.shutdown().await;
            return;
        };
        if batch.is_empty() {
            outbox.until_queued().await;
            continue;
        }
        bytes.clear();
        if bytes.capacity() > KEEP_BUFFER {
            bytes = Vec::new();
        }
        let mut answers = 0;
        for (line, is_event) in &batch {
            bytes.extend_from_slice(line.as_bytes());
            bytes.push(b'\n');
            answers += usize::from(!is_event);
        }
        drop(batch);
        if socket.write_all(&bytes).await.is_err() {
            // The client is gone; the reader sees that too and ends the connection.
            outbox.close();
            outbox.wrote(answers);
            return;
        }
        place.touch();
        outbox.wrote(answers);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::live::engine::Outcome;
    use crate::live::stop::EmergencyStop;

    /// A bound on a connection's task, far below a thread's stack (2 MiB, of which a
    /// thread touches tens of KiB).
    const CONNECTION_TASK_BYTES: usize = 16 << 10;

    fn accepted(t: f64) -> LineAnswer {
        LineAnswer {
            t,
            outcome: Outcome::Accepted {
                warnings: Vec::new(),
            },
        }
    }

    /// A robot whose jobs and stops the test answers itself, so that a request can be
    /// made to wait as long as the test likes.
    #[test]
    fn a_stop_behind_a_waiting_request_is_raised_at_once_and_answered_in_its_place() {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .expect("a runtime");
        let (jobs, queue) = std::sync::mpsc::channel();
        let stop = Arc::new(EmergencyStop::default());
        let live = Live {
            jobs,
            stop: Arc::clone(&stop),
            model: crate::inputs::load_robot_model("moro").expect("MoRo"),
            world: "none".into(),
        };
        let robots = Arc::new(Robots::one(live));
        runtime.block_on(async move {
            let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
                .await
                .expect("a loopback port");
            let addr = listener.local_addr().expect("its address");
            let server = tokio::spawn(async move {
                let (stream, _) = listener.accept().await.expect("a client");
                let registry = super::super::admit::Registry::default();
                let place = registry.admit(1).expect("a place");
                let _ = place.identify(crate::serve::access::Identity::anonymous(1));
                let server = Arc::new(Server {
                    robots,
                    timeouts: crate::serve::Timeouts::default(),
                    access: None,
                    leases: crate::serve::lease::Leases::default(),
                    audit: None,
                });
                let connection = serve(stream, place, server, None);
                // What a client costs besides its socket: this task (the 4 KiB read
                // chunk included), its writer's and the buffers it has filled.
                let size = std::mem::size_of_val(&connection);
                assert!(
                    size < CONNECTION_TASK_BYTES,
                    "a connection's task is {size} B"
                );
                connection.await;
            });
            let mut client = tokio::net::TcpStream::connect(addr).await.expect("connect");
            client
                .write_all(b"{\"ilmr\": \"n = 1\", \"id\": 1}\n{\"stop\": true, \"id\": 2}\n")
                .await
                .expect("send");
            // The line waits for a robot that does not answer; the stop is raised anyway.
            let deadline = Instant::now() + Duration::from_secs(10);
            let early = loop {
                if let Some(waiting) = stop.take() {
                    break waiting;
                }
                assert!(Instant::now() < deadline, "the stop was not raised at once");
                tokio::time::sleep(Duration::from_millis(5)).await;
            };
            let Ok(Job::Line { text, reply }) = queue.try_recv() else {
                panic!("the line waits in the robot's queue");
            };
            assert_eq!(text, "n = 1");
            for r in early {
                r.send(accepted(1.0));
            }
            reply.send(accepted(2.0));
            // In its place the stop is raised again (a `cont` before it cannot undo it).
            let deadline = Instant::now() + Duration::from_secs(10);
            let again = loop {
                if let Some(waiting) = stop.take() {
                    break waiting;
                }
                assert!(
                    Instant::now() < deadline,
                    "the stop was not raised in its place"
                );
                tokio::time::sleep(Duration::from_millis(5)).await;
            };
            for r in again {
                r.send(accepted(3.0));
            }
            let mut answers = String::new();
            let mut chunk = [0u8; 1024];
            while answers.matches('\n').count() < 2 {
                let n = tokio::time::timeout(Duration::from_secs(10), client.read(&mut chunk))
                    .await
                    .expect("the answers in time")
                    .expect("read");
                assert!(n > 0, "closed early: {answers}");
                answers.push_str(&String::from_utf8_lossy(&chunk[..n]));
            }
            let lines: Vec<Value> = answers
                .lines()
                .map(|l| serde_json::from_str(l).expect("JSON"))
                .collect();
            assert_eq!((&lines[0]["id"], &lines[0]["t"]), (&json(1), &json(2)));
            assert_eq!((&lines[1]["id"], &lines[1]["t"]), (&json(2), &json(3)));
            drop(client);
            let _ = tokio::time::timeout(Duration::from_secs(10), server).await;
        });
    }

    fn json(n: i32) -> Value {
        Value::from(n)
    }
}
