//! `--foxglove [ADDR]`: the run live in Foxglove, over the Foxglove WebSocket protocol
//! (subprotocol `foxglove.websocket.v1` or `foxglove.sdk.v1`, served by Foxglove's SDK), with the topics
//! and messages of the recording ([`super`]) and the run's logical time as the
//! viewer's clock.
//!
//! The tick never waits for a viewer. It hands its messages to an outbox of
//! [`OUTBOX`] messages; a publisher thread encodes them and gives them to the SDK,
//! which keeps [`BACKLOG`] messages per client and drops a slow client's oldest. Both
//! drops are counted: when the outbox is full (the publisher is behind), the tick's
//! messages are dropped ([`Live::dropped`]) and every viewer is told in a status
//! message; what the SDK drops for one slow viewer is counted per viewer
//! (through the patched SDK in `vendor/foxglove`; [`close`] says it on stderr) and that viewer is
//! told, at most once every [`TELL_EVERY`].
//!
//! A viewer that connects late still sees the scene: when it subscribes to a scene
//! topic, the world, the last [`KEPT_SCENES`] paths and trajectory pieces are sent
//! again.

use std::collections::VecDeque;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, SyncSender, TrySendError, sync_channel};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use foxglove::schemas::log::Level;
use foxglove::websocket::{Capability, Client, ServerListener, Status};
use foxglove::{ChannelBuilder, Context, PartialMetadata, RawChannel, WebSocketServer};
use ilmr_sim::World;
use ilmr_vm::{Event, Module};

use super::{Messages, Outgoing, Topic, nanos};
use crate::run::backend::WorldScan;

/// Where the live view listens unless told: Foxglove's own default port, on loopback.
pub const DEFAULT_ADDR: &str = "127.0.0.1:8765";

/// Messages waiting for the publisher: about two seconds of a run with a scan every
/// tick.
pub const OUTBOX: usize = 4096;
/// Messages the SDK keeps for each client before it drops the oldest.
pub const BACKLOG: usize = 1024;
/// Paths and trajectory pieces a late viewer is sent again, newest first.
pub const KEPT_SCENES: usize = 600;
/// A slow viewer is told how much it has missed at most this often: the warning goes
/// on its control queue, which the SDK does not let overflow (it disconnects instead).
pub const TELL_EVERY: Duration = Duration::from_secs(1);

/// What the publisher is sent: a message, or how many the tick has dropped so far.
enum Post {
    Message(Box<Outgoing>),
    Dropped(u64),
}

pub struct Live {
    outbox: Option<SyncSender<Post>>,
    publisher: Option<JoinHandle<()>>,
    addr: SocketAddr,
    messages: Messages,
    outgoing: Vec<Outgoing>,
    dropped: u64,
    /// Drops not yet told to the viewer.
    untold: u64,
    viewers: Viewers,
}

/// `--foxglove[=ADDR]`, shared by `run`, `shell`, `serve` and `sim`.
#[derive(clap::Args, Debug, Default, Clone)]
pub struct FoxgloveArgs {
    /// Serve the robot live to Foxglove (WebSocket, Foxglove's SDK) on
    /// `--foxglove` (127.0.0.1:8765) or `--foxglove=HOST:PORT` (loopback only; port 0
    /// takes a free one, named on stderr). See docs/foxglove.md.
    #[arg(long, num_args = 0..=1, require_equals = true, value_name = "ADDR",
          default_missing_value = DEFAULT_ADDR)]
    pub foxglove: Option<String>,
}

impl FoxgloveArgs {
    /// The live view, when asked for: started, its address said on stderr.
    pub fn open(&self, task: &str, world: Option<&World>) -> Result<Option<Live>, String> {
        match &self.foxglove {
            Some(addr) => open(addr, task, world).map(Some),
            None => Ok(None),
        }
    }
}

/// Parses `HOST:PORT`, or a bare port on loopback.
pub fn parse_addr(text: &str) -> Result<SocketAddr, String> {
    let text = text.trim();
    let full = if text.parse::<u16>().is_ok() {
        format!("127.0.0.1:{text}")
    } else {
        text.to_string()
    };
    full.parse()
        .map_err(|_| format!("--foxglove `{text}` is not HOST:PORT (e.g. {DEFAULT_ADDR})"))
}

