//! The cost of writing trace lines, side by side with the writers it is weighed
//! against (docs/performance.md, "Trace writing"):
//!
//! - `schema`: the typed records through `ilmr_trace::write_line` into a reused buffer,
//!   as `ilmrc run --trace` writes them;
//! - `by_hand`: the hand-written writer the VM and the run used before the schema
//!   (`json_str`/`fmt_num`, a `String` per line and per number), kept here as it was;
//! - `serde_json`: the same records with serde_json's own number formatting (ryu's
//!   shortest digits rather than four decimals), the library's floor.
//!
//! The lines are those of one second of `ilmrc run examples/way_out.ilmr --trace`,
//! where `scan` and `pose` lines are 97% of the bytes: ten pose samples and one scan
//! of 330 hits. `cargo bench -p ilmr-trace --bench write`.

use std::fmt::Write as _;

use divan::{Bencher, black_box};
use ilmr_trace::{Event, Num, Pose, Record, Scan, Source};
use serde::Serialize;

fn main() {
    divan::main();
}

fn poses() -> Vec<(f64, [f64; 5])> {
    (0..10)
        .map(|i| {
            let t = 120.0 + f64::from(i) * 0.1;
            let a = t * 0.173;
            (
                t,
                [
                    8.0 + a.cos() * 3.1234567,
                    5.0 + a.sin() * 2.7654321,
                    a,
                    0.4123,
                    0.0871,
                ],
            )
        })
        .collect()
}

fn hits() -> Vec<(f64, f64)> {
    (0..330)
        .map(|i| {
            let a = f64::from(i) * 0.0095;
            let cm = |v: f64| (v * 100.0).round() / 100.0;
            (cm(9.0 + a.cos() * 4.321), cm(5.0 + a.sin() * 3.21))
        })
        .collect()
}

fn pose_record(t: f64, p: [f64; 5]) -> Record<'static> {
    Record::new(
        t,
        Event::Pose(Pose {
            x: Num(p[0]),
            y: Num(p[1]),
            h: Num(p[2]),
            v: Num(p[3]),
            c: Num(p[4]),
            source: Source::Truth,
        }),
    )
}

fn scan_record<'a>(t: f64, hits: &'a [(f64, f64)]) -> Record<'a> {
    Record::new(
        t,
        Event::Scan(Scan {
            x: Num(8.85),
            y: Num(5.0),
            h: Num(0.0),
            hits: hits.into(),
        }),
    )
}

/// One second of lines through `write`, as `ilmrc run` renders them: each line into
/// the sink's buffer, then to the file (here a buffer of the whole second).
fn second(bencher: Bencher, write: impl Fn(&mut Vec<u8>, &Record<'_>)) {
    let (poses, hits) = (poses(), hits());
    let mut line = Vec::with_capacity(256);
    let mut file = Vec::with_capacity(1 << 16);
    bencher.bench_local(|| {
        file.clear();
        for &(t, p) in &poses {
            line.clear();
            write(&mut line, &pose_record(t, p));
            file.extend_from_slice(&line);
            file.push(b'\n');
        }
        line.clear();
        write(&mut line, &scan_record(121.0, &hits));
        file.extend_from_slice(&line);
        black_box(&file);
    });
}

#[divan::bench]
fn schema(bencher: Bencher) {
    second(bencher, |out, r| {
        let _ = ilmr_trace::write_line(out, r);
    });
}

#[divan::bench]
fn serde_json(bencher: Bencher) {
    second(bencher, |out, r| {
        let _ = r.serialize(&mut serde_json::Serializer::new(out));
    });
}

#[divan::bench]
fn by_hand(bencher: Bencher) {
    let (poses, hits) = (poses(), hits());
    // The same lines, byte for byte, or the comparison says nothing.
    let (t, p) = poses[3];
    assert_eq!(ilmr_trace::to_line(&pose_record(t, p)), old::pose(t, p));
    assert_eq!(
        ilmr_trace::to_line(&scan_record(121.0, &hits)),
        old::scan(121.0, &hits)
    );
    let mut file = Vec::with_capacity(1 << 16);
    bencher.bench_local(|| {
        file.clear();
        for &(t, p) in &poses {
            let line = old::pose(t, p);
            file.extend_from_slice(line.as_bytes());
            file.push(b'\n');
        }
        let line = old::scan(121.0, &hits);
        file.extend_from_slice(line.as_bytes());
        black_box(&file);
    });
}

/// The writer before the schema, as it was (`vm/src/runtime/trace.rs`'s `fmt_num` and
/// `render_event`, `src/run/record.rs`'s `scan_line`).
mod old {
    use super::*;

    pub fn fmt_num(x: f64) -> String {
        if !x.is_finite() {
            return if x.is_nan() {
                "null".into()
            } else if x > 0.0 {
                "1e999".into()
            } else {
                "-1e999".into()
            };
        }
        let s = format!("{:.4}", x);
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        if s == "-0" { "0".into() } else { s }
    }

    pub fn pose(t: f64, p: [f64; 5]) -> String {
        let mut o = String::with_capacity(96);
        let _ = write!(o, "{{\"t\":{},\"event\":\"pose\"", fmt_num(t));
        let _ = write!(
            o,
            ",\"x\":{},\"y\":{},\"h\":{},\"v\":{},\"c\":{},\"source\":\"true\"",
            fmt_num(p[0]),
            fmt_num(p[1]),
            fmt_num(p[2]),
            fmt_num(p[3]),
            fmt_num(p[4]),
        );
        o.push('}');
        o
    }

    pub fn scan(t: f64, hits: &[(f64, f64)]) -> String {
        let mut s = String::new();
        for (i, (x, y)) in hits.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            s.push_str(&format!(
                "[{},{}]",
                fmt_num((x * 100.0).round() / 100.0),
                fmt_num((y * 100.0).round() / 100.0)
            ));
        }
        format!(
            "{{\"t\":{},\"event\":\"scan\",\"x\":{},\"y\":{},\"h\":{},\"hits\":[{s}]}}",
            fmt_num(t),
            fmt_num(8.85),
            fmt_num(5.0),
            fmt_num(0.0)
        )
    }
}
