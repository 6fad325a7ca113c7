//! The databases built for the page, kept within a byte budget: each
//! entry's size estimated from its prisms (as [`crate::Budget`] does), the
//! least recently used evicted first, and an entry larger than the whole
//! budget used once and not kept.

use crate::fixture::Fixture;
use renderer::Database;
use std::collections::HashMap;
use std::sync::Arc;

/// What a database is kept under: fixture, view, Lorentz setting and the
/// speed factor's bits.
pub(super) type Key = (String, String, bool, u64);

/// A kept fixture (as sped up) and its database.
pub(super) type Entry = Arc<(Fixture, Database)>;

/// How full the cache is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CacheUsage {
    /// The estimated bytes of the entries kept.
    pub bytes: u64,
    /// How many entries are kept.
    pub entries: usize,
    /// The budget, bytes.
    pub budget: u64,
    /// Entries evicted so far.
    pub evicted: u64,
}

struct Kept<V> {
    entry: V,
    bytes: u64,
    used_at: u64,
}

/// A least-recently-used cache of databases within a byte budget.
pub(super) struct Lru<V> {
    kept: HashMap<Key, Kept<V>>,
    clock: u64,
    usage: CacheUsage,
}

impl<V: Clone> Lru<V> {
    /// An empty cache of `budget` bytes.
    pub(super) fn new(budget: u64) -> Lru<V> {
        Lru {
            kept: HashMap::new(),
            clock: 0,
            usage: CacheUsage {
                bytes: 0,
                entries: 0,
                budget,
                evicted: 0,
            },
        }
    }

    /// The entry kept under `key`, now the most recently used.
    pub(super) fn get(&mut self, key: &Key) -> Option<V> {
        self.clock += 1;
        let k = self.kept.get_mut(key)?;
        k.used_at = self.clock;
        Some(k.entry.clone())
    }

    /// Keeps `entry` of `bytes` under `key`, evicting the least recently
    /// used entries to make room; an entry over the budget is not kept.
    pub(super) fn put(&mut self, key: Key, entry: V, bytes: u64) {
        if bytes > self.usage.budget || self.kept.contains_key(&key) {
            return;
        }
        self.make_room(bytes);
        self.clock += 1;
        self.usage.bytes += bytes;
        self.kept.insert(
            key,
            Kept {
                entry,
                bytes,
                used_at: self.clock,
            },
        );
        self.usage.entries = self.kept.len();
    }

    /// Evicts the least recently used entries until `bytes` more fit the
    /// budget (all of them for an entry larger than the budget), so that
    /// a database is built in memory the cache has already let go.
    pub(super) fn make_room(&mut self, bytes: u64) {
        while self.usage.bytes + bytes > self.usage.budget {
            let Some(oldest) = self
                .kept
                .iter()
                .min_by_key(|(_, k)| k.used_at)
                .map(|(key, _)| key.clone())
            else {
                break;
            };
            if let Some(k) = self.kept.remove(&oldest) {
                self.usage.bytes -= k.bytes;
                self.usage.evicted += 1;
            }
        }
        self.usage.entries = self.kept.len();
    }

    /// How full it is.
    pub(super) fn usage(&self) -> CacheUsage {
        CacheUsage {
            entries: self.kept.len(),
            ..self.usage
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(i: u64) -> Key {
        ("f".into(), "v".into(), true, i)
    }

    #[test]
    fn the_least_recently_used_go_first_and_the_too_large_are_not_kept() {
        let mut c: Lru<u64> = Lru::new(100);
        c.put(key(1), 1, 40);
        c.put(key(2), 2, 40);
        assert_eq!(c.get(&key(1)), Some(1));
        c.put(key(3), 3, 40);
        assert_eq!(
            (c.get(&key(2)), c.get(&key(1)), c.get(&key(3))),
            (None, Some(1), Some(3))
        );
        let u = c.usage();
        assert_eq!((u.bytes, u.entries, u.evicted), (80, 2, 1));
        c.put(key(4), 4, 101);
        assert_eq!((c.get(&key(4)), c.usage().bytes), (None, 80));
        c.put(key(5), 5, 100);
        assert_eq!((c.usage().bytes, c.usage().entries), (100, 1));
        // Room made before a build: the kept entries go, oldest first.
        c.make_room(60);
        assert!(c.usage().bytes + 60 <= 100, "{:?}", c.usage());
        c.make_room(1000);
        assert_eq!(c.usage().bytes, 0);
    }
}
