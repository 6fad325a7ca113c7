//! Renders kept for reuse: a fixture's checks render the same probe for
//! several rows (an edge's two sides, a mirror's readings, a grid's lines),
//! and each such image is rendered once. The databases they are rendered
//! with are kept the same way: a probe's scene is seen at several times
//! and from several places, and each is built once.
//!
//! An image is kept under a keyed 128-bit hash of everything the render
//! reads: the scene (every mesh corner, motion and material, hashed on its
//! own first), the file's spec, the view (camera, model, settings) and the
//! traversal. The renderer
//! is deterministic, so a kept image is the one a new render would give, to
//! the bit. The hash runs over the values' `Debug` forms, which print each
//! f64 exactly (shortest round trip, the sign of a zero included). A
//! texture's texels are not hashed: they are the files the spec names, read
//! once when the fixture is loaded. The keys are drawn at random for each
//! loaded fixture, so no input can be made to collide on purpose. Hashing
//! reads every triangle once, as the database build it may save does
//! several times over (a one-off timing on the benchmark's 1M tori gave
//! about a quarter of a second). A database is keyed by the scene, the
//! Lorentz setting and the traversal alone (all [`Database::build`] and
//! [`Database::set_traversal`] read), and counted against the budget by
//! the estimate [`crate::Budget`] refuses scenes by.

use super::lazy::LazyImage;
use crate::fixture::{Fixture, View};
use renderer::{Database, Image, Traversal};
use std::collections::HashMap;
use std::fmt::{self, Write as _};
use std::hash::{BuildHasher, DefaultHasher, Hasher, RandomState};
use std::sync::{Arc, Mutex};

/// Bytes of images and databases kept at most for one loaded fixture;
/// renders and databases beyond them are made and not kept.
const BUDGET: usize = 256 << 20;

/// The images rendered for one loaded fixture and the copies checks make
/// of it (shared by those copies: each render is keyed by its content).
pub struct Renders {
    keys: (RandomState, RandomState),
    budget: usize,
    kept: Mutex<Kept>,
}

#[derive(Default)]
struct Kept {
    bytes: usize,
    images: HashMap<u128, Arc<Image>>,
    lazy: HashMap<u128, Arc<LazyImage>>,
    databases: HashMap<u128, Arc<Database>>,
    reused: usize,
}

/// What a render reads, hashed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Key(u128);

impl Default for Renders {
    fn default() -> Renders {
        Renders::within(BUDGET)
    }
}

impl fmt::Debug for Renders {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kept = self.lock();
        write!(
            f,
            "Renders({} kept, {} reused)",
            kept.images.len(),
            kept.reused
        )
    }
}

/// Two keyed SipHash streams over the same text.
struct TwoHashers(DefaultHasher, DefaultHasher);

impl fmt::Write for TwoHashers {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.0.write(s.as_bytes());
        self.1.write(s.as_bytes());
        Ok(())
    }
}

impl Renders {
    /// A store keeping at most `budget` bytes of images.
    pub(crate) fn within(budget: usize) -> Renders {
        Renders {
            keys: (RandomState::new(), RandomState::new()),
            budget,
            kept: Mutex::default(),
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Kept> {
        self.kept
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// The key of `fixture`'s scene alone: what the keys of its renders
    /// and databases are made from, so that a render that builds its
    /// database reads the scene once.
    pub(crate) fn scene_key(&self, fixture: &Fixture) -> Key {
        self.hash(format_args!("{:?}", fixture.scene))
    }

    /// The key of rendering `view` of `fixture`, whose scene's key is
    /// `scene`, with `traversal`.
    pub(crate) fn key(
        &self,
        scene: Key,
        fixture: &Fixture,
        view: &View,
        traversal: Traversal,
    ) -> Key {
        self.hash(format_args!(
            "{:032x}\u{1f}{:?}\u{1f}{view:?}\u{1f}{traversal:?}",
            scene.0, fixture.spec
        ))
    }

    /// The key of the database of the scene whose key is `scene`, for
    /// `lorentz`, searched by `traversal`.
    pub(crate) fn database_key(&self, scene: Key, lorentz: bool, traversal: Traversal) -> Key {
        self.hash(format_args!(
            "{:032x}\u{1f}{lorentz:?}\u{1f}{traversal:?}",
            scene.0
        ))
    }

    fn hash(&self, text: fmt::Arguments<'_>) -> Key {
        let mut h = TwoHashers(self.keys.0.build_hasher(), self.keys.1.build_hasher());
        // Writing into hashers cannot fail.
        let _ = h.write_fmt(text);
        Key(u128::from(h.0.finish()) << 64 | u128::from(h.1.finish()))
    }

    /// The image kept under `key`, if any.
    pub(crate) fn get(&self, key: Key) -> Option<Arc<Image>> {
        let mut kept = self.lock();
        let image = kept.images.get(&key.0).cloned();
        kept.reused += usize::from(image.is_some());
        image
    }

    /// Keeps `image` under `key` while the budget allows (shared, not
    /// copied).
    pub(crate) fn keep(&self, key: Key, image: &Arc<Image>) {
        let size = std::mem::size_of_val(image.pixels.as_slice());
        let mut kept = self.lock();
        if kept.bytes + size <= self.budget && !kept.images.contains_key(&key.0) {
            kept.bytes += size;
            kept.images.insert(key.0, Arc::clone(image));
        }
    }

    /// The image rendered as it is read kept under `key`, if any.
    pub(crate) fn get_lazy(&self, key: Key) -> Option<Arc<LazyImage>> {
        let mut kept = self.lock();
        let image = kept.lazy.get(&key.0).cloned();
        kept.reused += usize::from(image.is_some());
        image
    }

    /// Keeps `image`, rendered as it is read, under `key` while the budget
    /// allows (counted as its whole image, and its database as nothing:
    /// a probe's few kept objects).
    pub(crate) fn keep_lazy(&self, key: Key, image: &Arc<LazyImage>) {
        let size = image.bytes();
        let mut kept = self.lock();
        if kept.bytes + size <= self.budget && !kept.lazy.contains_key(&key.0) {
            kept.bytes += size;
            kept.lazy.insert(key.0, Arc::clone(image));
        }
    }

    /// The database kept under `key`, if any.
    pub(crate) fn get_database(&self, key: Key) -> Option<Arc<Database>> {
        self.lock().databases.get(&key.0).cloned()
    }

    /// Keeps `db`, estimated at `bytes`, under `key` while the budget
    /// allows (shared, not copied).
    pub(crate) fn keep_database(&self, key: Key, db: &Arc<Database>, bytes: u64) {
        let size = usize::try_from(bytes).unwrap_or(usize::MAX);
        let mut kept = self.lock();
        if size <= self.budget.saturating_sub(kept.bytes) && !kept.databases.contains_key(&key.0) {
            kept.bytes += size;
            kept.databases.insert(key.0, Arc::clone(db));
        }
    }

    /// How many images are kept, and how many renders reused one.
    pub fn counts(&self) -> (usize, usize) {
        let kept = self.lock();
        (kept.images.len(), kept.reused)
    }
}
