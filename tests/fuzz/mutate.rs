//! Mutators. Text mutators know lines, tokens, numbers and blocks, so that most
//! inputs stay close enough to ILMR (or ROBO.INI, or a JSON request) to reach the
//! checker, the lowering and the VM rather than dying in the lexer; byte mutators
//! cover what is not text at all. Every mutator keeps inputs under [`MAX_LEN`].

use serde_json::Value;

use super::engine::Rng;

/// Inputs grow no larger than this: big enough for deep nesting and long lines,
/// small enough to keep an iteration in the millisecond range.
pub const MAX_LEN: usize = 16 * 1024;

/// Numbers a range check, a parser or a table index is likely to get wrong.
pub const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "1",
    "-1",
    "0.5",
    "-0.4",
    "2",
    "3",
    "5",
    "90",
    "-90",
    "180",
    "-180",
    "360",
    "361",
    "-360.0001",
    "1e308",
    "1e309",
    "-1e400",
    "1e-320",
    "NaN",
    "inf",
    "-inf",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "99999999999999999999999999",
    "0.000000000000000000001",
    "00000000000000000000001",
    "1.",
    ".5",
    "1.2.3",
    "--1",
    "+1",
    "1e",
    "0x10",
];

/// Text that the lexer, parser or checker treats specially.
pub const PUNCTUATION: &[&str] = &[
    "(",
    ")",
    ",",
    "=",
    "==",
    "=>",
    ">=",
    "<=",
    "!=",
    "<",
    ">",
    "+",
    "-",
    "*",
    "/",
    ":",
    "//",
    "\n",
    "\n\n",
    "\r\n",
    "\r",
    "\t",
    " ",
    "\u{0}",
    "\u{feff}",
    "\u{202e}",
    "ä",
    "ö",
    "käännös",
    "😀",
    "\\",
    "\"",
    "'",
    ";",
    "[",
    "]",
    "#",
    "$",
    "_",
    "__",
    "d=",
    "c=",
    "r=",
    "p=",
    "rc=",
    "break(",
    "if(",
    "while(",
    "endif",
    "endwhile",
    "check",
    "checkend",
    "priority = highest",
];

/// Dictionary tokens for ILMR text: every command and keyword of the catalogue, the
/// reserved words, names from both shipped models, skill names, operators, numbers.
pub fn ilmr_dictionary() -> Vec<String> {
    let mut words: Vec<String> = ilmr_stdlib::Command::all()
        .map(|c| c.name().to_string())
        .collect();
    words.extend(ilmr_stdlib::all_keywords().iter().map(|w| w.to_string()));
    words.extend(ilmr_stdlib::RESERVED.iter().map(|w| w.to_string()));
    for robot in ["moro", "workpartner"] {
        if let Some(model) = ilmr_model::RobotModel::builtin(robot) {
            words.extend(model.names().map(|(n, _)| n.to_string()));
        }
    }
    words.extend(
        [
            "Takebox",
            "TURN1",
            "TURN2",
            "TURN1:",
            "Takebox:",
            "go_charger",
            "turn_around",
        ]
        .iter()
        .map(|w| w.to_string()),
    );
    words.extend(NUMBERS.iter().map(|w| w.to_string()));
    words.extend(PUNCTUATION.iter().map(|w| w.to_string()));
    words.sort();
    words.dedup();
    words
}

/// Dictionary tokens for ROBO.INI text: section tags, parameter names, device lines.
pub fn ini_dictionary() -> Vec<String> {
    let mut words: Vec<String> = [
        "[SENSORSANDACTUATORS]",
        "[OBJECTS]",
        "[COLORS]",
        "[IDENTIFIERS]",
        "[PARAMETERS]",
        "[END]",
        "[",
        "]",
        ";",
        "=",
        "scanner 1 0 30000 361",
        "scanner 1 0 30000 0",
        "scanner 1 0 30000 4294967296",
        "scanner 1 30000 0 361",
        "gyro 0 -180 180 1",
        "horn 10 0 1 1",
        "door 0.8 1.2",
        "door 1.2 0.8",
        "user yellow 30",
        "yellow 18",
        "navi 7",
        "wheels 5",
    ]
    .iter()
    .map(|w| w.to_string())
    .collect();
    words.extend(
        ilmr_model::PARAMETER_SPECS
            .iter()
            .map(|p| p.name.to_string()),
    );
    with_numbers_and_spacing(words)
}

