//! How `break(pattern)` finds the statements it ends (section 4.5.5): a statement
//! whose text contains the pattern's needle, ignoring case. One rule for the checker,
//! the language server and the VM.
//!
//! A program's needles are searched for all at once: one pass over a statement's text
//! finds every needle in it, where trying each pattern on each statement cost patterns
//! x statements (20,000 of each took 18 s to check, 45 s through W0904, and 9.5 s to
//! run). An Aho-Corasick automaton over the lower-cased needles, written out here
//! because the `aho-corasick` crate's construction is quadratic in the number of states
//! when thousands of needles share a prefix (its shuffle of match states).

use std::borrow::Cow;
use std::cell::Cell;

use rustc_hash::FxHashMap;

/// Whether a statement's text contains the needle, ignoring case: both lower-cased, as
/// the VM matches them when the break runs.
pub fn matches(statement: &str, needle: &str) -> bool {
    if needle.is_empty() {
        return false;
    }
    if statement.is_ascii() {
        // A needle with other letters stays other letters lower-cased; an ASCII text
        // holds none.
        return needle.is_ascii()
            && (statement.as_bytes())
                .windows(needle.len())
                .any(|w| w.eq_ignore_ascii_case(needle.as_bytes()));
    }
    statement.to_lowercase().contains(&needle.to_lowercase())
}

const ROOT: u32 = 0;
const NONE: u32 = u32::MAX;

pub struct Needles {
    /// The trie's edges: (state, byte) to state.
    next: FxHashMap<(u32, u8), u32>,
    /// Where a search goes on from each state when the next byte has no edge: the
    /// longest proper suffix of its text that is a state.
    fail: Vec<u32>,
    /// The distinct needle ending at each state, if any.
    ends: Vec<u32>,
    /// The nearest state down the failure chain at which a needle ends.
    shorter: Vec<u32>,
    /// For each needle given, its place among the distinct ones (`None`: empty).
    ids: Vec<Option<u32>>,
    distinct: usize,
    /// Matches the searches may still enumerate, out of `budget`.
    steps: Cell<u64>,
    budget: u64,
}