/// Every client that has subscribed to something, in the order they first did: the
/// ones the SDK can have dropped messages for. Their counts outlive their connections.
#[derive(Clone, Default)]
struct Viewers(Arc<Mutex<Vec<Viewer>>>);

struct Viewer {
    client: Client,
    /// Messages published since it first subscribed, on any topic.
    published: u64,
    /// How much it had missed when last told.
    told: u64,
    told_at: Option<Instant>,
}

impl Viewers {
    fn add(&self, client: Client) {
        let mut all = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if all.iter().all(|v| v.client.id() != client.id()) {
            all.push(Viewer {
                client,
                published: 0,
                told: 0,
                told_at: None,
            });
        }
    }

    /// What each viewer missed, and of how many published since it subscribed.
    fn missed(&self) -> Vec<(u64, u64)> {
        let all = self.0.lock().unwrap_or_else(|e| e.into_inner());
        all.iter()
            .map(|v| (v.client.dropped_messages(), v.published))
            .collect()
    }

    fn published(&self) {
        let mut all = self.0.lock().unwrap_or_else(|e| e.into_inner());
        for v in all.iter_mut() {
            v.published += 1;
        }
    }

    /// Tells each viewer that has missed more since it was last told.
    fn tell(&self, now: Instant) {
        let mut all = self.0.lock().unwrap_or_else(|e| e.into_inner());
        for v in all.iter_mut() {
            let missed = v.client.dropped_messages();
            let due = v
                .told_at
                .is_none_or(|t| now.duration_since(t) >= TELL_EVERY);
            if missed > v.told && due {
                v.client.send_status(
                    Status::warning(format!(
                        "ilmrc: {missed} messages dropped for this viewer so far (it is behind \
                         the run; the server keeps {BACKLOG} per viewer)"
                    ))
                    .with_id("missed"),
                );
                v.told = missed;
                v.told_at = Some(now);
            }
        }
    }
}

/// Sets a topic's flag when a client subscribes to it: the publisher then sends the
/// topic's kept messages again. Keeps the client among the viewers.
struct Subscriptions {
    resend: Arc<[AtomicBool; Topic::ALL.len()]>,
    viewers: Viewers,
}

impl ServerListener for Subscriptions {
    fn on_subscribe(&self, client: Client, channel: foxglove::websocket::ChannelView) {
        self.viewers.add(client);
        if let Some(i) = Topic::ALL.iter().position(|t| t.name() == channel.topic()) {
            self.resend[i].store(true, Ordering::Relaxed);
        }
    }
}

impl Live {
    /// Starts the server on `addr` (port 0 takes a free one) and sends the world.
    pub fn start(addr: SocketAddr, task: &str, world: Option<&World>) -> Result<Live, String> {
        let context = Context::new();
        let resend: Arc<[AtomicBool; Topic::ALL.len()]> =
            Arc::new(std::array::from_fn(|_| AtomicBool::new(false)));
        let viewers = Viewers::default();
        let listener = Subscriptions {
            resend: resend.clone(),
            viewers: viewers.clone(),
        };
        let mut channels = Vec::new();
        for topic in Topic::ALL {
            let channel = ChannelBuilder::new(topic.name())
                .context(&context)
                .message_encoding("protobuf")
                .schema(topic.schema())
                .build_raw()
                .map_err(|e| format!("--foxglove: cannot make `{}`: {e}", topic.name()))?;
            channels.push(channel);
        }
        let server = WebSocketServer::new()
            .name("ilmrc")
            .bind(addr.ip().to_string(), addr.port())
            .context(&context)
            .capabilities([Capability::Time])
            .message_backlog_size(BACKLOG)
            .listener(Arc::new(listener))
            .start_blocking()
            .map_err(|e| format!("--foxglove {addr}: cannot listen: {e}"))?;
        let addr = SocketAddr::new(addr.ip(), server.port());
        let (outbox, inbox) = sync_channel(OUTBOX);
        let publisher = Publisher {
            server,
            channels,
            resend,
            viewers: viewers.clone(),
            kept: Kept::default(),
            bytes: Vec::new(),
            _context: context,
        };
        let publisher = std::thread::Builder::new()
            .name("foxglove".into())
            .spawn(move || publisher.run(inbox))
            .map_err(|e| format!("--foxglove: cannot start its thread: {e}"))?;
        let mut live = Live {
            outbox: Some(outbox),
            publisher: Some(publisher),
            addr,
            messages: Messages::new(task),
            outgoing: Vec::new(),
            dropped: 0,
            untold: 0,
            viewers,
        };
        if let Some(w) = world {
            let world = live.messages.world(w);
            live.send(world);
        }
        Ok(live)
    }

    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Messages the tick could not hand over because the publisher was behind.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// The tick's events and scan.
    pub fn tick(&mut self, module: &Module, events: &[Event], scan: Option<&WorldScan>) {
        let mut outgoing = std::mem::take(&mut self.outgoing);
        self.messages.tick(module, events, scan, &mut outgoing);
        for o in outgoing.drain(..) {
            self.send(o);
        }
        self.outgoing = outgoing;
        if self.untold > 0 && self.post(Post::Dropped(self.dropped)) {
            self.untold = 0;
        }
    }

