//! The one place byte offsets meet LSP positions. The compiler's spans are bytes; LSP
//! counts lines and UTF-16 code units. Lines holding only ASCII (nearly all of them)
//! convert by arithmetic; the rest walk their characters from the nearest checkpoint,
//! so that a position on a megabyte-long line costs no more than one on a short one.

use ilmr_compiler::Span;
use tower_lsp_server::ls_types::{Position, Range, TextDocumentContentChangeEvent};

#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LineIndex {
    /// Byte offset where each line starts; the first is 0.
    starts: Vec<u32>,
    /// Whether each line is pure ASCII, where bytes and UTF-16 units coincide.
    ascii: Vec<bool>,
    /// On lines that are not ASCII, every `CHECKPOINT` bytes or so: a byte offset (a
    /// character boundary) and its UTF-16 column.
    checkpoints: Vec<(u32, u32)>,
    len: u32,
}

/// How far apart checkpoints are, in bytes: the most one conversion walks.
const CHECKPOINT: usize = 1024;

/// The lines of `text[from..to]` (`from` a line's start; `to` the text's end when
/// `to_end`, else one past a line break): the starts of all but the first, each line's
/// ASCII flag, and the checkpoints of the lines that are not ASCII.
struct Scanned {
    starts: Vec<u32>,
    ascii: Vec<bool>,
    checkpoints: Vec<(u32, u32)>,
}

fn scan(text: &str, from: usize, to: usize, to_end: bool) -> Scanned {
    let mut starts = Vec::new();
    let mut ascii = Vec::new();
    let mut line_ascii = true;
    for (i, b) in text.as_bytes()[from..to].iter().enumerate() {
        if *b == b'\n' {
            ascii.push(line_ascii);
            line_ascii = true;
            starts.push((from + i) as u32 + 1);
        } else if !b.is_ascii() {
            line_ascii = false;
        }
    }
    // The text's last line has no break; a region that ends at a break has no more.
    if to_end {
        ascii.push(line_ascii);
    } else {
        starts.pop();
    }
    let mut checkpoints = Vec::new();
    for (line, _) in ascii.iter().enumerate().filter(|(_, a)| !**a) {
        let start = if line == 0 {
            from
        } else {
            starts[line - 1] as usize
        };
        let end = starts.get(line).map_or(to, |&s| s as usize);
        let (mut last, mut column) = (start, 0);
        for (i, c) in text[start..end].char_indices() {
            if i + start - last >= CHECKPOINT {
                last = i + start;
                checkpoints.push((last as u32, column));
            }
            column += c.len_utf16() as u32;
        }
    }
    Scanned {
        starts,
        ascii,
        checkpoints,
    }
}

impl LineIndex {
    pub fn new(text: &str) -> LineIndex {
        let scanned = scan(text, 0, text.len(), true);
        let mut starts = Vec::with_capacity(scanned.starts.len() + 1);
        starts.push(0);
        starts.extend(scanned.starts);
        LineIndex {
            starts,
            ascii: scanned.ascii,
            checkpoints: scanned.checkpoints,
            len: text.len() as u32,
        }
    }

    /// Applies a client's edits to `text` in order, keeping this index in step: a
    /// ranged edit re-reads only the lines it touched, a whole-text one everything.
    pub fn apply(&mut self, text: &mut String, changes: Vec<TextDocumentContentChangeEvent>) {
        for change in changes {
            match change.range {
                Some(range) => {
                    let span = self.span(text, range);
                    text.replace_range(span.range(), &change.text);
                    self.edit(text, span.range(), change.text.len());
                }
                None => {
                    *text = change.text;
                    *self = LineIndex::new(text);
                }
            }
        }
    }

    /// The index of `text`, which is the indexed text with the bytes `old` replaced by
    /// `inserted` bytes: the lines the edit touched are read again and the rest
    /// shifted, so that a keystroke in a 100,000-line file does not read the file.
    pub fn edit(&mut self, text: &str, old: std::ops::Range<usize>, inserted: usize) {
        let first = self.line_of(old.start);
        let last = self.line_of(old.end);
        let from = self.starts[first] as usize;
        let shift = |offset: u32| (offset as i64 + inserted as i64 - old.len() as i64) as u32;
        // Where the lines after the edit begin, before and after it.
        let (next_old, next_new, to_end) = match self.starts.get(last + 1) {
            Some(&s) => (s as usize, shift(s) as usize, false),
            None => (self.len as usize + 1, text.len(), true),
        };
        let scanned = scan(text, from, next_new, to_end);
        let after = first + 1 + scanned.starts.len();
        self.starts.splice(first + 1..=last, scanned.starts);
        for s in &mut self.starts[after..] {
            *s = shift(*s);
        }
        self.ascii.splice(first..=last, scanned.ascii);
        let lo = self.checkpoints.partition_point(|c| (c.0 as usize) < from);
        let hi = self
            .checkpoints
            .partition_point(|c| (c.0 as usize) < next_old);
        let added = scanned.checkpoints.len();
        self.checkpoints.splice(lo..hi, scanned.checkpoints);
        for c in &mut self.checkpoints[lo + added..] {
            c.0 = shift(c.0);
        }
        self.len = text.len() as u32;
    }

