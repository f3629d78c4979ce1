//! Tables of names that ignore ASCII letter case without lower-casing a copy of the
//! name looked up. Every name in a program is looked up several times (a variable, a
//! command, a skill, a constant, a keyword?); copying and lower-casing it into a buffer
//! before hashing cost more than the lookups themselves.
//!
//! A table stores each key already lower-cased, by whatever rule its owner uses (ASCII,
//! or Unicode for names that are not ASCII). `get(name)` takes an ASCII name in any
//! case, or a name that is not ASCII already lower-cased, and finds the key equal to
//! `name` with its ASCII letters lower-cased.

use hashbrown::HashTable;
use hashbrown::hash_table::Entry;

/// The keys live end to end in one string and the table holds where each lies: a
/// table of a large program's variables would otherwise allocate once per name.
#[derive(Clone)]
pub struct FoldMap<V> {
    table: HashTable<(Key, V)>,
    keys: String,
}

/// A key: its first folded word, which is all of a key under eight bytes (most names),
/// so that those compare without reading `keys`; and where it lies in `keys`.
#[derive(Clone, Copy)]
struct Key {
    first: u64,
    start: u32,
    len: u32,
}

impl Key {
    fn of(self, keys: &str) -> &[u8] {
        &keys.as_bytes()[self.start as usize..][..self.len as usize]
    }
}

impl<V> Default for FoldMap<V> {
    fn default() -> Self {
        FoldMap {
            table: HashTable::new(),
            keys: String::new(),
        }
    }
}

impl<V: std::fmt::Debug> std::fmt::Debug for FoldMap<V> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_map().entries(self.iter()).finish()
    }
}

const ONES: u64 = 0x0101_0101_0101_0101;
const HIGH: u64 = ONES * 0x80;

/// Lower-cases the ASCII letters among eight bytes at once. On the low seven bits of
/// each byte (so that no sum carries into the next byte), adding 0x3f reaches the top bit
/// from `A` on and adding 0x25 from `[` on; bytes with their own top bit set (UTF-8
/// beyond ASCII) are left alone.
fn fold(w: u64) -> u64 {
    let low = w & !HIGH;
    let upper = low.wrapping_add(ONES * 0x3f) & !low.wrapping_add(ONES * 0x25) & !w & HIGH;
    w | (upper >> 2)
}

fn load4(b: &[u8], at: usize) -> u64 {
    b.get(at..)
        .and_then(|s| s.first_chunk::<4>())
        .map_or(0, |c| u64::from(u32::from_le_bytes(*c)))
}

fn load8(b: &[u8], at: usize) -> u64 {
    b.get(at..)
        .and_then(|s| s.first_chunk::<8>())
        .map_or(0, |c| u64::from_le_bytes(*c))
}

/// A name of fewer than eight bytes as one word (its first, middle and last byte cover
/// a name of up to three; two overlapping halves one of four to seven), folded.
fn short(b: &[u8]) -> u64 {
    let n = b.len();
    fold(match n {
        0 => 0,
        1..4 => u64::from(b[0]) | u64::from(b[n / 2]) << 8 | u64::from(b[n - 1]) << 16,
        _ => load4(b, 0) | load4(b, n.saturating_sub(4)) << 32,
    })
}

/// The folded word at `at`; the last word of a long name overlaps the one before.
fn long(b: &[u8], at: usize) -> u64 {
    fold(load8(b, at.min(b.len().saturating_sub(8))))
}

/// A name's first folded word and its hash, computed once per lookup.
struct Folded {
    first: u64,
    hash: u64,
}

/// FxHash's step over the folded words. Keys are stored lower-cased and names that are
/// not ASCII are looked up lower-cased, so a name and its key hash alike.
fn folded(b: &[u8]) -> Folded {
    const K: u64 = 0xf135_7aea_2e62_a9c5;
    let step = |h: u64, w: u64| (h.rotate_left(5) ^ w).wrapping_mul(K);
    let first = if b.len() < 8 { short(b) } else { long(b, 0) };
    let mut h = step((b.len() as u64).wrapping_mul(K), first);
    for at in (8..b.len()).step_by(8) {
        h = step(h, long(b, at));
    }
    // hashbrown takes the bucket from the low bits and a tag from the top seven.
    Folded {
        first,
        hash: h ^ (h >> 29),
    }
}

