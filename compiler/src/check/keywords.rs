//! Which commands take a word as a keyword. `CommandSpec::has_keyword` walks every
//! parameter of every form, and the argument matcher asks it for nearly every name an
//! argument list holds, so the answer is indexed once per process.

use std::sync::OnceLock;

use ilmr_stdlib::{Command, CommandSpec, ParamKind};

use crate::check::fold::FoldMap;

/// Lower-cased keyword to the set of commands (bit `command as u8`) that take it.
type Index = FoldMap<u64>;

/// Exactly `spec.has_keyword(word)`.
pub fn is_keyword(spec: &CommandSpec, word: &str) -> bool {
    let bit = spec.command as usize;
    if !word.is_ascii() || bit >= 64 {
        return spec.has_keyword(word);
    }
    index()
        .get(word)
        .is_some_and(|commands| commands & (1u64 << bit) != 0)
}

fn index() -> &'static Index {
    static INDEX: OnceLock<Index> = OnceLock::new();
    INDEX.get_or_init(|| {
        let mut index = Index::default();
        for command in Command::all() {
            let bit = command as usize;
            if bit >= 64 {
                continue;
            }
            let params = command.spec().forms.iter().flat_map(|f| f.params);
            for param in params {
                add(&mut index, &param.kind, bit);
            }
        }
        index
    })
}

/// The words `has_keyword` compares, by its own walk. `eq_ignore_ascii_case` never
/// matches an ASCII word with a non-ASCII one, and only ASCII words are looked up here,
/// so only ASCII keywords are indexed.
fn add(index: &mut Index, kind: &ParamKind, bit: usize) {
    match *kind {
        ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => {
            for word in words.iter().filter(|w| w.is_ascii()) {
                *index.get_or_insert_with(&word.to_ascii_lowercase(), || 0) |= 1u64 << bit;
            }
        }
        ParamKind::OneOf { kinds } => {
            for kind in kinds {
                add(index, kind, bit);
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_index_answers_what_the_catalogue_answers() {
        let mut words: Vec<String> = vec![
            "cnt".into(),
            "".into(),
            "käännös".into(),
            "x".repeat(40),
            "scanner".into(),
            "door".into(),
        ];
        for command in Command::all() {
            words.push(command.name().to_uppercase());
            for form in command.spec().forms {
                for param in form.params {
                    let mut kinds = vec![&param.kind];
                    while let Some(kind) = kinds.pop() {
                        match kind {
                            ParamKind::Keyword { words: w } | ParamKind::Mode { words: w, .. } => {
                                for word in *w {
                                    words.push(word.to_string());
                                    words.push(word.to_uppercase());
                                    words.push(format!("{word}s"));
                                }
                            }
                            ParamKind::OneOf { kinds: k } => kinds.extend(k.iter()),
                            _ => {}
                        }
                    }
                }
            }
        }
        assert!(words.iter().any(|w| w == "FOREVER"));
        for command in Command::all() {
            let spec = command.spec();
            for word in &words {
                assert_eq!(
                    is_keyword(spec, word),
                    spec.has_keyword(word),
                    "{} {word:?}",
                    spec.name
                );
            }
        }
    }
}