    /// A robot without a VM (`sim`): its true pose and motion.
    pub fn robot(&mut self, t: f64, pose: (f64, f64, f64), motion: (f64, f64)) {
        let mut outgoing = std::mem::take(&mut self.outgoing);
        self.messages.robot(t, pose, motion, &mut outgoing);
        for o in outgoing.drain(..) {
            self.send(o);
        }
        self.outgoing = outgoing;
    }

    /// A robot without a VM (`sim`): a new scan.
    pub fn scan(&mut self, scan: &WorldScan) {
        self.send(Messages::scan(scan));
    }

    /// A log line of the run's own (how it ended, a line typed in the shell).
    pub fn note(&mut self, t: f64, level: Level, message: String) {
        let note = self.messages.note(t, level, message);
        self.send(note);
    }

    fn send(&mut self, o: Outgoing) {
        if !self.post(Post::Message(Box::new(o))) {
            self.dropped += 1;
            self.untold += 1;
        }
    }

    fn post(&self, post: Post) -> bool {
        match self.outbox.as_ref().map(|o| o.try_send(post)) {
            Some(Ok(())) => true,
            Some(Err(TrySendError::Full(_))) => false,
            // The publisher is gone (its thread failed): nothing reaches a viewer.
            Some(Err(TrySendError::Disconnected(_))) | None => false,
        }
    }

    /// Sends what is waiting and stops the server.
    pub fn finish(mut self) {
        self.outbox = None;
        if let Some(p) = self.publisher.take() {
            let _ = p.join();
        }
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        self.outbox = None;
        if let Some(p) = self.publisher.take() {
            let _ = p.join();
        }
    }
}

/// The scene messages a late viewer is sent again.
#[derive(Default)]
struct Kept {
    world: Option<Outgoing>,
    paths: VecDeque<Outgoing>,
    trajectory: VecDeque<Outgoing>,
}

impl Kept {
    fn keep(&mut self, o: &Outgoing) {
        let list = match o.topic {
            Topic::World => {
                self.world = Some(o.clone());
                return;
            }
            Topic::Paths => &mut self.paths,
            Topic::Trajectory => &mut self.trajectory,
            _ => return,
        };
        if list.len() == KEPT_SCENES {
            list.pop_front();
        }
        list.push_back(o.clone());
    }

    fn of(&self, topic: Topic) -> Vec<&Outgoing> {
        match topic {
            Topic::World => self.world.iter().collect(),
            Topic::Paths => self.paths.iter().collect(),
            Topic::Trajectory => self.trajectory.iter().collect(),
            _ => Vec::new(),
        }
    }
}

struct Publisher {
    server: foxglove::WebSocketServerHandle,
    /// By [`Topic`].
    channels: Vec<Arc<RawChannel>>,
    resend: Arc<[AtomicBool; Topic::ALL.len()]>,
    viewers: Viewers,
    kept: Kept,
    bytes: Vec<u8>,
    /// Holds the channels' sinks for as long as the server runs.
    _context: Arc<Context>,
}

