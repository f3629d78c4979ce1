//! The trace's numbers: at most four decimals, no trailing zeros, and a string for the
//! values JSON has no number for.
//!
//! JSON has no infinity and no NaN. A variable can hold either (`x=1e999`, the distance
//! of an endless movement), so the trace writes them as the strings `"inf"`, `"-inf"`
//! and `"nan"`, and a [`Num`] reads them back: every value the VM traces round-trips.
//! (Before schema version 1 the writer put `1e999`, which serde_json refuses.)

use std::borrow::Cow;
use std::fmt::{self, Write as _};
use std::io;

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A number of the trace (see the module's documentation for its form).
#[derive(Debug, Clone, Copy, Default)]
pub struct Num(pub f64);

/// The strings that stand for the values JSON has no number for.
pub const INFINITY: &str = "inf";
pub const NEG_INFINITY: &str = "-inf";
pub const NAN: &str = "nan";

impl PartialEq for Num {
    /// Bit for bit once NaNs are made one: a NaN read back is the NaN written.
    fn eq(&self, other: &Num) -> bool {
        (self.0.is_nan() && other.0.is_nan()) || self.0 == other.0
    }
}

impl From<f64> for Num {
    fn from(x: f64) -> Num {
        Num(x)
    }
}

fn non_finite_name(x: f64) -> Option<&'static str> {
    if x.is_nan() {
        Some(NAN)
    } else if x == f64::INFINITY {
        Some(INFINITY)
    } else if x == f64::NEG_INFINITY {
        Some(NEG_INFINITY)
    } else {
        None
    }
}

impl Serialize for Num {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match non_finite_name(self.0) {
            Some(name) => s.serialize_str(name),
            None => s.serialize_f64(self.0),
        }
    }
}

struct NumVisitor;

