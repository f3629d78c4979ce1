//! Cutting the client's byte stream into messages (`Content-Length` framing), so that
//! a bad header, an oversized message or a stream of garbage costs one error answer
//! and the next message is read as usual. tower-lsp-server's own decoder ends the
//! whole session at the first frame it cannot decode, so it only ever sees frames
//! this reader has cut and `message::check` has accepted.
//!
//! Headers follow the LSP base protocol: lines ending in `\r\n` (a bare `\n` is taken
//! too), names case-insensitive, an empty line before the body. `Content-Length` is
//! required; `Content-Type`, when given, must name UTF-8 or no charset; other headers
//! are ignored. Line breaks between messages are skipped.

use std::io::Read;

use crate::message::{PARSE_ERROR, Rejection};

/// The largest message body read, in bytes. It must hold a `didOpen` or full-text
/// `didChange` of the largest source `ilmrc` reads (`ilmr_files::MAX_SOURCE_BYTES`,
/// 8 MiB), even if JSON escapes every byte as `\u00XX` (six times as long). A longer
/// message is skipped by its declared length, unread, so that the next message is found
/// where the sender put it.
pub const MAX_MESSAGE_BYTES: usize = 64 * 1024 * 1024;

const _: () = assert!(6 * ilmr_files::MAX_SOURCE_BYTES + 4096 < MAX_MESSAGE_BYTES as u64);

/// The longest header section, in bytes. Real clients send one or two short lines; a
/// stream without an empty line within this many bytes is garbage, not a header.
pub const MAX_HEADER_BYTES: usize = 8 * 1024;

/// How much is read from the stream at once.
const CHUNK: usize = 64 * 1024;

const CONTENT_LENGTH: &[u8] = b"content-length";

/// One message cut from the stream.
#[derive(Debug, PartialEq)]
pub enum Frame {
    Body(Vec<u8>),
    /// What the sender gets instead of an answer; reading goes on after it.
    Bad(Rejection),
}

pub struct Reader<R> {
    input: R,
    /// Bytes read but not yet consumed; while headers are read, they start here.
    buf: Vec<u8>,
    eof: bool,
    /// What to drop before the next message, after the last one was answered: the
    /// answer goes out at once, not when the sender's next bytes arrive.
    pending: Pending,
}

enum Pending {
    Nothing,
    /// The body of a message refused by its header.
    Skip(u64),
    /// Everything up to the next `Content-Length` at or after this offset.
    Resync(usize),
}

/// A header section that could not be used, and whether the body's length is known
/// all the same (then the body is skipped; else the stream is searched for the next
/// `Content-Length`).
struct HeaderError {
    message: String,
    length: Option<u64>,
}

impl<R: Read> Reader<R> {
    pub fn new(input: R) -> Reader<R> {
        Reader {
            input,
            buf: Vec::new(),
            eof: false,
            pending: Pending::Nothing,
        }
    }

    /// The next message; `None` once the stream has ended.
    pub fn next_frame(&mut self) -> Option<Frame> {
        match std::mem::replace(&mut self.pending, Pending::Nothing) {
            Pending::Nothing => {}
            Pending::Skip(length) => self.skip(length),
            Pending::Resync(from) => self.resync(from),
        }
        loop {
            let breaks = self
                .buf
                .iter()
                .take_while(|b| matches!(b, b'\r' | b'\n'))
                .count();
            self.buf.drain(..breaks);
            if self.buf.is_empty() {
                if !self.fill() {
                    return None;
                }
                continue;
            }
            let Some((end, body)) = header_end(&self.buf) else {
                if self.buf.len() > MAX_HEADER_BYTES {
                    self.pending = Pending::Resync(1);
                    return Some(bad(format!(
                        "no end of header within {MAX_HEADER_BYTES} bytes"
                    )));
                }
                if !self.fill() {
                    self.buf.clear();
                    return Some(bad("the input ended inside a header".to_string()));
                }
                continue;
            };
            match parse_header(&self.buf[..end]) {
                Ok(length) => {
                    self.buf.drain(..body);
                    if length > MAX_MESSAGE_BYTES as u64 {
                        self.pending = Pending::Skip(length);
                        return Some(bad(format!(
                            "a message of {length} bytes is longer than the limit of \
                             {MAX_MESSAGE_BYTES} bytes"
                        )));
                    }
                    return Some(match self.take(length as usize) {
                        Some(body) => Frame::Body(body),
                        None => bad(format!(
                            "the input ended inside a message of {length} bytes"
                        )),
                    });
                }
                Err(HeaderError {
                    message,
                    length: Some(length),
                }) => {
                    self.buf.drain(..body);
                    self.pending = Pending::Skip(length);
                    return Some(bad(message));
                }
                Err(HeaderError {
                    message,
                    length: None,
                }) => {
                    self.pending = Pending::Resync(1);
                    return Some(bad(message));
                }
            }
        }
    }