    /// The checkpoint of a line nearest before `offset` (a byte offset, or a column
    /// when `by_column`), else the line's start.
    fn checkpoint(&self, line: usize, at: usize, by_column: bool) -> (usize, usize) {
        let start = self.starts[line] as usize;
        let end = self
            .starts
            .get(line + 1)
            .map_or(self.len as usize + 1, |&s| s as usize);
        let from = self.checkpoints.partition_point(|c| (c.0 as usize) < start);
        let to = self.checkpoints.partition_point(|c| (c.0 as usize) < end);
        let ours = &self.checkpoints[from..to];
        let before = ours.partition_point(|&(b, c)| {
            if by_column {
                c as usize <= at
            } else {
                b as usize <= at
            }
        });
        match before.checked_sub(1).map(|i| ours[i]) {
            Some((b, c)) => (b as usize, c as usize),
            None => (start, 0),
        }
    }

    pub fn line_count(&self) -> usize {
        self.starts.len()
    }

    /// 0-based line holding a byte offset.
    pub fn line_of(&self, offset: usize) -> usize {
        self.starts.partition_point(|&s| s as usize <= offset) - 1
    }

    /// The byte range of a line without its line break.
    pub fn line_span(&self, text: &str, line: usize) -> Span {
        let start = self.starts.get(line).map_or(self.len, |&s| s) as usize;
        let end = self
            .starts
            .get(line + 1)
            .map_or(self.len as usize, |&s| s as usize - 1);
        let end = end.max(start);
        // A CRLF file keeps its `\r` out of the line's text.
        let end = if text.as_bytes().get(end.wrapping_sub(1)) == Some(&b'\r') && end > start {
            end - 1
        } else {
            end
        };
        Span::new(start, end)
    }

    pub fn position(&self, text: &str, offset: usize) -> Position {
        let offset = offset.min(self.len as usize);
        let line = self.line_of(offset);
        let start = self.starts[line] as usize;
        let character = if self.ascii[line] {
            offset - start
        } else {
            // An offset inside a character counts up to that character's start.
            let mut end = offset;
            while !text.is_char_boundary(end) {
                end -= 1;
            }
            let (from, column) = self.checkpoint(line, end, false);
            column + text[from..end].chars().map(char::len_utf16).sum::<usize>()
        };
        Position::new(line as u32, character as u32)
    }

    /// The byte offset of a position, clamped to its line: clients may send a column past
    /// the end of the line, or a line past the end of the text.
    pub fn offset(&self, text: &str, position: Position) -> usize {
        let line = position.line as usize;
        if line >= self.starts.len() {
            return self.len as usize;
        }
        let span = self.line_span(text, line);
        let wanted = position.character as usize;
        if self.ascii[line] {
            return (span.start as usize + wanted).min(span.end as usize);
        }
        let (from, mut units) = self.checkpoint(line, wanted, true);
        let from = from.min(span.end as usize);
        for (i, c) in text[from..span.end as usize].char_indices() {
            if units >= wanted {
                return from + i;
            }
            units += c.len_utf16();
        }
        span.end as usize
    }

    /// Converts offsets given in increasing order, each line walked at most once:
    /// semantic tokens ask for every token of a file.
    pub fn walk<'a>(&'a self, text: &'a str) -> Walk<'a> {
        Walk {
            index: self,
            text,
            line: usize::MAX,
            offset: 0,
            column: 0,
        }
    }

    pub fn range(&self, text: &str, span: Span) -> Range {
        Range::new(
            self.position(text, span.start as usize),
            self.position(text, span.end as usize),
        )
    }

    pub fn span(&self, text: &str, range: Range) -> Span {
        let start = self.offset(text, range.start);
        let end = self.offset(text, range.end).max(start);
        Span::new(start, end)
    }
}

/// See [`LineIndex::walk`]: the last position converted, to walk on from.
pub struct Walk<'a> {
    index: &'a LineIndex,
    text: &'a str,
    line: usize,
    offset: usize,
    column: usize,
}