/// Line breaks, blanks and characters no format here gives a meaning to, for every
/// dictionary of a line-based text format.
pub const SPACING: &[&str] = &["\n", " ", "\t", "\r\n", "ä", "\u{0}"];

/// A text format's own `words`, then [`NUMBERS`] and [`SPACING`]: what every reader of
/// text must take.
pub fn with_numbers_and_spacing(mut words: Vec<String>) -> Vec<String> {
    words.extend(NUMBERS.iter().chain(SPACING).map(|w| w.to_string()));
    words
}

/// A havoc round: one to four mutations of `base`, chosen at random, with material
/// spliced from `corpus` and tokens from `dictionary`.
pub fn text(base: &[u8], rng: &mut Rng, corpus: &[Vec<u8>], dictionary: &[String]) -> Vec<u8> {
    let mut text = String::from_utf8_lossy(base).into_owned();
    let rounds = 1 + rng.below(4);
    for _ in 0..rounds {
        text = match rng.below(13) {
            0 => delete_line(&text, rng),
            1 => duplicate_line(&text, rng),
            2 => swap_lines(&text, rng),
            3 => splice_line(&text, rng, corpus),
            4 | 5 => replace_token(&text, rng, dictionary),
            6 => insert_token(&text, rng, dictionary),
            7 => replace_number(&text, rng),
            8 => wrap_block(&text, rng),
            9 => nest_deeply(&text, rng),
            10 => delete_range(&text, rng),
            11 => insert_blank_line(&text, rng),
            _ => {
                return truncate(bytes(text.into_bytes(), rng));
            }
        };
    }
    truncate(text.into_bytes())
}

fn truncate(mut bytes: Vec<u8>) -> Vec<u8> {
    bytes.truncate(MAX_LEN);
    bytes
}

fn lines(text: &str) -> Vec<&str> {
    text.split('\n').collect()
}

fn delete_line(text: &str, rng: &mut Rng) -> String {
    let mut l = lines(text);
    if !l.is_empty() {
        l.remove(rng.below(l.len()));
    }
    l.join("\n")
}

fn duplicate_line(text: &str, rng: &mut Rng) -> String {
    let mut l = lines(text);
    if let Some(&line) = rng.pick(&l) {
        let at = rng.below(l.len() + 1);
        // Sometimes many times: long programs, many blocks, many variables.
        let times = if rng.chance(10) {
            1 + rng.below(200)
        } else {
            1
        };
        for _ in 0..times {
            l.insert(at, line);
        }
    }
    l.join("\n")
}

fn swap_lines(text: &str, rng: &mut Rng) -> String {
    let mut l = lines(text);
    if !l.is_empty() {
        let (a, b) = (rng.below(l.len()), rng.below(l.len()));
        l.swap(a, b);
    }
    l.join("\n")
}

fn splice_line(text: &str, rng: &mut Rng, corpus: &[Vec<u8>]) -> String {
    let Some(other) = rng.pick(corpus) else {
        return text.to_string();
    };
    let other = String::from_utf8_lossy(other);
    let donor = lines(&other);
    let mut l = lines(text);
    let count = 1 + rng.below(6);
    let from = rng.below(donor.len());
    let at = rng.below(l.len() + 1);
    for (k, line) in donor.iter().skip(from).take(count).enumerate() {
        l.insert(at + k, line);
    }
    l.join("\n")
}

/// Byte ranges of the words and numbers in `text` (runs of alphanumerics, `_`, `.`).
fn tokens(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices() {
        let word = c.is_alphanumeric() || c == '_' || c == '.';
        match (word, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, text.len()));
    }
    out
}

fn replace_token(text: &str, rng: &mut Rng, dictionary: &[String]) -> String {
    let toks = tokens(text);
    match (rng.pick(&toks), rng.pick(dictionary)) {
        (Some(&(s, e)), Some(word)) => format!("{}{}{}", &text[..s], word, &text[e..]),
        _ => text.to_string(),
    }
}

fn insert_token(text: &str, rng: &mut Rng, dictionary: &[String]) -> String {
    let Some(word) = rng.pick(dictionary) else {
        return text.to_string();
    };
    let at = char_boundary(text, rng.below(text.len() + 1));
    format!("{}{}{}", &text[..at], word, &text[at..])
}

