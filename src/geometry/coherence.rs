//! Coherence between neighbouring rays: a per-thread memory of the normals
//! that the last casts at each convex set ([`super::convex::Convex`]) found,
//! for the next cast along nearly the same direction to start from (a
//! neighbouring pixel's ray meets the surface near the last one's). It is on
//! only inside [`coherent`] — a row of pixels, whose rays one thread casts
//! in a fixed order — and emptied at its start, so that what a ray finds,
//! and the steps counted, never depend on which thread cast what before.

use glam::DVec3;
use std::cell::RefCell;

/// The casts remembered: each convex set's entry and exit, for camera rays
/// and for each light's shadow rays, of a few sets.
const ENTRIES: usize = 16;

/// The least cosine between a remembered cast's direction and a new one's
/// for its normal to be a start.
const ALIGNED: f64 = 0.999;

struct Entry {
    key: usize,
    slot: u8,
    dir: DVec3,
    normal: DVec3,
}

#[derive(Default)]
struct Memory {
    on: bool,
    entries: Vec<Entry>,
    /// The entry replaced next when all are taken.
    next: usize,
}

thread_local! {
    static MEMORY: RefCell<Memory> = RefCell::new(Memory::default());
}

/// Runs `f` with the memory on, emptied first, and off again after (within
/// a call already on, simply runs it).
pub fn coherent<R>(f: impl FnOnce() -> R) -> R {
    let started = MEMORY.with(|m| {
        let mut m = m.borrow_mut();
        if m.on {
            return false;
        }
        m.on = true;
        m.entries.clear();
        m.next = 0;
        true
    });
    let out = f();
    if started {
        MEMORY.with(|m| {
            let mut m = m.borrow_mut();
            m.on = false;
            m.entries.clear();
        });
    }
    out
}

fn aligned(a: DVec3, b: DVec3) -> bool {
    a.dot(b) > ALIGNED * a.length() * b.length()
}

/// The unit normal the last cast of set `key` (`slot`: 0 its entry, 1 its
/// exit) along nearly `dir` found, when the memory is on and holds one.
pub fn recall(key: usize, slot: u8, dir: DVec3) -> Option<DVec3> {
    MEMORY.with(|m| {
        let m = m.borrow();
        if !m.on {
            return None;
        }
        m.entries
            .iter()
            .find(|e| e.key == key && e.slot == slot && aligned(e.dir, dir))
            .map(|e| e.normal)
    })
}

/// Keeps `normal` (unit) as what the cast of set `key` along `dir` found,
/// in place of the entry for nearly that direction, else of the oldest.
pub fn remember(key: usize, slot: u8, dir: DVec3, normal: DVec3) {
    MEMORY.with(|m| {
        let mut m = m.borrow_mut();
        if !m.on {
            return;
        }
        let entry = Entry {
            key,
            slot,
            dir,
            normal,
        };
        if let Some(e) = m
            .entries
            .iter_mut()
            .find(|e| e.key == key && e.slot == slot && aligned(e.dir, dir))
        {
            *e = entry;
        } else if m.entries.len() < ENTRIES {
            m.entries.push(entry);
        } else {
            let k = m.next;
            m.entries[k] = entry;
            m.next = (k + 1) % ENTRIES;
        }
    })
}
