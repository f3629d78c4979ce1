//! Seed corpora and AFL++ dictionaries, generated from what the seeded loop starts
//! from: the repository's files, generated tasks, built modules, the catalogue's and
//! the models' words, and every regression input.

use std::io;
use std::path::Path;

use crate::engine;
use crate::mutate;
use crate::targets::{corpus, fleets, modules, requests, scenarios, testfiles, traces, worlds};

/// One target: its name (the binary's, and its directory under
/// `tests/fuzz/regressions/`), its seeds and its dictionary's tokens.
pub struct Seeds {
    pub name: &'static str,
    pub corpus: Vec<Vec<u8>>,
    pub dictionary: Vec<Vec<u8>>,
}

pub fn all() -> Vec<Seeds> {
    let ilmr = as_bytes(mutate::ilmr_dictionary());
    vec![
        Seeds {
            name: "task",
            corpus: corpus::tasks().to_vec(),
            dictionary: ilmr.clone(),
        },
        Seeds {
            name: "skills",
            corpus: corpus::skill_files(),
            dictionary: ilmr,
        },
        Seeds {
            name: "model",
            corpus: corpus::ini_files(),
            dictionary: as_bytes(mutate::ini_dictionary()),
        },
        Seeds {
            name: "world",
            corpus: worlds::seeds(),
            dictionary: as_bytes(worlds::dictionary()),
        },
        Seeds {
            name: "module",
            corpus: modules::modules(),
            dictionary: vec![
                ilmr_vm::bytecode::file::MAGIC.to_vec(),
                ilmr_vm::bytecode::VERSION.to_le_bytes().to_vec(),
            ],
        },
        Seeds {
            name: "request",
            corpus: requests::seeds(),
            dictionary: request_words(),
        },
        Seeds {
            name: "trace",
            corpus: traces::seeds(),
            dictionary: json_words(traces::seeds()),
        },
        Seeds {
            name: "testfile",
            corpus: testfiles::seeds(),
            dictionary: as_bytes(testfiles::dictionary()),
        },
        Seeds {
            name: "scenario",
            corpus: scenarios::seeds(),
            dictionary: as_bytes(scenarios::dictionary()),
        },
        Seeds {
            name: "fleet",
            corpus: fleets::seeds(),
            dictionary: as_bytes(fleets::dictionary()),
        },
    ]
}

/// Writes `dir/NAME/` (the corpus and the regression inputs, one file each) and
/// `dir/NAME.dict` for every target.
pub fn write(dir: &Path) -> io::Result<()> {
    for seeds in all() {
        let out = dir.join(seeds.name);
        std::fs::create_dir_all(&out)?;
        let regressions = engine::regression_inputs(seeds.name)
            .into_iter()
            .map(|(_, bytes)| bytes);
        let mut inputs: Vec<Vec<u8>> = seeds.corpus.into_iter().chain(regressions).collect();
        inputs.sort();
        inputs.dedup();
        for (i, input) in inputs.iter().enumerate() {
            std::fs::write(out.join(format!("{i:05}")), input)?;
        }
        let dictionary: String = seeds
            .dictionary
            .iter()
            .filter(|w| !w.is_empty() && w.len() <= MAX_TOKEN)
            .enumerate()
            .map(|(i, w)| format!("w{i}=\"{}\"\n", escape(w)))
            .collect();
        std::fs::write(dir.join(format!("{}.dict", seeds.name)), dictionary)?;
        eprintln!(
            "seeds {}: {} inputs, {} dictionary words",
            seeds.name,
            inputs.len(),
            seeds.dictionary.len()
        );
    }
    Ok(())
}

/// AFL++ reads dictionary tokens of at most 128 bytes (`MAX_DICT_FILE`).
const MAX_TOKEN: usize = 128;

fn as_bytes(words: Vec<String>) -> Vec<Vec<u8>> {
    words.into_iter().map(String::into_bytes).collect()
}

/// The request seeds' keys and JSON's own words.
fn request_words() -> Vec<Vec<u8>> {
    json_words(requests::seeds())
}

/// The keys of the JSON in `seeds` (one document, or one a line) and JSON's own words.
fn json_words(seeds: Vec<Vec<u8>>) -> Vec<Vec<u8>> {
    fn keys(value: &serde_json::Value, out: &mut Vec<String>) {
        match value {
            serde_json::Value::Object(map) => {
                for (k, v) in map {
                    out.push(format!("\"{k}\":"));
                    keys(v, out);
                }
            }
            serde_json::Value::Array(items) => items.iter().for_each(|v| keys(v, out)),
            _ => {}
        }
    }
    let mut words = Vec::new();
    for seed in seeds {
        for doc in std::iter::once(&seed[..]).chain(seed.split(|&b| b == b'\n')) {
            if let Ok(value) = serde_json::from_slice(doc) {
                keys(&value, &mut words);
            }
        }
    }
    words.extend(
        [
            "{", "}", "[", "]", ",", "\"", "\\u0000", "\\n", "true", "false", "null",
        ]
        .iter()
        .map(|w| w.to_string()),
    );
    words.extend(mutate::NUMBERS.iter().map(|w| w.to_string()));
    words.sort();
    words.dedup();
    as_bytes(words)
}

/// A token in the dictionary's quoting: printable ASCII as is, but for `"` and `\`,
/// everything else as `\xNN`. afl-fuzz refuses a dictionary with a malformed line, so
/// every run of `tools/fuzz.sh` checks this.
pub fn escape(word: &[u8]) -> String {
    word.iter()
        .map(|&b| match b {
            b'"' | b'\\' => format!("\\{}", b as char),
            0x20..=0x7e => (b as char).to_string(),
            _ => format!("\\x{b:02x}"),
        })
        .collect()
}