fn replace_number(text: &str, rng: &mut Rng) -> String {
    let numbers: Vec<(usize, usize)> = tokens(text)
        .into_iter()
        .filter(|&(s, _)| text[s..].starts_with(|c: char| c.is_ascii_digit()))
        .collect();
    let replacement = rng.pick(NUMBERS).copied().unwrap_or("0");
    match rng.pick(&numbers) {
        Some(&(s, e)) => format!("{}{}{}", &text[..s], replacement, &text[e..]),
        None => text.to_string(),
    }
}

/// Puts a run of lines inside `if`/`while`/`check`, sometimes without its closer.
fn wrap_block(text: &str, rng: &mut Rng) -> String {
    let mut l: Vec<String> = lines(text).into_iter().map(str::to_string).collect();
    let (open, close) = *rng
        .pick(&[
            ("if(1)", "endif"),
            ("while(x<3)", "endwhile"),
            ("check", "checkend"),
            ("w = while(0)", "endwhile"),
            ("if(door)", "endif"),
        ])
        .unwrap_or(&("if(1)", "endif"));
    let start = rng.below(l.len() + 1);
    let end = (start + rng.below(8)).min(l.len());
    if !rng.chance(15) {
        l.insert(end, close.to_string());
    }
    l.insert(start, open.to_string());
    l.join("\n")
}

/// Deep nesting: what recursion in a parser or a checker would trip over.
fn nest_deeply(text: &str, rng: &mut Rng) -> String {
    let depth = 1 + rng.below(120);
    let mut out = String::new();
    match rng.below(3) {
        0 => {
            out.push_str(&"if(1)\n".repeat(depth));
            out.push_str(text);
            out.push('\n');
            out.push_str(&"endif\n".repeat(depth));
        }
        1 => {
            out.push_str("x = ");
            out.push_str(&"(".repeat(depth));
            out.push('1');
            out.push_str(&")".repeat(depth));
            out.push('\n');
            out.push_str(text);
        }
        _ => {
            out.push_str("speed(");
            out.push_str(&"-".repeat(depth));
            out.push_str("0.1)\n");
            out.push_str(text);
        }
    }
    out
}

fn delete_range(text: &str, rng: &mut Rng) -> String {
    if text.is_empty() {
        return String::new();
    }
    let a = char_boundary(text, rng.below(text.len()));
    let b = char_boundary(text, (a + 1 + rng.below(24)).min(text.len()));
    format!("{}{}", &text[..a], &text[b..])
}

fn insert_blank_line(text: &str, rng: &mut Rng) -> String {
    let mut l = lines(text);
    let at = rng.below(l.len() + 1);
    l.insert(at, "");
    l.join("\n")
}