/// How long the server's tasks are given to close their connections.
const STOP_WAIT: Duration = Duration::from_secs(1);

/// How long a connected viewer is given to receive the last messages of a run.
const LINGER: Duration = Duration::from_millis(300);

/// How often the publisher looks for new subscribers when no message comes.
const IDLE: Duration = Duration::from_millis(50);

impl Publisher {
    fn run(mut self, inbox: Receiver<Post>) {
        let mut clock = 0;
        loop {
            match inbox.recv_timeout(IDLE) {
                Ok(Post::Message(o)) => {
                    self.kept.keep(&o);
                    self.publish(&o);
                    let t = nanos(o.t);
                    if t > clock {
                        clock = t;
                        self.server.broadcast_time(clock);
                    }
                }
                Ok(Post::Dropped(n)) => self.server.publish_status(
                    Status::warning(format!(
                        "ilmrc: {n} messages dropped so far (the viewer or this machine is behind the run)"
                    ))
                    .with_id("dropped"),
                ),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break,
            }
            self.resend_kept();
            self.viewers.tell(Instant::now());
        }
        // Stopping discards what the SDK still queues for a client: a connected
        // viewer is given a moment to receive the run's last messages first.
        if self.server.client_count() > 0 {
            std::thread::sleep(LINGER);
        }
        // A viewer that stopped reading can hold its connection's close for ever: the
        // run does not wait on it longer than STOP_WAIT.
        let stopped = self.server.stop();
        let (done, waited) = std::sync::mpsc::channel();
        let waiting = std::thread::spawn(move || {
            stopped.wait_blocking();
            let _ = done.send(());
        });
        if waited.recv_timeout(STOP_WAIT).is_ok() {
            let _ = waiting.join();
        }
    }

    fn resend_kept(&mut self) {
        for (i, topic) in Topic::ALL.into_iter().enumerate() {
            if self.resend[i].swap(false, Ordering::Relaxed) {
                let kept: Vec<Outgoing> = self.kept.of(topic).into_iter().cloned().collect();
                for o in &kept {
                    self.publish(o);
                }
            }
        }
    }

    fn publish(&mut self, o: &Outgoing) {
        let channel = &self.channels[o.topic as usize];
        if !channel.has_sinks() {
            return;
        }
        self.bytes.clear();
        o.message.encode(&mut self.bytes);
        channel.log_with_meta(
            &self.bytes,
            PartialMetadata {
                log_time: Some(nanos(o.t)),
            },
        );
        self.viewers.published();
    }
}

fn open(addr: &str, task: &str, world: Option<&World>) -> Result<Live, String> {
    let addr = parse_addr(addr)?;
    if !addr.ip().is_loopback() {
        return Err(format!(
            "--foxglove {addr}: the live view has no authentication, so it listens on loopback \
             only; from another machine, tunnel to it (ssh -L 8765:127.0.0.1:8765 ROBOT)"
        ));
    }
    // The SDK starts its own async runtime, which it cannot do from within one (serve
    // runs in one): it is started from a thread of its own.
    let world = world.cloned();
    let task = task.to_string();
    let live = std::thread::spawn(move || Live::start(addr, &task, world.as_ref()))
        .join()
        .map_err(|_| "--foxglove: the live view failed to start".to_string())??;
    eprintln!(
        "foxglove: live view on ws://{} (Foxglove: Open connection, Foxglove WebSocket)",
        live.addr()
    );
    Ok(live)
}

/// Ends the live view, saying on stderr what the viewers missed.
pub fn close(live: Live) {
    let dropped = live.dropped();
    let viewers = live.viewers.clone();
    live.finish();
    if dropped > 0 {
        eprintln!(
            "foxglove: {dropped} messages dropped (the viewer or this machine was behind the run)"
        );
    }
    for (i, (missed, of)) in viewers.missed().into_iter().enumerate() {
        if missed > 0 {
            eprintln!(
                "foxglove: viewer {} fell behind the run: {missed} of the {of} messages \
                 published since it subscribed were dropped (the server keeps {BACKLOG} per \
                 viewer)",
                i + 1
            );
        }
    }
}
