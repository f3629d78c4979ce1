//! "Did you mean" suggestions.

use std::borrow::Cow;

use crate::limits;

/// The candidate closest to `word` (ignoring case), if it is close enough to be a typo.
/// For short lists fixed by the language or the robot model; a search over names the
/// program brings goes through [`Budget::closest`].
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let mut unlimited = u64::MAX;
    search(word, candidates, &mut unlimited)
}

/// What "did you mean" may still spend in one program, in the steps of
/// [`limits::SUGGESTION_STEPS`]. A search over the program's own names (its variables, its
/// skills) costs as many steps as there are names, so a file that binds hundreds of
/// thousands of names and then misuses a thousand others would otherwise take minutes;
/// once the budget is spent, names get no suggestion.
#[derive(Debug)]
pub struct Budget {
    steps: u64,
}

impl Default for Budget {
    fn default() -> Budget {
        Budget::with_steps(limits::SUGGESTION_STEPS)
    }
}

impl Budget {
    pub fn with_steps(steps: u64) -> Budget {
        Budget { steps }
    }

    /// [`closest`], paid for from the budget: `None` once it is spent, even where a
    /// search would have found one.
    pub fn closest<'a>(
        &mut self,
        word: &str,
        candidates: impl IntoIterator<Item = &'a str>,
    ) -> Option<&'a str> {
        search(word, candidates, &mut self.steps)
    }

    pub fn is_spent(&self) -> bool {
        self.steps == 0
    }
}

fn search<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
    steps: &mut u64,
) -> Option<&'a str> {
    let word = word.to_lowercase();
    let length = word.chars().count();
    // One edit in three characters; names of one or two letters get no guesses, since
    // every other short name would be one edit away.
    let limit = length / 3;
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        let lower = if c.bytes().any(|b| b.is_ascii_uppercase()) || !c.is_ascii() {
            Cow::Owned(c.to_lowercase())
        } else {
            Cow::Borrowed(c)
        };
        // Every edit changes the length by at most one, so a name whose length is further
        // off cannot be close enough, and needs no edit distance.
        let far = lower.chars().count().abs_diff(length) > limit;
        let cost = if far {
            1
        } else {
            limits::SUGGESTION_COMPARISON
        };
        if *steps < cost {
            *steps = 0;
            return None;
        }
        *steps -= cost;
        if far {
            continue;
        }
        let d = strsim::damerau_levenshtein(&word, &lower);
        if d <= limit && best.is_none_or(|(bd, bc)| (d, c.len()) < (bd, bc.len())) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
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

    #[test]
    fn a_spent_budget_suggests_nothing_more() {
        let words = ["left", "right", "middle"];
        let each = limits::SUGGESTION_COMPARISON;
        // "lft" is within one edit of "left" only: the other two are skipped on their
        // length, at a step each.
        let mut budget = Budget::with_steps(each + 2);
        assert_eq!(budget.closest("lft", words), Some("left"));
        assert!(budget.is_spent());
        assert_eq!(budget.closest("lft", words), None);
        // A search that runs out part way finds nothing, not the best so far.
        let mut budget = Budget::with_steps(each);
        assert_eq!(budget.closest("lft", ["left", "lefts"]), None);
    }

    #[test]
    fn skipping_on_length_keeps_the_answer() {
        // The search as it was before names were skipped on their length: an edit
        // distance for every candidate.
        fn every_distance<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
            let word = word.to_lowercase();
            let limit = word.chars().count() / 3;
            (candidates.iter())
                .map(|c| (strsim::damerau_levenshtein(&word, &c.to_lowercase()), *c))
                .filter(|&(d, _)| d <= limit)
                .min_by_key(|&(d, c)| (d, c.len()))
                .map(|(_, c)| c)
        }
        let words = [
            "middle", "midle", "MIDDLE", "riddle", "mid", "mİddle", "middles", "iddle", "dimple",
            "speed", "spede", "sped", "speeds", "goahead", "go_ahead", "İ",
        ];
        for word in words
            .iter()
            .chain(&["middel", "midl", "MİDDLE", "spee", "goaheda", "x"])
        {
            assert_eq!(closest(word, words), every_distance(word, &words), "{word}");
        }
        assert_eq!(closest("midl", words), Some("mid"));
        assert_eq!(closest("MİDDLE", ["mİddle", "middle"]), Some("mİddle"));
    }
}