    /// Reads more into the buffer; false at the end of the stream.
    fn fill(&mut self) -> bool {
        if self.eof {
            return false;
        }
        let old = self.buf.len();
        self.buf.resize(old + CHUNK, 0);
        let n = loop {
            match self.input.read(&mut self.buf[old..]) {
                Ok(n) => break n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(_) => break 0,
            }
        };
        self.buf.truncate(old + n);
        self.eof = n == 0;
        n > 0
    }

    /// The next `length` bytes; `None` if the stream ends first.
    fn take(&mut self, length: usize) -> Option<Vec<u8>> {
        while self.buf.len() < length {
            if !self.fill() {
                self.buf.clear();
                return None;
            }
        }
        let rest = self.buf.split_off(length);
        Some(std::mem::replace(&mut self.buf, rest))
    }

    /// Drops the next `length` bytes without keeping them.
    fn skip(&mut self, mut length: u64) {
        loop {
            let here = (self.buf.len() as u64).min(length) as usize;
            self.buf.drain(..here);
            length -= here as u64;
            if length == 0 || !self.fill() {
                return;
            }
        }
    }

    /// Drops bytes up to the next `Content-Length` at or after `from`, where the next
    /// message presumably starts.
    fn resync(&mut self, from: usize) {
        let mut from = from.min(self.buf.len());
        loop {
            if let Some(at) = find_ignore_case(&self.buf[from..], CONTENT_LENGTH) {
                self.buf.drain(..from + at);
                return;
            }
            // Keep a tail that may be the start of the name, split between reads.
            let keep = (CONTENT_LENGTH.len() - 1).min(self.buf.len() - from);
            self.buf.drain(..self.buf.len() - keep);
            from = 0;
            if !self.fill() {
                self.buf.clear();
                return;
            }
        }
    }
}

fn bad(message: String) -> Frame {
    Frame::Bad(Rejection::new(PARSE_ERROR, message))
}

/// Where the header section ends (before its empty line) and where the body starts,
/// looking no further than `MAX_HEADER_BYTES`.
fn header_end(buf: &[u8]) -> Option<(usize, usize)> {
    let window = &buf[..buf.len().min(MAX_HEADER_BYTES + 4)];
    let mut line_start = 0;
    for (i, &b) in window.iter().enumerate() {
        if b != b'\n' {
            continue;
        }
        let line = &window[line_start..i];
        if line.is_empty() || line == b"\r" {
            return Some((line_start, i + 1));
        }
        line_start = i + 1;
    }
    None
}

fn parse_header(header: &[u8]) -> Result<u64, HeaderError> {
    let mut length: Option<u64> = None;
    let mut length_error: Option<String> = None;
    let mut other_error: Option<String> = None;
    let text = match std::str::from_utf8(header) {
        Ok(t) if t.is_ascii() => t,
        _ => {
            return Err(HeaderError {
                message: "a header holds bytes that are not ASCII".to_string(),
                length: None,
            });
        }
    };
    for line in text.lines() {
        let Some((name, value)) = line.split_once(':') else {
            other_error.get_or_insert(format!("a header line without `:`: {:?}", clip(line)));
            continue;
        };
        let value = value.trim();
        if name.is_empty() || !name.bytes().all(is_token_byte) {
            other_error.get_or_insert(format!("not a header name: {:?}", clip(name)));
        } else if name.eq_ignore_ascii_case("content-length") {
            let parsed = value
                .bytes()
                .all(|b| b.is_ascii_digit())
                .then(|| value.parse::<u64>().ok())
                .flatten();
            match (parsed, length) {
                (Some(n), None) => length = Some(n),
                (Some(n), Some(m)) if n == m => {}
                (Some(_), Some(_)) => {
                    length_error = Some("two different Content-Length headers".to_string());
                }
                (None, _) => {
                    length_error =
                        Some(format!("Content-Length is not a length: {:?}", clip(value)));
                }
            }
        } else if name.eq_ignore_ascii_case("content-type") {
            let charset = value
                .split(';')
                .skip(1)
                .filter_map(|p| p.split_once('='))
                .find(|(k, _)| k.trim().eq_ignore_ascii_case("charset"))
                .map(|(_, v)| v.trim().trim_matches('"'));
            if let Some(c) = charset
                && !c.eq_ignore_ascii_case("utf-8")
                && !c.eq_ignore_ascii_case("utf8")
            {
                other_error.get_or_insert(format!(
                    "charset {:?} is not supported, only utf-8",
                    clip(c)
                ));
            }
        }
    }
    if let Some(message) = length_error {
        return Err(HeaderError {
            message,
            length: None,
        });
    }
    let Some(length) = length else {
        return Err(HeaderError {
            message: other_error.unwrap_or_else(|| "no Content-Length header".to_string()),
            length: None,
        });
    };
    match other_error {
        Some(message) => Err(HeaderError {
            message,
            length: Some(length),
        }),
        None => Ok(length),
    }
}

/// RFC 9110's `tchar`.
fn is_token_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b"!#$%&'*+-.^_`|~".contains(&b)
}

