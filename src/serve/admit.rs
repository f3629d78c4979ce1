//! Who gets a place: the client limit, the places kept for when every client is busy,
//! and which client makes room for a newcomer. A client that holds a place without
//! using it (it connected and said nothing, sends half a line a byte at a time, or
//! has been silent a while) gives it up to a newcomer, so that an operator can always
//! connect and send `stop`.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

use tokio::sync::Notify;

use super::access::Identity;

/// Clients served at once before a newcomer needs a place made for it.
pub const MAX_CLIENTS: usize = 64;
/// Places beyond `MAX_CLIENTS` for newcomers while no client can be asked to make
/// room (every one is busy); once they are taken too, a newcomer is refused.
pub const RESERVED_PLACES: usize = 8;
/// A client that has sent a request is asked to make room only once it has been
/// silent this long (no request finished, nothing written to it).
pub const EVICT_AFTER: Duration = Duration::from_secs(2);

/// One client's place, shared by its connection and the registry.
pub struct Place {
    pub conn: u64,
    epoch: Instant,
    /// Milliseconds after `epoch` of the last sign of use: connecting, a finished
    /// request, a line written to the client.
    active_ms: AtomicU64,
    spoken: AtomicBool,
    evicted: AtomicBool,
    pub evict: Notify,
    /// Who the client is, once it has proved it (at once for a certificate, or on a
    /// server that asks nobody).
    identity: OnceLock<Identity>,
}

impl Place {
    /// The client finished a request.
    pub fn spoke(&self) {
        self.spoken.store(true, Ordering::SeqCst);
        self.touch();
    }

    /// The client used its place (a line was written to it).
    pub fn touch(&self) {
        let ms = u64::try_from(self.epoch.elapsed().as_millis()).unwrap_or(u64::MAX);
        self.active_ms.store(ms, Ordering::SeqCst);
    }

    pub fn has_spoken(&self) -> bool {
        self.spoken.load(Ordering::SeqCst)
    }

    /// When the place was last used.
    pub fn last_active(&self) -> Instant {
        self.epoch + Duration::from_millis(self.active_ms.load(Ordering::SeqCst))
    }

    pub fn identity(&self) -> Option<&Identity> {
        self.identity.get()
    }

    /// Records who the client is; a client proves it once.
    pub fn identify(&self, identity: Identity) -> Result<(), Identity> {
        self.identity.set(identity)
    }

    pub fn is_evicted(&self) -> bool {
        self.evicted.load(Ordering::SeqCst)
    }
}

/// What becomes of a newcomer.
#[derive(Debug, PartialEq, Eq)]
pub enum Admission {
    Take,
    /// Take it, after the client at this index has made room.
    MakeRoom(usize),
    Refuse,
}

/// A client as the choice sees it.
#[derive(Debug, Clone, Copy)]
pub struct Seen {
    /// It has proved who it is (always, on a server that asks nobody).
    pub known: bool,
    pub spoken: bool,
    pub silent: Duration,
}

/// The rule: below the limit, take; else make room with a client that has not proved
/// who it is, or else with the longest-silent client that has never finished a
/// request or has been silent `EVICT_AFTER`; else take into a reserved place; else
/// refuse. So the reserved places are in the end held by clients known to the
/// server: a stranger gives its place to the next newcomer.
pub fn choose(clients: &[Seen]) -> Admission {
    if clients.len() < MAX_CLIENTS {
        return Admission::Take;
    }
    let idlest = clients
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.known || !c.spoken || c.silent >= EVICT_AFTER)
        .max_by_key(|(_, c)| (!c.known, c.silent));
    match idlest {
        Some((i, _)) => Admission::MakeRoom(i),
        None if clients.len() < MAX_CLIENTS + RESERVED_PLACES => Admission::Take,
        None => Admission::Refuse,
    }
}

/// Every place in use.
#[derive(Default)]
pub struct Registry {
    places: Mutex<Vec<Arc<Place>>>,
}

impl Registry {
    /// A place for connection `conn`, made by evicting another when the rule says so;
    /// `None` when it is refused.
    pub fn admit(&self, conn: u64) -> Option<Arc<Place>> {
        let mut places = self
            .places
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        // An evicted client is on its way out: its place is already free.
        places.retain(|p| !p.is_evicted());
        let now = Instant::now();
        let seen: Vec<Seen> = places
            .iter()
            .map(|p| Seen {
                known: p.identity().is_some(),
                spoken: p.has_spoken(),
                silent: now.saturating_duration_since(p.last_active()),
            })
            .collect();
        match choose(&seen) {
            Admission::Take => {}
            Admission::MakeRoom(i) => {
                let out = places.swap_remove(i);
                out.evicted.store(true, Ordering::SeqCst);
                out.evict.notify_one();
            }
            Admission::Refuse => return None,
        }
        let place = Arc::new(Place {
            conn,
            epoch: now,
            active_ms: AtomicU64::new(0),
            spoken: AtomicBool::new(false),
            evicted: AtomicBool::new(false),
            evict: Notify::new(),
            identity: OnceLock::new(),
        });
        places.push(Arc::clone(&place));
        Some(place)
    }

    pub fn leave(&self, conn: u64) {
        self.places
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .retain(|p| p.conn != conn);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clients(n: usize, spoken: bool, silent_ms: u64) -> Vec<Seen> {
        vec![
            Seen {
                known: true,
                spoken,
                silent: Duration::from_millis(silent_ms),
            };
            n
        ]
    }

    #[test]
    fn below_the_limit_everyone_is_taken() {
        assert_eq!(choose(&clients(MAX_CLIENTS - 1, true, 0)), Admission::Take);
    }

    #[test]
    fn at_the_limit_the_longest_silent_makes_room() {
        let mut c = clients(MAX_CLIENTS, false, 10);
        c[7].silent = Duration::from_millis(50);
        assert_eq!(choose(&c), Admission::MakeRoom(7));
        // A client that spoke a moment ago keeps its place; one that never spoke
        // does not, however new.
        let mut c = clients(MAX_CLIENTS, true, 0);
        c[3].spoken = false;
        assert_eq!(choose(&c), Admission::MakeRoom(3));
        let mut c = clients(MAX_CLIENTS, true, 100);
        c[9].silent = EVICT_AFTER;
        assert_eq!(choose(&c), Admission::MakeRoom(9));
    }

    #[test]
    fn a_client_that_has_not_proved_who_it_is_makes_room_first() {
        // Busy all of them, even the stranger; it goes, not the longest silent.
        let mut c = clients(MAX_CLIENTS + RESERVED_PLACES, true, 100);
        c[5].silent = Duration::from_millis(900);
        c[11].known = false;
        c[11].silent = Duration::from_millis(1);
        assert_eq!(choose(&c), Admission::MakeRoom(11));
    }

    #[test]
    fn busy_clients_leave_the_reserved_places_then_refuse() {
        assert_eq!(choose(&clients(MAX_CLIENTS, true, 100)), Admission::Take);
        assert_eq!(
            choose(&clients(MAX_CLIENTS + RESERVED_PLACES, true, 100)),
            Admission::Refuse
        );
    }

    #[test]
    fn the_registry_evicts_and_frees() {
        let r = Registry::default();
        let first = r.admit(0).expect("a place");
        for conn in 1..MAX_CLIENTS as u64 {
            r.admit(conn).expect("a place").spoke();
        }
        let newcomer = r.admit(100).expect("room is made");
        assert!(first.is_evicted(), "the one that never spoke made room");
        assert!(!newcomer.is_evicted());
        r.leave(100);
        assert!(r.admit(101).is_some());
    }
}
