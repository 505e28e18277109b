//! A one-entry cache for what a parameter edit may or may not invalidate: the renderer keeps
//! the last lobe table and back-scattering tables with the parameters they were built for, and
//! rebuilds them only when those change (an absorption edit changes neither). It counts its
//! builds, so that a test can tell an edit that rebuilt from one that did not.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// The last value built and the key it was built for, and how many builds there were.
#[derive(Debug)]
pub struct LastBuilt<K, V> {
    last: Mutex<Option<(K, Arc<V>)>>,
    builds: AtomicU64,
}

impl<K, V> Default for LastBuilt<K, V> {
    fn default() -> Self {
        Self {
            last: Mutex::new(None),
            builds: AtomicU64::new(0),
        }
    }
}

impl<K, V> LastBuilt<K, V> {
    /// How many times a value was built.
    pub fn builds(&self) -> u64 {
        self.builds.load(Ordering::Relaxed)
    }
}

impl<K: PartialEq, V> LastBuilt<K, V> {
    /// The value for `key`: the last one if it was built for an equal key, else `build()`'s,
    /// which replaces it.
    pub fn get_or_build(&self, key: K, build: impl FnOnce() -> V) -> Arc<V> {
        let mut last = self.last.lock().unwrap_or_else(PoisonError::into_inner);
        match &*last {
            Some((k, v)) if *k == key => v.clone(),
            _ => {
                self.builds.fetch_add(1, Ordering::Relaxed);
                let v = Arc::new(build());
                *last = Some((key, v.clone()));
                v
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::LastBuilt;
    use std::sync::Arc;

    /// An equal key returns the same allocation without building; a new key builds.
    #[test]
    fn rebuilds_only_for_a_new_key() {
        let cache = LastBuilt::default();
        let mut builds = 0;
        let a = cache.get_or_build(1, || {
            builds += 1;
            "one"
        });
        let b = cache.get_or_build(1, || {
            builds += 1;
            "again"
        });
        assert!(Arc::ptr_eq(&a, &b));
        let c = cache.get_or_build(2, || {
            builds += 1;
            "two"
        });
        assert_eq!((*c, builds, cache.builds()), ("two", 2, 2));
    }
}
