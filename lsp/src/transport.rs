//! stdin and stdout for tower-lsp-server with the framing in front: a thread cuts
//! stdin into messages and passes on only those `message::check` accepts; the others
//! are answered on stdout at once. Both writers put whole messages on stdout under one
//! lock, so an error answer never lands inside one of the server's messages.

use std::io::{Read, Write};
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::sync::mpsc;

use crate::framing::{Frame, Reader};
use crate::message;

/// stdout, shared by the server and the reader thread, written one message at a time.
#[derive(Clone)]
pub struct Output(Arc<Mutex<Box<dyn Write + Send>>>);

impl Output {
    pub fn new(out: impl Write + Send + 'static) -> Output {
        Output(Arc::new(Mutex::new(Box::new(out))))
    }

    fn write_message(&self, bytes: &[u8]) -> std::io::Result<()> {
        let mut out = self.0.lock().unwrap_or_else(|e| e.into_inner());
        out.write_all(bytes)?;
        out.flush()
    }
}

/// The accepted messages, re-framed, as the server's input stream.
pub struct Incoming {
    messages: mpsc::Receiver<Vec<u8>>,
    chunk: Vec<u8>,
    at: usize,
}

/// Starts the thread that reads `input`; it ends with the input (or the process).
pub fn incoming(input: impl Read + Send + 'static, output: Output) -> std::io::Result<Incoming> {
    // One message in flight: a slow server slows the reading, not the memory.
    let (tx, messages) = mpsc::channel::<Vec<u8>>(1);
    std::thread::Builder::new()
        .name("ilmr-stdin".into())
        .spawn(move || {
            let mut reader = Reader::new(input);
            while let Some(frame) = reader.next_frame() {
                let refused = match frame {
                    Frame::Body(body) => match message::check(&body) {
                        Ok(()) => {
                            let head = format!("Content-Length: {}\r\n\r\n", body.len());
                            if tx.blocking_send(head.into_bytes()).is_err()
                                || tx.blocking_send(body).is_err()
                            {
                                return;
                            }
                            continue;
                        }
                        Err(r) => r,
                    },
                    Frame::Bad(r) => r,
                };
                eprintln!("ilmr-lsp: refused a message: {}", refused.message);
                if output.write_message(&refused.response()).is_err() {
                    return;
                }
            }
        })?;
    Ok(Incoming {
        messages,
        chunk: Vec::new(),
        at: 0,
    })
}

impl AsyncRead for Incoming {
    fn poll_read(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<std::io::Result<()>> {
        let this = self.get_mut();
        while this.at == this.chunk.len() {
            match this.messages.poll_recv(cx) {
                Poll::Ready(Some(chunk)) => {
                    this.chunk = chunk;
                    this.at = 0;
                }
                // The end of input: an empty read.
                Poll::Ready(None) => return Poll::Ready(Ok(())),
                Poll::Pending => return Poll::Pending,
            }
        }
        let n = buf.remaining().min(this.chunk.len() - this.at);
        buf.put_slice(&this.chunk[this.at..this.at + n]);
        this.at += n;
        Poll::Ready(Ok(()))
    }
}

/// The server's output stream: written to stdout a whole message at a time.
pub struct Outgoing {
    output: Output,
    pending: Vec<u8>,
}

impl Outgoing {
    pub fn new(output: Output) -> Outgoing {
        Outgoing {
            output,
            pending: Vec::new(),
        }
    }
}

impl AsyncWrite for Outgoing {
    fn poll_write(
        self: Pin<&mut Self>,
        _: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<std::io::Result<usize>> {
        let this = self.get_mut();
        this.pending.extend_from_slice(buf);
        while let Some(n) = complete_message(&this.pending) {
            this.output.write_message(&this.pending[..n])?;
            this.pending.drain(..n);
        }
        Poll::Ready(Ok(buf.len()))
    }

    fn poll_flush(self: Pin<&mut Self>, _: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Poll::Ready(Ok(()))
    }

    fn poll_shutdown(self: Pin<&mut Self>, _: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Poll::Ready(Ok(()))
    }
}

/// The length of the first message in `buf` once all of it is there. The server's own
/// encoder wrote it: `Content-Length: N\r\n\r\n` and N bytes.
fn complete_message(buf: &[u8]) -> Option<usize> {
    let end = buf.windows(4).position(|w| w == b"\r\n\r\n")?;
    let head = std::str::from_utf8(&buf[..end]).ok()?;
    let length: usize = head
        .lines()
        .find_map(|l| l.strip_prefix("Content-Length: "))?
        .trim()
        .parse()
        .ok()?;
    let total = end + 4 + length;
    (buf.len() >= total).then_some(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_is_complete_with_its_whole_body() {
        let m = b"Content-Length: 2\r\n\r\n{}Content-Length: 1";
        assert_eq!(complete_message(&m[..22]), None);
        assert_eq!(complete_message(&m[..23]), Some(23));
        assert_eq!(complete_message(m), Some(23));
    }
}
