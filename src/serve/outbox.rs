//! What waits to be written to one client: its answers, and its events up to a byte
//! budget. An event that does not fit is dropped and counted, and the client is told
//! how many it missed (`{"event":"dropped",...}`) before the next event it gets, so a
//! client that does not read costs the server at most the budget, never the robot
//! anything.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard};

use tokio::sync::Notify;

use crate::live::engine::EventSink;

/// Bytes of events queued for one client at most (or one event, if larger).
pub const EVENT_BUDGET_BYTES: usize = 64 << 10;

#[derive(Default)]
pub struct Outbox {
    state: Mutex<State>,
    /// Something was queued, or the outbox closed: for the writer.
    queued: Notify,
    /// Something was written: for the reader waiting for its answer to go out.
    written: Notify,
}

#[derive(Default)]
struct State {
    /// Each line, and whether it is an event (not an answer).
    lines: VecDeque<(Arc<str>, bool)>,
    event_bytes: usize,
    answers: usize,
    dropped: u64,
    unreported: u64,
    closed: bool,
}

impl Outbox {
    fn state(&self) -> MutexGuard<'_, State> {
        self.state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Queues an answer: always taken, since a client has at most one answer waiting
    /// (its next request is not read until this one is written); dropped once the
    /// outbox is closed (the client has gone).
    pub fn answer(&self, line: String) {
        let mut s = self.state();
        if s.closed {
            return;
        }
        s.lines.push_back((Arc::from(line), false));
        s.answers += 1;
        drop(s);
        self.queued.notify_one();
    }

    /// Answers still to be written.
    pub fn answers_waiting(&self) -> usize {
        self.state().answers
    }

    /// Events dropped so far.
    pub fn dropped(&self) -> u64 {
        self.state().dropped
    }

    /// Everything queued, in order, for the writer; `None` once closed and empty.
    pub fn take(&self) -> Option<Vec<(Arc<str>, bool)>> {
        let mut s = self.state();
        if s.lines.is_empty() && s.closed {
            return None;
        }
        let lines: Vec<_> = s.lines.drain(..).collect();
        s.event_bytes = 0;
        Some(lines)
    }

    /// The writer wrote `answers` answers.
    pub fn wrote(&self, answers: usize) {
        let mut s = self.state();
        s.answers = s.answers.saturating_sub(answers);
        drop(s);
        self.written.notify_one();
    }

    /// Takes no more events; the writer ends once what is queued is written.
    pub fn close(&self) {
        self.state().closed = true;
        self.queued.notify_one();
    }

    pub async fn until_queued(&self) {
        self.queued.notified().await;
    }

    pub async fn until_written(&self) {
        self.written.notified().await;
    }
}

impl EventSink for Arc<Outbox> {
    fn answer(&self, line: String) -> bool {
        Outbox::answer(self, line);
        true
    }

    fn offer(&self, event: &Arc<str>) -> bool {
        let mut s = self.state();
        if s.closed {
            return false;
        }
        if s.event_bytes > 0 && s.event_bytes + event.len() > EVENT_BUDGET_BYTES {
            s.dropped += 1;
            s.unreported += 1;
            return true;
        }
        if s.unreported > 0 {
            let notice = format!(
                "{{\"event\":\"dropped\",\"events\":{},\"total\":{}}}",
                s.unreported, s.dropped
            );
            s.unreported = 0;
            s.lines.push_back((Arc::from(notice), true));
        }
        s.event_bytes += event.len();
        s.lines.push_back((Arc::clone(event), true));
        drop(s);
        self.queued.notify_one();
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn event(n: usize) -> Arc<str> {
        Arc::from(format!(
            "{{\"event\":\"pose\",\"pad\":\"{}\"}}",
            "x".repeat(n)
        ))
    }

    #[test]
    fn events_past_the_budget_are_dropped_counted_and_reported_before_the_next() {
        let out = Arc::new(Outbox::default());
        let big = event(EVENT_BUDGET_BYTES / 4);
        let mut taken = 0;
        for _ in 0..10 {
            assert!(out.offer(&big));
            taken += 1;
        }
        // Four fit at most; the rest were counted, not queued.
        let queued = out.take().unwrap_or_default();
        assert!(queued.len() < 5, "{}", queued.len());
        assert_eq!(out.dropped(), (taken - queued.len()) as u64);
        assert!(out.offer(&event(1)));
        let next = out.take().unwrap_or_default();
        assert_eq!(next.len(), 2);
        assert!(
            next[0].0.starts_with(&format!(
                "{{\"event\":\"dropped\",\"events\":{}",
                out.dropped()
            )),
            "{}",
            next[0].0
        );
    }

    #[test]
    fn answers_are_always_taken_and_a_closed_outbox_takes_no_events() {
        let out = Arc::new(Outbox::default());
        assert!(
            out.offer(&event(EVENT_BUDGET_BYTES * 2)),
            "one large event fits"
        );
        out.answer("{\"ok\":true}".into());
        assert_eq!(out.answers_waiting(), 1);
        assert_eq!(out.take().map(|l| l.len()), Some(2));
        out.wrote(1);
        assert_eq!(out.answers_waiting(), 0);
        out.close();
        assert!(!out.offer(&event(1)));
        assert!(out.take().is_none());
    }
}