fn char_boundary(text: &str, mut at: usize) -> usize {
    while at > 0 && !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// Byte-level havoc: flips, random bytes, cuts. May leave UTF-8 behind on purpose.
pub fn bytes(mut data: Vec<u8>, rng: &mut Rng) -> Vec<u8> {
    let rounds = 1 + rng.below(8);
    for _ in 0..rounds {
        let len = data.len();
        match rng.below(5) {
            0 if len > 0 => {
                let i = rng.below(len);
                data[i] ^= 1 << rng.below(8);
            }
            1 if len > 0 => {
                let i = rng.below(len);
                data[i] = rng.next_u64() as u8;
            }
            2 => {
                let i = rng.below(len + 1);
                data.insert(i, rng.next_u64() as u8);
            }
            3 if len > 0 => {
                data.truncate(rng.below(len));
            }
            _ if len > 1 => {
                let a = rng.below(len);
                let b = (a + 1 + rng.below(16)).min(len);
                data.drain(a..b);
            }
            _ => data.push(b'\n'),
        }
    }
    truncate(data)
}

/// Strings a JSON mutation puts where a string was: the names serde matches on.
const JSON_STRINGS: &[&str] = &[
    "ILMB",
    "ILMR",
    "",
    "issue",
    "assign",
    "copy",
    "wait_time",
    "wait_var",
    "if",
    "while",
    "call",
    "break",
    "break_all",
    "stop",
    "cont",
    "priority",
    "clear",
    "num",
    "word",
    "setting",
    "var",
    "const",
    "field",
    "add",
    "div",
    "pos_eq",
    "status",
    "number",
    "reading",
    "position",
    "movement",
    "dist",
    "value",
    "x",
    "h",
    "goahead",
    "turn",
    "sensor",
    "gotoxy",
    "speed",
    "bodypose",
    "init",
    "wait",
    "manipulate",
    "actuator",
    "createpath",
    "record",
    "followpath",
    "ilmr",
    "subscribe",
    "events",
    "id",
];

/// A structure-aware mutation of a JSON document: a number, string, array or object
/// somewhere in it changes, so that the result still parses and reaches validation.
/// Text that is not JSON gets byte havoc instead.
pub fn json(base: &[u8], rng: &mut Rng) -> Vec<u8> {
    let Ok(mut value) = serde_json::from_slice::<Value>(base) else {
        return bytes(base.to_vec(), rng);
    };
    let rounds = 1 + rng.below(3);
    for _ in 0..rounds {
        let count = count_nodes(&value);
        let target = rng.below(count);
        let mut seen = 0;
        mutate_node(&mut value, target, &mut seen, rng);
    }
    let out = serde_json::to_vec(&value).unwrap_or_default();
    if rng.chance(5) {
        bytes(out, rng)
    } else {
        truncate_json(out)
    }
}

fn truncate_json(out: Vec<u8>) -> Vec<u8> {
    // Modules are larger than text inputs; keep them whole unless they explode.
    if out.len() > 16 * MAX_LEN {
        out[..16 * MAX_LEN].to_vec()
    } else {
        out
    }
}

fn count_nodes(v: &Value) -> usize {
    1 + match v {
        Value::Array(a) => a.iter().map(count_nodes).sum(),
        Value::Object(o) => o.values().map(count_nodes).sum(),
        _ => 0,
    }
}

fn mutate_node(v: &mut Value, target: usize, seen: &mut usize, rng: &mut Rng) -> bool {
    if *seen == target {
        replace_value(v, rng);
        return true;
    }
    *seen += 1;
    match v {
        Value::Array(a) => a.iter_mut().any(|x| mutate_node(x, target, seen, rng)),
        Value::Object(o) => o.values_mut().any(|x| mutate_node(x, target, seen, rng)),
        _ => false,
    }
}

fn replace_value(v: &mut Value, rng: &mut Rng) {
    let interesting_number = |rng: &mut Rng, near: i64| -> Value {
        match rng.below(9) {
            0 => Value::from(0),
            1 => Value::from(near + 1),
            2 => Value::from(near - 1),
            3 => Value::from(u32::MAX),
            4 => Value::from(u64::from(u32::MAX) + 1),
            5 => Value::from(-1),
            6 => Value::from(1.5),
            7 => Value::from(1e300),
            _ => Value::from(rng.below(64) as i64),
        }
    };
    match v {
        Value::Number(n) => {
            let near = n.as_i64().unwrap_or(0);
            *v = interesting_number(rng, near);
        }
        Value::String(_) => {
            *v = if rng.chance(80) {
                Value::from(*rng.pick(JSON_STRINGS).unwrap_or(&""))
            } else {
                Value::from(interesting_number(rng, 0).to_string())
            };
        }
        Value::Array(a) => match rng.below(5) {
            0 if !a.is_empty() => {
                let i = rng.below(a.len());
                a.remove(i);
            }
            1 if !a.is_empty() => {
                let i = rng.below(a.len());
                let copy = a[i].clone();
                a.insert(rng.below(a.len() + 1), copy);
            }
            2 if a.len() > 1 => {
                let (i, j) = (rng.below(a.len()), rng.below(a.len()));
                a.swap(i, j);
            }
            3 => a.clear(),
            _ => a.push(interesting_number(rng, 0)),
        },
        Value::Object(o) => {
            let keys: Vec<String> = o.keys().cloned().collect();
            match rng.below(3) {
                0 if !keys.is_empty() => {
                    if let Some(k) = rng.pick(&keys) {
                        o.remove(k);
                    }
                }
                1 => {
                    let key = rng.pick(JSON_STRINGS).copied().unwrap_or("x");
                    o.insert(key.to_string(), interesting_number(rng, 0));
                }
                _ => {
                    if let Some(k) = rng.pick(&keys) {
                        o.insert(k.clone(), Value::Null);
                    }
                }
            }
        }
        Value::Bool(b) => *b = !*b,
        Value::Null => *v = Value::from(true),
    }
}