/// Enough of a bad header to recognise it in an error message.
fn clip(s: &str) -> &str {
    let mut end = s.len().min(40);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    &s[..end]
}

fn find_ignore_case(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack
        .windows(needle.len())
        .position(|w| w.eq_ignore_ascii_case(needle))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames(input: &[u8]) -> Vec<Result<String, String>> {
        let mut reader = Reader::new(input);
        std::iter::from_fn(|| reader.next_frame())
            .map(|f| match f {
                Frame::Body(b) => Ok(String::from_utf8(b).expect("test bodies are text")),
                Frame::Bad(r) => Err(r.message),
            })
            .collect()
    }

    fn ok(s: &str) -> Result<String, String> {
        Ok(s.to_string())
    }

    #[test]
    fn messages_follow_one_another() {
        let input = b"Content-Length: 2\r\n\r\n{}Content-Length: 3\r\nContent-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n[1]";
        assert_eq!(frames(input), vec![ok("{}"), ok("[1]")]);
    }

    #[test]
    fn names_ignore_case_and_bare_line_feeds_and_blank_lines_are_taken() {
        let input = b"\r\n\ncontent-length: 2\n\n{}\r\nCONTENT-LENGTH:3\r\n\r\n[1]";
        assert_eq!(frames(input), vec![ok("{}"), ok("[1]")]);
    }

    #[test]
    fn a_bad_length_is_answered_and_the_next_message_is_found() {
        let input = b"Content-Length: 1x\r\n\r\n{}Content-Length: 2\r\n\r\n{}";
        let got = frames(input);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(got[0].as_ref().unwrap_err().contains("not a length"));
        assert_eq!(got[1], ok("{}"));
    }

    #[test]
    fn a_missing_length_is_answered_and_the_next_message_is_found() {
        let input = b"Content-Type: application/json\r\n\r\n{}Content-Length: 2\r\n\r\n{}";
        let got = frames(input);
        assert_eq!(got[0], Err("no Content-Length header".to_string()));
        assert_eq!(got[1..], [ok("{}")]);
    }

    #[test]
    fn garbage_before_a_header_costs_one_error() {
        let input = b"{\"jsonrpc\":\"2.0\"}Content-Length: 2\r\n\r\n{}";
        let got = frames(input);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(got[0].is_err());
        assert_eq!(got[1], ok("{}"));
    }

    #[test]
    fn a_wrong_charset_skips_the_body_by_its_length() {
        let input =
            b"Content-Length: 2\r\nContent-Type: text/plain; charset=latin1\r\n\r\n{}Content-Length: 3\r\n\r\n[1]";
        let got = frames(input);
        assert!(got[0].as_ref().unwrap_err().contains("latin1"), "{got:?}");
        assert_eq!(got[1..], [ok("[1]")]);
    }

    #[test]
    fn an_oversized_message_is_skipped_unread() {
        let mut input = format!("Content-Length: {}\r\n\r\n", MAX_MESSAGE_BYTES + 1).into_bytes();
        input.resize(input.len() + MAX_MESSAGE_BYTES + 1, b'x');
        input.extend_from_slice(b"Content-Length: 2\r\n\r\n{}");
        let got = frames(&input);
        assert_eq!(got.len(), 2);
        assert!(
            got[0]
                .as_ref()
                .unwrap_err()
                .contains("longer than the limit")
        );
        assert_eq!(got[1], ok("{}"));
    }

    #[test]
    fn an_endless_header_is_cut_at_the_limit() {
        let mut input = vec![b'a'; MAX_HEADER_BYTES * 3];
        input.extend_from_slice(b"Content-Length: 2\r\n\r\n{}");
        let got = frames(&input);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(got[0].as_ref().unwrap_err().contains("no end of header"));
        assert_eq!(got[1], ok("{}"));
    }

    /// A reader that fails the test if asked for more than it was given.
    struct NoMore<'a>(&'a [u8]);

    impl Read for NoMore<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            assert!(!self.0.is_empty(), "read past what the sender sent so far");
            let n = self.0.len().min(buf.len());
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    #[test]
    fn a_refusal_does_not_wait_for_the_next_message() {
        for input in [
            &b"Content-Length: x\r\n\r\n"[..],
            &b"Content-Length: 99999999999\r\n\r\n"[..],
        ] {
            let mut reader = Reader::new(NoMore(input));
            assert!(matches!(reader.next_frame(), Some(Frame::Bad(_))));
        }
    }

    #[test]
    fn a_length_past_the_end_of_the_input_is_answered() {
        let got = frames(b"Content-Length: 10\r\n\r\n{}");
        assert_eq!(
            got,
            vec![Err(
                "the input ended inside a message of 10 bytes".to_string()
            )]
        );
        assert_eq!(
            frames(b"Content-Len"),
            vec![Err("the input ended inside a header".to_string())]
        );
        assert_eq!(frames(b"\r\n"), vec![]);
    }
}
