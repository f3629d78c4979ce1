//! Where the engine sends an answer: a thread's channel (`shell`) or an async task's
//! one-shot (`serve`), so that neither front end blocks a thread per question.

use std::sync::mpsc;

/// One answer's way back to whoever asked. Sending never blocks and never fails the
/// engine: an asker that has gone simply gets nothing.
pub struct Reply<T>(Box<dyn FnOnce(T) + Send>);

impl<T> Reply<T> {
    pub fn send(self, value: T) {
        (self.0)(value);
    }
}

impl<T: Send + 'static> From<mpsc::Sender<T>> for Reply<T> {
    fn from(sender: mpsc::Sender<T>) -> Reply<T> {
        Reply(Box::new(move |v| {
            let _ = sender.send(v);
        }))
    }
}

impl<T: Send + 'static> From<tokio::sync::oneshot::Sender<T>> for Reply<T> {
    fn from(sender: tokio::sync::oneshot::Sender<T>) -> Reply<T> {
        Reply(Box::new(move |v| {
            let _ = sender.send(v);
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_kinds_deliver_and_a_gone_asker_is_no_error() {
        let (tx, rx) = mpsc::channel();
        Reply::from(tx).send(3);
        assert_eq!(rx.recv().ok(), Some(3));
        let (tx, mut rx) = tokio::sync::oneshot::channel();
        Reply::from(tx).send("a");
        assert_eq!(rx.try_recv().ok(), Some("a"));
        let (tx, rx) = mpsc::channel::<u8>();
        drop(rx);
        Reply::from(tx).send(1);
    }
}