impl Needles {
    /// An automaton over `needles` whose searches together enumerate at most `budget`
    /// matches (each needle counted once for each place it ends at): past it they say
    /// so, rather than take time and memory without bound.
    pub fn new<'a>(needles: impl IntoIterator<Item = &'a str>, budget: u64) -> Needles {
        let mut n = Needles {
            next: FxHashMap::default(),
            fail: vec![ROOT],
            ends: vec![NONE],
            shorter: vec![NONE],
            ids: Vec::new(),
            distinct: 0,
            steps: Cell::new(budget),
            budget,
        };
        for needle in needles {
            let id = (!needle.is_empty()).then(|| n.insert(&needle.to_lowercase()));
            n.ids.push(id);
        }
        n.link();
        n
    }

    fn insert(&mut self, needle: &str) -> u32 {
        let mut state = ROOT;
        for &b in needle.as_bytes() {
            let len = self.fail.len() as u32;
            state = *self.next.entry((state, b)).or_insert(len);
            if state == len {
                self.fail.push(ROOT);
                self.ends.push(NONE);
                self.shorter.push(NONE);
            }
        }
        let end = &mut self.ends[state as usize];
        if *end == NONE {
            *end = self.distinct as u32;
            self.distinct += 1;
        }
        *end
    }

    /// Failure and output links, breadth first: a state's links depend on those of
    /// states with shorter texts.
    fn link(&mut self) {
        let mut children: Vec<Vec<(u8, u32)>> = vec![Vec::new(); self.fail.len()];
        for (&(from, b), &to) in &self.next {
            children[from as usize].push((b, to));
        }
        let mut queue = std::collections::VecDeque::from([ROOT]);
        while let Some(state) = queue.pop_front() {
            for &(b, child) in &children[state as usize] {
                let fail = if state == ROOT {
                    ROOT
                } else {
                    self.step(self.fail[state as usize], b)
                };
                self.fail[child as usize] = fail;
                self.shorter[child as usize] = if self.ends[fail as usize] != NONE {
                    fail
                } else {
                    self.shorter[fail as usize]
                };
                queue.push_back(child);
            }
        }
    }

    /// The state after reading `b` in `state`.
    fn step(&self, mut state: u32, b: u8) -> u32 {
        loop {
            if let Some(&to) = self.next.get(&(state, b)) {
                return to;
            }
            if state == ROOT {
                return ROOT;
            }
            state = self.fail[state as usize];
        }
    }

    /// Gives the searches the whole budget again: the language server keeps one
    /// automaton per check and searches it again on every request, each of which is
    /// bounded on its own.
    pub fn refill(&self) {
        self.steps.set(self.budget);
    }

    /// The distinct needles, numbered from 0.
    pub fn distinct(&self) -> usize {
        self.distinct
    }

    /// The distinct needle the `i`-th needle given is, unless it was empty.
    pub fn id(&self, i: usize) -> Option<u32> {
        self.ids[i]
    }

    /// Whether `text` contains any needle; `None` past the budget, as for
    /// [`Needles::each_in`].
    pub fn any_in(&self, text: &str) -> Option<bool> {
        let mut any = false;
        self.each_in(text, &mut Vec::new(), |_| any = true)?;
        Some(any)
    }

    /// Calls `f` once for each distinct needle `text` contains, ignoring case as
    /// [`matches`] does, in increasing order; `None`, and no call, when the matches to
    /// enumerate pass what is left of the budget (each needle counts once for each
    /// place it ends at).
    pub fn each_in(&self, text: &str, seen: &mut Vec<u32>, mut f: impl FnMut(u32)) -> Option<()> {
        if self.distinct == 0 {
            return Some(());
        }
        // ASCII letters are lower-cased byte by byte as they are read.
        let text = if text.is_ascii() {
            Cow::Borrowed(text)
        } else {
            Cow::Owned(text.to_lowercase())
        };
        seen.clear();
        let mut steps = self.steps.get();
        let mut state = ROOT;
        for &b in text.as_bytes() {
            state = self.step(state, b.to_ascii_lowercase());
            let mut at = if self.ends[state as usize] != NONE {
                state
            } else {
                self.shorter[state as usize]
            };
            while at != NONE {
                if steps == 0 {
                    self.steps.set(0);
                    return None;
                }
                steps -= 1;
                seen.push(self.ends[at as usize]);
                at = self.shorter[at as usize];
            }
        }
        self.steps.set(steps);
        seen.sort_unstable();
        seen.dedup();
        seen.iter().for_each(|&id| f(id));
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BUDGET: u64 = 1_000_000;

    fn found(needles: &Needles, text: &str) -> Vec<u32> {
        let mut out = Vec::new();
        needles
            .each_in(text, &mut Vec::new(), |id| out.push(id))
            .unwrap();
        out.sort();
        out
    }

    #[test]
    fn finds_what_matching_one_by_one_finds() {
        let needles = [
            "turn(d=",
            "TURN",
            "urn",
            "n(",
            "while(c",
            "a",
            "aa",
            "aaa",
            "",
            "käännös",
            "ÄÄ",
            "turn",
            "x=goahead(1",
            "oa",
        ];
        let texts = [
            "turn(d=90,c=0.5)",
            "Turn(left)",
            "while(cnt<5)",
            "while(claps<2)",
            "aaaa",
            "käännös=turn(left)",
            "KÄÄNNÖS",
            "x=goahead(1)",
            "",
            "nothing here",
        ];
        let set = Needles::new(needles, BUDGET);
        for text in texts {
            let mut expected: Vec<u32> = (needles.iter().enumerate())
                .filter(|(_, n)| matches(text, n))
                .map(|(i, _)| set.id(i).unwrap())
                .collect();
            expected.sort();
            expected.dedup();
            assert_eq!(found(&set, text), expected, "{text}");
            assert_eq!(set.any_in(text), Some(!expected.is_empty()), "{text}");
        }
        // "TURN" and "turn" are one needle; the empty one is none.
        assert_eq!(set.id(1), set.id(11));
        assert_eq!(set.id(8), None);
        assert_eq!(set.distinct(), needles.len() - 2);
    }

    #[test]
    fn thousands_of_needles_with_one_prefix() {
        let needles: Vec<String> = (0..20_000).map(|i| format!("zz{i}")).collect();
        let set = Needles::new(needles.iter().map(String::as_str), BUDGET);
        assert_eq!(set.distinct(), 20_000);
        // "zz123" holds "zz1", "zz12" and "zz123".
        let ids: Vec<u32> = ["zz1", "zz12", "zz123"]
            .iter()
            .map(|n| {
                set.id(needles.iter().position(|m| m == n).unwrap())
                    .unwrap()
            })
            .collect();
        assert_eq!(found(&set, "x=ZZ123"), ids);
    }

    #[test]
    fn a_spent_budget_is_said() {
        let set = Needles::new(["a", "aa"], 3);
        // "aa" ends "a" twice and "aa" once: three matches.
        assert_eq!(set.any_in("aa"), Some(true));
        assert_eq!(set.any_in("a"), None);
        assert_eq!(set.any_in("b"), Some(false));
    }
}
