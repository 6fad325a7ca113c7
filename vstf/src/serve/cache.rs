//! The databases `serve` keeps between requests, within a byte budget:
//! each entry is charged the memory estimate of its scene's database, and
//! the least recently used entries go first. An entry larger than the whole
//! budget is built and used, never kept.

use std::sync::Arc;

/// A cache of `V` by `K` within `budget` bytes.
pub(super) struct Lru<K, V> {
    budget: u64,
    used: u64,
    tick: u64,
    entries: Vec<Entry<K, V>>,
}

struct Entry<K, V> {
    key: K,
    value: Arc<V>,
    bytes: u64,
    last: u64,
}

impl<K: PartialEq, V> Lru<K, V> {
    /// An empty cache of at most `budget` bytes.
    pub(super) fn new(budget: u64) -> Self {
        Lru {
            budget,
            used: 0,
            tick: 0,
            entries: Vec::new(),
        }
    }

    /// The value kept for `key`, marked as just used.
    pub(super) fn get(&mut self, key: &K) -> Option<Arc<V>> {
        self.tick += 1;
        let tick = self.tick;
        self.entries.iter_mut().find(|e| e.key == *key).map(|e| {
            e.last = tick;
            e.value.clone()
        })
    }

    /// Keeps `value` (of `bytes`) for `key`, evicting the least recently
    /// used entries to make room; kept only if it fits the budget alone.
    pub(super) fn insert(&mut self, key: K, value: Arc<V>, bytes: u64) {
        self.entries.retain(|e| e.key != key);
        self.used = self.entries.iter().map(|e| e.bytes).sum();
        if bytes > self.budget {
            return;
        }
        while self.used + bytes > self.budget {
            let Some(oldest) = (0..self.entries.len()).min_by_key(|&i| self.entries[i].last) else {
                break;
            };
            self.used -= self.entries.swap_remove(oldest).bytes;
        }
        self.tick += 1;
        self.used += bytes;
        self.entries.push(Entry {
            key,
            value,
            bytes,
            last: self.tick,
        });
    }

    /// The bytes charged to the entries kept.
    pub(super) fn used(&self) -> u64 {
        self.used
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_least_recently_used_goes_first_and_the_budget_holds() {
        let mut c = Lru::new(100);
        c.insert(1, Arc::new("a"), 40);
        c.insert(2, Arc::new("b"), 40);
        assert!(c.get(&1).is_some());
        c.insert(3, Arc::new("c"), 40);
        assert!(c.get(&2).is_none(), "the least recently used stays");
        assert!(c.get(&1).is_some() && c.get(&3).is_some());
        assert_eq!(c.used(), 80);
        c.insert(4, Arc::new("huge"), 101);
        assert!(c.get(&4).is_none(), "an entry over the budget is kept");
        assert_eq!(c.used(), 80);
        for k in 10..40 {
            c.insert(k, Arc::new("x"), 30);
            assert!(c.used() <= 100);
        }
    }
}