impl Walk<'_> {
    pub fn position(&mut self, offset: usize) -> Position {
        let (index, text) = (self.index, self.text);
        let mut offset = offset.min(index.len as usize);
        let line = index.line_of(offset);
        if index.ascii[line] {
            return Position::new(line as u32, (offset - index.starts[line] as usize) as u32);
        }
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let (mut from, mut column) = index.checkpoint(line, offset, false);
        if line == self.line && from <= self.offset && self.offset <= offset {
            (from, column) = (self.offset, self.column);
        }
        column += text[from..offset]
            .chars()
            .map(char::len_utf16)
            .sum::<usize>();
        (self.line, self.offset, self.column) = (line, offset, column);
        Position::new(line as u32, column as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finnish_names_count_utf16_units() {
        let text = "a=1\nkäännös=turn(left)\novi_ö=𝔸\n";
        let idx = LineIndex::new(text);
        let eq = text.find("=turn").unwrap();
        assert_eq!(idx.position(text, eq), Position::new(1, 7));
        assert_eq!(idx.offset(text, Position::new(1, 7)), eq);
        // U+1D538 takes two UTF-16 units and four bytes.
        let end = text.rfind('\n').unwrap();
        assert_eq!(idx.position(text, end), Position::new(2, 8));
        assert_eq!(idx.offset(text, Position::new(2, 8)), end);
        // A column in the middle of a surrogate pair lands on the character after it.
        assert_eq!(idx.offset(text, Position::new(2, 7)), end);
    }

    /// Positions walked from the line's start, as the index did before checkpoints.
    fn walked(text: &str, offset: usize) -> Position {
        let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
        let line = text[..offset].matches('\n').count() as u32;
        let units: usize = text[line_start..offset].chars().map(char::len_utf16).sum();
        Position::new(line, units as u32)
    }

    #[test]
    fn long_lines_convert_through_checkpoints_as_walking_does() {
        let line: String = (0..3_000).map(|i| ["ä", "a", "𝔸", "ab"][i % 4]).collect();
        let text = format!("x\n{line}\nplain {}\n{line}", "b".repeat(5_000));
        let idx = LineIndex::new(&text);
        assert!(!idx.checkpoints.is_empty());
        let mut walk = idx.walk(&text);
        for (offset, _) in text.char_indices().chain([(text.len(), ' ')]) {
            let p = walked(&text, offset);
            assert_eq!(idx.position(&text, offset), p, "at byte {offset}");
            assert_eq!(walk.position(offset), p, "walking, at byte {offset}");
            assert_eq!(idx.offset(&text, p), offset, "at {p:?}");
        }
    }

    #[test]
    fn out_of_range_positions_are_clamped() {
        let text = "ab\ncd";
        let idx = LineIndex::new(text);
        assert_eq!(idx.offset(text, Position::new(0, 99)), 2);
        assert_eq!(idx.offset(text, Position::new(9, 0)), 5);
        assert_eq!(idx.position(text, 99), Position::new(1, 2));
    }

    /// Edits of every shape (within a line, across lines, adding and removing breaks,
    /// at both ends, on long lines that are not ASCII) leave the index as reading the
    /// whole text again would.
    #[test]
    fn an_edited_index_is_the_index_of_the_edited_text() {
        let pieces = ["a", "ä", "\n", "\r\n", "𝔸", "xyz", "", "\n\n"];
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = |n: usize| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % n as u64) as usize
        };
        let long: String = "ä".repeat(CHECKPOINT);
        let mut text = format!("start\n{long}\nmiddle\n{long}b\nend");
        let mut index = LineIndex::new(&text);
        for _ in 0..3_000 {
            let boundaries: Vec<usize> = text
                .char_indices()
                .map(|(i, _)| i)
                .chain([text.len()])
                .collect();
            let a = boundaries[next(boundaries.len())];
            let b = boundaries[next(boundaries.len())];
            let (a, b) = (a.min(b), a.max(b));
            let (a, b) = if next(4) == 0 {
                (a, a)
            } else {
                (a, b.min(a + 40))
            };
            let b = *boundaries.iter().find(|&&x| x >= b).expect("a boundary");
            let mut inserted: String = (0..next(4)).map(|_| pieces[next(pieces.len())]).collect();
            if next(50) == 0 {
                inserted.push_str(&long);
            }
            text.replace_range(a..b, &inserted);
            index.edit(&text, a..b, inserted.len());
            assert_eq!(
                index,
                LineIndex::new(&text),
                "after replacing {a}..{b} by {inserted:?}"
            );
        }
    }

    #[test]
    fn crlf_lines_end_before_the_carriage_return() {
        let text = "ab\r\ncd";
        let idx = LineIndex::new(text);
        assert_eq!(idx.line_span(text, 0), Span::new(0, 2));
        assert_eq!(idx.offset(text, Position::new(0, 5)), 2);
    }
}
