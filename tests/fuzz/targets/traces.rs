//! Trace files, as `replay`, `diff` and `test` read them (`ilmr_trace::records`), with
//! the recorded inputs `replay --inputs` feeds back to the VM: a line is read or
//! refused with a code and its line number, and what is read writes back to a line
//! that reads as itself (written once, a record is in its canonical form).

use ilmr_trace::{Record, records, to_line};

use crate::engine::{self, Budget, Rng, Stats};
use crate::mutate;

/// Lines of every kind a trace holds, the recorded inputs among them, each a seed on
/// its own after the version line and all together.
const LINES: &[&str] = &[
    r#"{"t":0,"event":"run","task":"t.ilmr","robot":"moro","world":"office","seed":0,"start":{"x":8,"y":5,"h":0}}"#,
    r#"{"t":0.0,"event":"tape","format":1,"ilmrc":"0.1.0","backend":"sim","model":"moro","body":"moro","pose_every":10,"scan_every":1.0,"max_time":600.0,"hold_limit":"inf","paths":[{"name":"P","points":[[0,0],[10,0]]}]}"#,
    r#"{"t":0.0,"event":"input","calls":[{"call":"known_map","map":{"bounds":[0.0,0.0,35.0,37.0],"solids":[{"a":[0.5,0.5],"b":[0.5,18.0],"radius":0.075,"name":"w"}]}},{"call":"actuator_range","id":"arm","range":[0.0,1.0]},{"call":"update","t":0.0},{"call":"snapshot","snapshot":{"t":0.0,"pose":{"x":8.0,"y":5.0,"h":8.959822065514375e-6},"true_pose":{"x":8.0,"y":5.0,"h":0.0},"speed":0.0,"curvature":0.0,"scan":{"device":"scanner","t":0.0,"angle_min":-1.5707963267948966,"angle_step":0.008726646259971648,"ranges":[1.07,"inf",30.0]},"battery":25.6,"devices":[{"name":"gyro","value":0.0005133599895421614},{"name":"horn"}],"detections":[{"sensor":"camera","object":"ball","x":1.0,"y":2.0,"h":0.5,"side":"left"}],"odometry_t":0.0}},{"call":"set_motion","speed":0.005,"curvature":-0.000023373908677313283,"error":{"kind":"refused","message":"too fast"}},{"call":"start","op":{"manipulate":"take"},"id":3},{"call":"poll","id":3,"status":{"failed":"dropped"}},{"call":"cancel","id":9,"error":{"kind":"unknown_op","id":9}},{"call":"bodypose","roll":1.5},{"call":"locate","pose":{"x":1,"y":2,"h":"nan"}},{"call":"locmode","mode":"gps"},{"call":"actuator","id":"arm","value":1.0}],"robot":{"at_rest":false,"true_pose":{"x":8.000025,"y":4.999999999999993,"h":-5.836441805196392e-10},"motion":[0.005,-0.000023373908677313283],"contacts":1,"scan":{"t":0.0,"origin":{"x":8.85,"y":5.0,"h":0.0},"angle_min":-1.57,"angle_step":0.0087,"max_range":30.0}}}"#,
    r#"{"t":0,"event":"issue","line":3,"text":"speed(0.4)","count":2}"#,
    r#"{"t":0,"event":"path","line":4,"text":"goahead(1.2)","points":[[8,5],[9.2,5]]}"#,
    r#"{"t":0.01,"event":"var","line":5,"text":"x=1e999","var":"x","status":1,"value":"inf","dist":"nan","how":"completed"}"#,
    r#"{"t":0.1,"event":"pose","x":8,"y":5,"h":0,"v":0.3,"c":0,"source":"true"}"#,
    r#"{"t":1,"event":"scan","x":8.85,"y":5,"h":0,"hits":[[8.85,4.07],[8.86,4.1]]}"#,
    r#"{"t":1,"event":"line","text":"goahead(1)","accepted":false,"codes":["E0407"]}"#,
    r#"{"t":2,"event":"end","line":4,"text":"goahead(1.2)","how":"broken","linked":true,"code":"R0101"}"#,
    r#"{"t":3,"event":"fault","fault":"obstacle_near","code":"R0206","reaction":"hold","message":"m","help":"h"}"#,
    r#"{"t":9,"event":"truncated","limit":4096,"message":"full"}"#,
];

const VERSION: &str = r#"{"t":0,"event":"trace","version":1}"#;

pub fn seeds() -> Vec<Vec<u8>> {
    let mut seeds: Vec<Vec<u8>> = LINES
        .iter()
        .map(|l| format!("{VERSION}\n{l}\n").into_bytes())
        .collect();
    seeds.push(format!("{VERSION}\n{}\n", LINES.join("\n")).into_bytes());
    seeds.push(b"{\"t\":0.01,\"event\":\"issue\",\"line\":3,\"text\":\"x=1\"}\n".to_vec());
    seeds
}

pub fn fuzz(budget: Budget) -> Stats {
    engine::run("trace", &seeds(), budget, mutation, feed)
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/trace.rs`).
pub fn feed(input: &[u8]) {
    // Readers take text (`ilmr_files::read_text` refuses other bytes with its place).
    let Ok(text) = std::str::from_utf8(input) else {
        return;
    };
    for (i, read) in records(text).enumerate() {
        match read {
            Ok(record) => canonical(&record),
            Err(e) => {
                assert!(e.line >= 1, "an error names its line: {e}");
                assert!(!e.message.is_empty(), "an error says why: {e:?}");
                assert!(
                    e.line > i,
                    "line {} reported for the record at index {i}",
                    e.line
                );
            }
        }
    }
}

/// A record written, read and written again gives the same line: the writer's form
/// (four decimals, exact inputs) is a fixed point.
fn canonical(record: &Record<'_>) {
    let once = to_line(record);
    assert!(!once.contains('\n'), "a record is one line: {once}");
    let text = format!("{VERSION}\n{once}\n");
    let again: Vec<Record<'_>> = match records(&text).collect::<Result<_, _>>() {
        Ok(r) => r,
        Err(e) => panic!("a written record does not read back ({e}): {once}"),
    };
    let twice = to_line(&again[again.len() - 1]);
    assert_eq!(once, twice, "written again, a record changed");
}

fn mutation(base: &[u8], rng: &mut Rng) -> Vec<u8> {
    match rng.below(5) {
        0 => mutate::bytes(base.to_vec(), rng),
        1 => {
            // One line of the trace mutated as JSON, the rest kept: the mutant gets
            // past the version line.
            let text = String::from_utf8_lossy(base);
            let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
            if lines.is_empty() {
                return base.to_vec();
            }
            let i = rng.below(lines.len());
            lines[i] = String::from_utf8_lossy(&mutate::json(lines[i].as_bytes(), rng)).into();
            lines.join("\n").into_bytes()
        }
        2 => {
            // Lines of other seeds spliced in.
            let mut out = base.to_vec();
            if let Some(line) = rng.pick(LINES) {
                out.extend_from_slice(line.as_bytes());
                out.push(b'\n');
            }
            out
        }
        _ => mutate::json(base, rng),
    }
}
