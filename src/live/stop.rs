//! The emergency stop's own path to the robot: it does not queue behind lines being
//! compiled or answers being written. A front end raises it; the engine's thread looks
//! before every tick, joins the ILMR line `stop` (so it means exactly what typing
//! `stop` means, ramp included) and acknowledges once the robot has been commanded
//! to brake.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use super::engine::LineAnswer;
use super::reply::Reply;

/// Raised by any number of front ends at once; every raiser is answered.
#[derive(Default)]
pub struct EmergencyStop {
    raised: AtomicBool,
    /// Who waits for the acknowledgement: one per asking request, and a front end
    /// asks one at a time per client, so this is bounded by the clients.
    waiting: Mutex<Vec<Reply<LineAnswer>>>,
}

impl EmergencyStop {
    /// Asks for a stop; `reply` gets the answer of the `stop` line once the robot has
    /// been commanded to brake (at most two ticks later).
    pub fn raise(&self, reply: Reply<LineAnswer>) {
        self.waiting
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(reply);
        self.raised.store(true, Ordering::SeqCst);
    }

    /// The waiting raisers, when a stop was asked for since the last look (the
    /// engine's, before every tick).
    pub fn take(&self) -> Option<Vec<Reply<LineAnswer>>> {
        if !self.raised.swap(false, Ordering::SeqCst) {
            return None;
        }
        Some(std::mem::take(
            &mut *self
                .waiting
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raises_are_taken_once_together() {
        let stop = EmergencyStop::default();
        assert!(stop.take().is_none());
        let (tx, _rx) = std::sync::mpsc::channel();
        stop.raise(tx.clone().into());
        stop.raise(tx.into());
        assert_eq!(stop.take().map(|w| w.len()), Some(2));
        assert!(stop.take().is_none());
    }
}
