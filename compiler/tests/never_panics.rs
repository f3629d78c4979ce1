//! The parser, the checker and the formatter never panic, whatever the input: random
//! token soup, random bytes, and mutations of the dissertation's programs.

use ilmr_compiler::check::{Source, analyze};
use ilmr_model::RobotModel;
use proptest::prelude::*;

const PIECES: &[&str] = &[
    "goahead",
    "turn",
    "sensor",
    "speed",
    "if",
    "endif",
    "while",
    "endwhile",
    "check",
    "checkend",
    "break",
    "priority",
    "highest",
    "wait",
    "(",
    ")",
    ",",
    "=",
    "==",
    "=>",
    "<",
    "+",
    "-",
    "*",
    "/",
    ":",
    "d=",
    "c=",
    "left",
    "door",
    "scanner",
    "forever",
    "x",
    "1",
    "0.5",
    "-3",
    "\n",
    "\n\n",
    " ",
    "//c",
    "käännös",
    "$",
    "break(",
    "Takebox",
    "TURN1:",
];

const EXAMPLES: &[&str] = &[
    include_str!("../../examples/fetch_boxes.ilmr"),
    include_str!("../../examples/concurrency.ilmr"),
    include_str!("../../examples/loop.ilmr"),
    include_str!("../../examples/skills/turns.ilms"),
    include_str!("../../tests/check/broken/syntax.ilmr"),
];

fn run(text: &str) {
    let sources = [
        Source::new("fuzz.ilmr", text),
        Source::library("lib.ilms", "TURN1:\nturn(left)\n"),
    ];
    for robot in ["moro", "workpartner"] {
        let model = RobotModel::builtin(robot).unwrap();
        let analysis = analyze(&sources, &model);
        for d in &analysis.diagnostics {
            // Every span lies inside its file, on character boundaries.
            let file = analysis.files[d.file.0 as usize].text;
            assert!(file.get(d.span.range()).is_some(), "{d:?} out of {file:?}");
        }
        let _ = ilmr_compiler::format::format(text, &model);
    }
    let _ = ilmr_compiler::tree::render(
        &ilmr_compiler::parser::parse(text, ilmr_compiler::FileId(0)).file,
    );
}

fn mutate(base: &str, cuts: &[(usize, usize, usize)]) -> String {
    let mut text: Vec<char> = base.chars().collect();
    for &(at, len, piece) in cuts {
        if text.is_empty() {
            break;
        }
        let at = at % text.len();
        let end = (at + len % 8).min(text.len());
        let insert: Vec<char> = PIECES[piece % PIECES.len()].chars().collect();
        text.splice(at..end, insert);
    }
    text.into_iter().collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn token_soup(pieces in proptest::collection::vec(0..PIECES.len(), 0..120)) {
        let text: String = pieces.iter().map(|&i| PIECES[i]).collect();
        run(&text);
    }

    #[test]
    fn arbitrary_text(text in "\\PC{0,300}") {
        run(&text);
    }

    #[test]
    fn mutated_examples(
        which in 0..EXAMPLES.len(),
        cuts in proptest::collection::vec((0usize..10_000, 0usize..8, 0usize..64), 1..12),
    ) {
        run(&mutate(EXAMPLES[which], &cuts));
    }
}