#[cfg(test)]
fn hash(name: &str) -> u64 {
    folded(name.as_bytes()).hash
}

/// Whether the key at `key` is the name `n` (folded as `f`) with its ASCII letters
/// lower-cased. The first words settle names under eight bytes.
#[inline]
fn matches(key: &Key, keys: &str, n: &[u8], f: &Folded) -> bool {
    key.len as usize == n.len()
        && key.first == f.first
        && (n.len() < 8 || same_tail(key.of(keys), n))
}

/// The words after the first of two names of the same length, eight bytes or more.
fn same_tail(k: &[u8], n: &[u8]) -> bool {
    (8..k.len()).step_by(8).all(|at| long(k, at) == long(n, at))
}

/// Whether `key` (lower-cased) is `name` with its ASCII letters lower-cased.
#[cfg(test)]
fn same(key: &str, name: &str) -> bool {
    let (k, n) = (key.as_bytes(), name.as_bytes());
    k.len() == n.len() && folded(k).first == folded(n).first && same_tail(k, n)
}

/// The bytes of text a key is given room for by [`FoldMap::with_capacity`]: most
/// names are shorter (room not written is never touched).
const KEY_BYTES: usize = 8;

impl<V> FoldMap<V> {
    /// Room for `capacity` keys, and for their text at [`KEY_BYTES`] each: a large
    /// table's keys would otherwise be copied each time their string doubles.
    pub fn with_capacity(capacity: usize) -> Self {
        FoldMap {
            table: HashTable::with_capacity(capacity),
            keys: String::with_capacity(capacity.saturating_mul(KEY_BYTES)),
        }
    }

    #[inline]
    pub fn get(&self, name: &str) -> Option<&V> {
        let n = name.as_bytes();
        let f = folded(n);
        self.table
            .find(f.hash, |(key, _)| matches(key, &self.keys, n, &f))
            .map(|(_, v)| v)
    }

    /// The value under `key` (lower-cased by the caller), inserted by `make` if absent.
    pub fn get_or_insert_with(&mut self, key: &str, make: impl FnOnce() -> V) -> &mut V {
        let entry = match self.entry(key) {
            (Entry::Occupied(o), _, _) => o,
            (Entry::Vacant(v), keys, first) => v.insert((push_key(keys, key, first), make())),
        };
        &mut entry.into_mut().1
    }

    /// The value under `name` in any case, inserted by `make` if absent: an ASCII name is
    /// looked up as it is written and lower-cased only when it is new (`buf` holds a
    /// lower-cased copy of any other).
    pub fn get_or_insert_named(
        &mut self,
        name: &str,
        buf: &mut String,
        make: impl FnOnce() -> V,
    ) -> &mut V {
        if !name.is_ascii() {
            return self.get_or_insert_with(super::constants::key(name, buf), make);
        }
        let entry = match self.entry(name) {
            (Entry::Occupied(o), _, _) => o,
            (Entry::Vacant(v), keys, first) => {
                let at = push_key(keys, name, first);
                keys[at.start as usize..].make_ascii_lowercase();
                v.insert((at, make()))
            }
        };
        &mut entry.into_mut().1
    }

    /// Sets the value under `key` (lower-cased by the caller), replacing any before.
    pub fn insert(&mut self, key: &str, value: V) {
        match self.entry(key) {
            (Entry::Occupied(mut o), _, _) => o.get_mut().1 = value,
            (Entry::Vacant(v), keys, first) => {
                v.insert((push_key(keys, key, first), value));
            }
        }
    }

    /// The table's entry for `key`, the key string to append a new key to, and the
    /// key's first word.
    fn entry(&mut self, key: &str) -> (Entry<'_, (Key, V)>, &mut String, u64) {
        let FoldMap { table, keys } = self;
        let k = key.as_bytes();
        let f = folded(k);
        let entry = table.entry(
            f.hash,
            |(at, _)| matches(at, keys, k, &f),
            |(at, _)| folded(at.of(keys)).hash,
        );
        (entry, keys, f.first)
    }

