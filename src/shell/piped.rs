//! Lines from stdin when it is not a terminal (a pipe, a file). Each line is read
//! within [`MAX_LINE_BYTES`]; a line that is too long or not UTF-8 is an error for
//! that line only, and the lines after it are read as usual.

use std::io::{self, BufRead, Read};

use crate::live::MAX_LINE_BYTES;

/// Reads a line at a time from `input`, counting lines from 1.
pub struct Piped<R> {
    input: R,
    number: usize,
    buf: Vec<u8>,
}

/// One line, or why it is skipped.
pub type Line = Result<String, String>;

impl<R: BufRead> Piped<R> {
    pub fn new(input: R) -> Piped<R> {
        Piped {
            input,
            number: 0,
            buf: Vec::new(),
        }
    }

    /// The next line without its `\n` (or `\r\n`); `None` at the end of input. Only a
    /// failing read is an `Err`.
    pub fn next_line(&mut self) -> io::Result<Option<Line>> {
        self.buf.clear();
        let limit = MAX_LINE_BYTES as u64 + 1;
        let read = (&mut self.input)
            .take(limit)
            .read_until(b'\n', &mut self.buf)?;
        if read == 0 {
            return Ok(None);
        }
        self.number += 1;
        let ended = self.buf.last() == Some(&b'\n');
        if !ended && self.buf.len() > MAX_LINE_BYTES {
            self.skip_rest()?;
            return Ok(Some(Err(format!(
                "line {} is longer than {} bytes (MAX_LINE_BYTES); skipped",
                self.number, MAX_LINE_BYTES
            ))));
        }
        if ended {
            self.buf.pop();
            if self.buf.last() == Some(&b'\r') {
                self.buf.pop();
            }
        }
        Ok(Some(match std::str::from_utf8(&self.buf) {
            Ok(text) => Ok(text.to_string()),
            Err(e) => Err(format!(
                "line {} is not UTF-8 (invalid byte at column {}); skipped",
                self.number,
                e.valid_up_to() + 1
            )),
        }))
    }

    /// Drops the rest of an overlong line, up to and with its `\n`, holding at most
    /// one buffer of it at a time.
    fn skip_rest(&mut self) -> io::Result<()> {
        loop {
            let (found, used) = {
                let chunk = self.input.fill_buf()?;
                if chunk.is_empty() {
                    return Ok(());
                }
                match chunk.iter().position(|&b| b == b'\n') {
                    Some(i) => (true, i + 1),
                    None => (false, chunk.len()),
                }
            };
            self.input.consume(used);
            if found {
                return Ok(());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(input: &[u8]) -> Vec<Line> {
        let mut p = Piped::new(io::BufReader::with_capacity(64, input));
        let mut out = Vec::new();
        while let Ok(Some(line)) = p.next_line() {
            out.push(line);
        }
        out
    }

    #[test]
    fn bad_bytes_spoil_their_line_only() {
        assert_eq!(
            lines(b"speed(0.2)\r\ngo\xffahead(1)\n\nstop"),
            vec![
                Ok("speed(0.2)".into()),
                Err("line 2 is not UTF-8 (invalid byte at column 3); skipped".into()),
                Ok(String::new()),
                Ok("stop".into()),
            ]
        );
    }

    #[test]
    fn an_overlong_line_is_skipped_whole() {
        let mut input = b"cont\n".to_vec();
        input.extend(std::iter::repeat_n(b'(', 3 * MAX_LINE_BYTES));
        input.extend(b"\nstop\n");
        assert_eq!(
            lines(&input),
            vec![
                Ok("cont".into()),
                Err(format!(
                    "line 2 is longer than {MAX_LINE_BYTES} bytes (MAX_LINE_BYTES); skipped"
                )),
                Ok("stop".into()),
            ]
        );
        // Exactly the limit, newline apart, is a line.
        let mut input = vec![b'x'; MAX_LINE_BYTES];
        input.push(b'\n');
        assert_eq!(
            lines(&input).first().map(|l| l.as_ref().map(String::len)),
            Some(Ok(MAX_LINE_BYTES))
        );
    }
}