impl Visitor<'_> for NumVisitor {
    type Value = Num;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "a number, \"{INFINITY}\", \"{NEG_INFINITY}\" or \"{NAN}\""
        )
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Num, E> {
        Ok(Num(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Num, E> {
        Ok(Num(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Num, E> {
        Ok(Num(v as f64))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Num, E> {
        match v {
            INFINITY => Ok(Num(f64::INFINITY)),
            NEG_INFINITY => Ok(Num(f64::NEG_INFINITY)),
            NAN => Ok(Num(f64::NAN)),
            _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
        }
    }
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Num, D::Error> {
        d.deserialize_any(NumVisitor)
    }
}

impl JsonSchema for Num {
    fn schema_name() -> Cow<'static, str> {
        "Num".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A number: at most four decimals, except in the exact `tape` and `input` lines; infinity, minus infinity and NaN, which JSON has no number for, are the strings \"inf\", \"-inf\" and \"nan\".",
            "oneOf": [
                { "type": "number" },
                { "type": "string", "enum": [INFINITY, NEG_INFINITY, NAN] }
            ]
        })
    }
}

/// Room for `{:.4}` of any finite f64: 309 integer digits, a sign, a point and four
/// decimals.
const SHORT_ROOM: usize = 320;

/// Formats on the stack, so writing a number allocates nothing.
struct Stack {
    buf: [u8; SHORT_ROOM],
    len: usize,
}

impl fmt::Write for Stack {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        let room = self.buf.get_mut(self.len..end).ok_or(fmt::Error)?;
        room.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// Writes a finite number with at most four decimals and no trailing zeros (`-0` as
/// `0`). A non-finite one is written as [`fmt_num`] words it.
pub fn write_short<W: ?Sized + io::Write>(out: &mut W, x: f64) -> io::Result<()> {
    if !x.is_finite() {
        return out.write_all(human_non_finite(x).as_bytes());
    }
    if let Some(n) = ten_thousandths(x) {
        return write_ten_thousandths(out, n);
    }
    let mut s = Stack {
        buf: [0; SHORT_ROOM],
        len: 0,
    };
    write!(s, "{x:.4}").map_err(|_| io::Error::other("a number too long to write"))?;
    let mut text = &s.buf[..s.len];
    if text.contains(&b'.') {
        while let [rest @ .., b'0'] = text {
            text = rest;
        }
        if let [rest @ .., b'.'] = text {
            text = rest;
        }
    }
    if text == b"-0" {
        text = b"0";
    }
    out.write_all(text)
}

/// Beyond this many ten-thousandths the product `x * 1e4` may be off by more than
/// [`HALF_MARGIN`] allows.
const FAST_LIMIT: f64 = 1e11;
/// How far from a half the product must be for rounding it to agree with rounding
/// `x`'s exact decimal value, as `{:.4}` does: the product's own error is at most
/// half an ulp of 1e11, about 1e-5.
const HALF_MARGIN: f64 = 1e-3;

/// `x` rounded to ten-thousandths, when rounding the product `x * 1e4` is sure to
/// give what `{:.4}` gives; `None` near a half, where only exact formatting can tell.
/// `{:.4}` is ten times slower than the rest of writing a line, and most values
/// (poses, scanner hits) are far from a half.
fn ten_thousandths(x: f64) -> Option<i64> {
    let f = x * 1e4;
    if f.abs() >= FAST_LIMIT || (f.abs().fract() - 0.5).abs() <= HALF_MARGIN {
        return None;
    }
    Some(f.round() as i64)
}

/// Writes `n` ten-thousandths as `{:.4}` and the trimming would.
fn write_ten_thousandths<W: ?Sized + io::Write>(out: &mut W, n: i64) -> io::Result<()> {
    // Sign, 11 integer digits at most (FAST_LIMIT), point, four decimals.
    let mut buf = [0u8; 24];
    let mut at = buf.len();
    let (whole, mut frac) = (n.unsigned_abs() / 10_000, n.unsigned_abs() % 10_000);
    let mut decimals = 4;
    while decimals > 0 && frac % 10 == 0 && frac > 0 {
        frac /= 10;
        decimals -= 1;
    }
    if frac > 0 {
        for _ in 0..decimals {
            at -= 1;
            buf[at] = b'0' + (frac % 10) as u8;
            frac /= 10;
        }
        at -= 1;
        buf[at] = b'.';
    }
    let mut w = whole;
    loop {
        at -= 1;
        buf[at] = b'0' + (w % 10) as u8;
        w /= 10;
        if w == 0 {
            break;
        }
    }
    if n < 0 {
        at -= 1;
        buf[at] = b'-';
    }
    out.write_all(&buf[at..])
}

/// How a message for a person words a value JSON has no number for. Trace lines never
/// use it: they carry [`Num`]'s strings.
fn human_non_finite(x: f64) -> &'static str {
    if x.is_nan() {
        "null"
    } else if x > 0.0 {
        "1e999"
    } else {
        "-1e999"
    }
}

/// A number as the trace writes it, for messages and answers that quote trace values.
pub fn fmt_num(x: f64) -> String {
    let mut out = Vec::with_capacity(16);
    // Writing to a Vec cannot fail and the text is ASCII.
    let _ = write_short(&mut out, x);
    String::from_utf8(out).unwrap_or_default()
}

/// serde_json's formatter with the trace's numbers.
#[derive(Debug, Clone, Copy, Default)]
pub struct Short;

impl serde_json::ser::Formatter for Short {
    fn write_f64<W: ?Sized + io::Write>(&mut self, out: &mut W, x: f64) -> io::Result<()> {
        write_short(out, x)
    }

    fn write_f32<W: ?Sized + io::Write>(&mut self, out: &mut W, x: f32) -> io::Result<()> {
        write_short(out, f64::from(x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_stable() {
        assert_eq!(fmt_num(0.01), "0.01");
        assert_eq!(fmt_num(3.0 * 0.01), "0.03");
        assert_eq!(fmt_num(-0.00001), "0");
        assert_eq!(fmt_num(1.23456), "1.2346");
        assert_eq!(fmt_num(2.0), "2");
        assert_eq!(fmt_num(-12.5), "-12.5");
        assert_eq!(fmt_num(1e20), "100000000000000000000");
        assert_eq!(fmt_num(f64::MAX).len(), 309);
        assert_eq!(fmt_num(-f64::MAX).len(), 310);
    }

    /// The fast path gives `{:.4}`'s digits, trimmed, for values of every size and
    /// for those at and near a half.
    #[test]
    fn the_fast_path_writes_what_exact_formatting_writes() {
        let exact = |x: f64| {
            let s = format!("{x:.4}");
            let s = if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                s
            };
            if s == "-0" { "0".to_string() } else { s }
        };
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut fast = 0;
        for i in 0..400_000 {
            let r = (next() >> 11) as f64 / (1u64 << 53) as f64;
            let scale = 10f64.powi(i % 16 - 5);
            let mut x = (r - 0.5) * scale;
            if i % 4 == 0 {
                // On and next to a half of the fourth decimal.
                x = ((x * 1e4).trunc() + 0.5) / 1e4;
            } else if i % 4 == 1 {
                x = (x * 100.0).round() / 100.0;
            }
            fast += usize::from(ten_thousandths(x).is_some());
            assert_eq!(fmt_num(x), exact(x), "{x:e}");
        }
        assert!(fast > 200_000, "the fast path took {fast}");
    }

    #[test]
    fn non_finite_values_round_trip_as_strings() {
        for x in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 0.5, -3.0] {
            let mut out = Vec::new();
            let mut ser = serde_json::Serializer::with_formatter(&mut out, Short);
            Num(x).serialize(&mut ser).unwrap();
            let text = String::from_utf8(out).unwrap();
            let back: Num = serde_json::from_str(&text).unwrap();
            assert_eq!(back, Num(x), "{x} written as {text}");
        }
        assert_eq!(
            serde_json::to_string(&Num(f64::INFINITY)).unwrap(),
            "\"inf\""
        );
        assert_eq!(serde_json::to_string(&Num(f64::NAN)).unwrap(), "\"nan\"");
        assert!(serde_json::from_str::<Num>("\"infinity\"").is_err());
    }
}
