//! "Did you mean" suggestions.

/// The candidate closest to `word` (ignoring case), if it is close enough to be a typo.
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let word = word.to_lowercase();
    // One edit in three characters; names of one or two letters get no guesses, since
    // every other short name would be one edit away.
    let limit = word.chars().count() / 3;
    candidates
        .into_iter()
        .map(|c| (strsim::damerau_levenshtein(&word, &c.to_lowercase()), c))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, c)| (d, c.len()))
        .map(|(_, c)| c)
}

/// Up to `n` candidates, the nearest to `word` (ignoring case) first.
pub fn nearest<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
    n: usize,
) -> Vec<&'a str> {
    let word = word.to_lowercase();
    let mut ranked: Vec<(usize, &str)> = candidates
        .into_iter()
        .map(|c| (strsim::damerau_levenshtein(&word, &c.to_lowercase()), c))
        .collect();
    ranked.sort_unstable();
    ranked.dedup();
    ranked.into_iter().take(n).map(|(_, c)| c).collect()
}

/// "one of `a`, `b` or `c`".
pub fn one_of(words: &[&str]) -> String {
    match words {
        [] => String::from("nothing"),
        [one] => format!("`{one}`"),
        [init @ .., last] => {
            let init: Vec<String> = init.iter().map(|w| format!("`{w}`")).collect();
            format!("one of {} or `{last}`", init.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_typos_but_not_strangers() {
        let words = ["left", "right", "middle"];
        assert_eq!(closest("lft", words), Some("left"));
        assert_eq!(closest("MIDDEL", words), Some("middle"));
        assert_eq!(closest("forward", words), None);
        let near = nearest("rigid", words, 2);
        assert_eq!((near.len(), near[0]), (2, "right"));
    }
}
