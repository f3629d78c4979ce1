//! The checker's resolution of each name, looked up by the name's span. The lowering
//! asks in nearly source order, so the resolutions are sorted once (a stable sort of
//! what the checker recorded in nearly that order costs about one pass) and each
//! lookup gallops on from the last: the accesses stay sequential where a hash table's
//! would each miss the cache on a large task (a third of lowering 100,000 blocks).

use std::borrow::Cow;
use std::cell::Cell;

use crate::check::Resolved;
use crate::span::Span;

pub struct Refs<'a> {
    sorted: Cow<'a, [(Span, Resolved)]>,
    /// Where the last lookup ended.
    cursor: Cell<usize>,
}

impl<'a> Refs<'a> {
    pub fn new(refs: &'a [(Span, Resolved)]) -> Refs<'a> {
        let sorted = if refs.is_sorted_by_key(|&(span, _)| span) {
            Cow::Borrowed(refs)
        } else {
            let mut sorted = refs.to_vec();
            nearly_sorted(&mut sorted);
            Cow::Owned(sorted)
        };
        Refs {
            sorted,
            cursor: Cell::new(0),
        }
    }

    /// The last resolution recorded for `span` (a name is resolved once per role).
    pub fn get(&self, span: Span) -> Option<Resolved> {
        let v = &self.sorted;
        let at = self.cursor.get().min(v.len());
        let after = |i: usize| v[i].0 > span;
        // The first entry past `span`, searched from the cursor outwards.
        let end = if at > 0 && after(at - 1) {
            v[..at].partition_point(|e| e.0 <= span)
        } else {
            let (mut lo, mut step) = (at, 1);
            while lo + step <= v.len() && !after(lo + step - 1) {
                lo += step;
                step *= 2;
            }
            let hi = (lo + step).min(v.len());
            lo + v[lo..hi].partition_point(|e| e.0 <= span)
        };
        self.cursor.set(end);
        let (found, resolved) = *v.get(end.checked_sub(1)?)?;
        (found == span).then_some(resolved)
    }
}

/// Sorts by span, stably (of several resolutions of one span, the last recorded stays
/// last). The checker records a statement's names nearly in order (an assignment's
/// value before its target), so an insertion sort does it in about one pass; past a
/// few moves per entry the disorder is not local, and the library's sort finishes.
fn nearly_sorted(v: &mut [(Span, Resolved)]) {
    let budget = 8 * v.len();
    let mut moves = 0;
    for i in 1..v.len() {
        let mut j = i;
        while j > 0 && v[j - 1].0 > v[j].0 {
            v.swap(j - 1, j);
            j -= 1;
            moves += 1;
        }
        if moves > budget {
            v.sort_by_key(|&(span, _)| span);
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::VarId;

    fn span(start: u32) -> Span {
        Span {
            start,
            end: start + 1,
        }
    }

    /// Against a map of the last resolution of each span, asked in order, out of
    /// order, and for spans that have none.
    #[test]
    fn finds_what_a_map_of_the_last_resolution_finds() {
        let mut recorded = Vec::new();
        for i in 0..500u32 {
            // Recorded nearly in order, some twice with another resolution.
            let s = span(i * 3 + (i % 7));
            recorded.push((s, Resolved::Variable(VarId(i))));
            if i % 11 == 0 {
                recorded.push((s, Resolved::Keyword));
            }
        }
        recorded.swap(10, 40);
        // Far from sorted as well: the insertion sort gives up and the library's
        // finishes, with the same result.
        let mut reversed = recorded.clone();
        reversed.reverse();
        let mut expected = reversed.clone();
        expected.sort_by_key(|&(span, _)| span);
        nearly_sorted(&mut reversed);
        assert_eq!(reversed, expected);
        let map: std::collections::HashMap<Span, Resolved> = recorded.iter().copied().collect();
        let refs = Refs::new(&recorded);
        let mut asks: Vec<u32> = (0..1600).collect();
        asks.extend((0..1600).rev().step_by(7));
        asks.extend([5, 1500, 3, 800, 0, 1599]);
        for start in asks {
            assert_eq!(
                refs.get(span(start)),
                map.get(&span(start)).copied(),
                "{start}"
            );
        }
    }
}
