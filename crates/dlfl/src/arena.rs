//! Slot storage with generations and O(1) insert and remove.
//!
//! Values sit in one `Vec`; a parallel `Vec<u32>` holds each slot's
//! generation, odd while the slot is live and even while it is free, and
//! freed slots are kept on a stack for reuse. Iteration visits live slots in
//! index order, so it is deterministic.

use crate::error::{Error, Result};
use crate::ids::EntityKind;

#[derive(Clone, Debug)]
pub(crate) struct Arena<T> {
    values: Vec<T>,
    generations: Vec<u32>,
    free: Vec<u32>,
    live: usize,
}

impl<T> Default for Arena<T> {
    fn default() -> Self {
        Arena {
            values: Vec::new(),
            generations: Vec::new(),
            free: Vec::new(),
            live: 0,
        }
    }
}

impl<T: Copy> Arena<T> {
    /// An arena holding `values` in slots `0..n`, all live at generation 1.
    pub(crate) fn from_values(values: Vec<T>) -> Self {
        let n = values.len();
        Arena {
            values,
            generations: vec![1; n],
            free: Vec::new(),
            live: n,
        }
    }

    /// Number of live values.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.live
    }

    /// One past the largest slot index ever used.
    #[inline]
    pub(crate) fn capacity_slots(&self) -> usize {
        self.values.len()
    }

    /// Stores `value`, returning its slot index and generation.
    #[inline]
    pub(crate) fn insert(&mut self, value: T) -> (u32, u32) {
        self.live += 1;
        if let Some(i) = self.free.pop() {
            let slot = i as usize;
            self.values[slot] = value;
            self.generations[slot] = self.generations[slot].wrapping_add(1);
            (i, self.generations[slot])
        } else {
            let i = u32::try_from(self.values.len()).expect("more than 2^32 mesh entities");
            self.values.push(value);
            self.generations.push(1);
            (i, 1)
        }
    }

    /// Frees slot `i`. The caller guarantees it is live.
    #[inline]
    pub(crate) fn remove(&mut self, i: u32) {
        let slot = i as usize;
        debug_assert!(self.is_live(i));
        self.generations[slot] = self.generations[slot].wrapping_add(1);
        self.free.push(i);
        self.live -= 1;
    }

    #[inline]
    pub(crate) fn is_live(&self, i: u32) -> bool {
        self.generations.get(i as usize).is_some_and(|g| g & 1 == 1)
    }

    /// True when slot `i` is live and has generation `generation`.
    #[inline]
    pub(crate) fn matches(&self, i: u32, generation: u32) -> bool {
        generation & 1 == 1 && self.generations.get(i as usize) == Some(&generation)
    }

    /// Slot `index` when it is live with generation `generation` (a handle
    /// to a `kind` entity); otherwise the handle is stale.
    #[inline]
    pub(crate) fn check(&self, kind: EntityKind, index: u32, generation: u32) -> Result<u32> {
        if self.matches(index, generation) {
            Ok(index)
        } else {
            Err(Error::Stale {
                kind,
                index,
                generation,
            })
        }
    }

    #[inline]
    pub(crate) fn generation(&self, i: u32) -> u32 {
        self.generations[i as usize]
    }

    #[inline]
    pub(crate) fn get(&self, i: u32) -> &T {
        &self.values[i as usize]
    }

    #[inline]
    pub(crate) fn get_mut(&mut self, i: u32) -> &mut T {
        &mut self.values[i as usize]
    }

    /// Live slot indices in increasing order.
    pub(crate) fn live_indices(&self) -> impl Iterator<Item = u32> + '_ {
        self.generations
            .iter()
            .enumerate()
            .filter(|(_, g)| *g & 1 == 1)
            .map(|(i, _)| i as u32)
    }

    /// Bytes held by this arena's buffers (for memory accounting).
    pub(crate) fn heap_bytes(&self) -> usize {
        self.values.capacity() * std::mem::size_of::<T>()
            + self.generations.capacity() * 4
            + self.free.capacity() * 4
    }
}