    pub fn len(&self) -> usize {
        self.table.len()
    }

    /// Every key and value, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &V)> {
        self.table.iter().map(|(k, v)| {
            let start = k.start as usize;
            (&self.keys[start..start + k.len as usize], v)
        })
    }
}

/// `name` as a table is asked for it: an ASCII name as it is, any other lower-cased into
/// `buf`.
pub fn lookup<'a>(name: &'a str, buf: &'a mut String) -> &'a str {
    if name.is_ascii() {
        name
    } else {
        super::constants::key(name, buf)
    }
}

fn push_key(keys: &mut String, key: &str, first: u64) -> Key {
    let at = Key {
        first,
        start: keys.len() as u32,
        len: key.len() as u32,
    };
    keys.push_str(key);
    at
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_names_find_their_lower_cased_keys() {
        let mut m = FoldMap::default();
        *m.get_or_insert_with("cnt", || 0) += 1;
        *m.get_or_insert_with("käännös", || 0) += 2;
        *m.get_or_insert_with("cnt", || 0) += 4;
        assert_eq!(m.iter().count(), 2);
        assert_eq!(m.get("CNT"), Some(&5));
        assert_eq!(m.get("Cnt"), Some(&5));
        assert_eq!(m.get("käännös"), Some(&2));
        assert_eq!(m.get("cn"), None);
        assert_eq!(m.get("cntx"), None);
        m.insert("cnt", 6);
        assert_eq!(m.get("cNT"), Some(&6));
        let mut buf = String::new();
        *m.get_or_insert_named("CNT", &mut buf, || 0) += 10;
        *m.get_or_insert_named("NewName", &mut buf, || 1) += 10;
        *m.get_or_insert_named("KÄÄNNÖS", &mut buf, || 0) += 10;
        assert_eq!(m.get("cnt"), Some(&16));
        assert_eq!(m.get("newname"), Some(&11));
        assert!(m.iter().any(|(k, v)| k == "newname" && *v == 11));
        assert_eq!(m.get("käännös"), Some(&12));
        m.insert("cnt", 6);
        for i in 0..1000 {
            m.get_or_insert_with(&format!("v{i}"), || i);
        }
        assert!((0..1000).all(|i| m.get(&format!("V{i}")) == Some(&i)));
        let long = "Robot_Arm_Velocity_Limit_2";
        m.insert(&long.to_ascii_lowercase(), 7);
        assert_eq!(m.get(long), Some(&7));
        assert_eq!(m.get("robot_arm_velocity_limit_3"), None);
    }

    #[test]
    fn words_fold_exactly_the_ascii_letters() {
        let all: Vec<u8> = (0u8..128).collect();
        let folded: Vec<u8> = (0..128)
            .step_by(8)
            .flat_map(|at| long(&all, at).to_le_bytes())
            .collect();
        assert_eq!(folded, all.to_ascii_lowercase());
        for (a, b) in [
            ("Cnt", "cnt"),
            ("ABCDEFGHIJ", "abcdefghij"),
            ("@[`{", "@[`{"),
        ] {
            assert!(same(b, a), "{a} {b}");
            assert_eq!(hash(a), hash(b));
        }
        assert!(!same("cnt", "cn"));
        assert!(!same("cnt1", "cnt2"));
        assert!(!same("a\0", "a"));
        for len in 0..40 {
            let name: String = "AbCdEfGhIjKlMnOpQrStUvWxYz0123456789_xyzw"[..len].into();
            let key = name.to_ascii_lowercase();
            assert!(same(&key, &name));
            assert_eq!(hash(&key), hash(&name));
            for at in 0..len {
                let mut other = key.clone().into_bytes();
                other[at] = b'#';
                assert!(
                    !same(&key, std::str::from_utf8(&other).unwrap()),
                    "{len} {at}"
                );
            }
        }
        assert!(same("käännös", "käännös") && !same("käännös", "KÄännös"));
        assert_eq!(
            fold(u64::from_le_bytes(*b"\xc3\x84AZaz@[")),
            u64::from_le_bytes(*b"\xc3\x84azaz@[")
        );
    }
}
