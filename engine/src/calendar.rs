//! The event calendar: which body has the earliest pending event.
//!
//! Every body owns exactly one entry, the time of its own earliest predicted
//! event (infinity if none). The calendar is an indexed binary min-heap over
//! those entries, so rescheduling a body is `O(log n)` in place and no stale
//! entries pile up. Predictions that an event on *another* body has made
//! obsolete are detected lazily by the world (generation counters) when they
//! reach the top. Ties are broken by body slot, which keeps runs deterministic.

/// An indexed min-heap of `(time, slot)` with one entry per slot.
#[derive(Clone, Debug, Default)]
pub struct Calendar {
    /// Heap of slots, ordered by `(time[slot], slot)`.
    heap: Vec<u32>,
    /// Position of each slot in `heap`.
    pos: Vec<u32>,
    /// Key of each slot.
    time: Vec<f64>,
}

impl Calendar {
    /// A calendar of `n` slots, all at infinity.
    pub fn new(n: usize) -> Self {
        Calendar {
            heap: (0..n as u32).collect(),
            pos: (0..n as u32).collect(),
            time: vec![f64::INFINITY; n],
        }
    }

    /// Number of slots.
    pub fn len(&self) -> usize {
        self.heap.len()
    }

    /// Whether there are no slots.
    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }

    /// Adds a slot (numbered `len()`) at infinity.
    pub fn push_slot(&mut self) -> usize {
        let s = self.heap.len();
        self.heap.push(s as u32);
        self.pos.push(s as u32);
        self.time.push(f64::INFINITY);
        s
    }

    /// The slot with the earliest time, and that time.
    #[inline]
    pub fn peek(&self) -> Option<(usize, f64)> {
        self.heap
            .first()
            .map(|&s| (s as usize, self.time[s as usize]))
    }

    /// The time of `slot`'s entry.
    pub fn time_of(&self, slot: usize) -> f64 {
        self.time[slot]
    }

    /// Sets `slot`'s time and restores the heap order.
    #[inline]
    pub fn set(&mut self, slot: usize, t: f64) {
        let old = self.time[slot];
        self.time[slot] = t;
        let i = self.pos[slot] as usize;
        if t < old {
            self.sift_up(i);
        } else if t > old {
            self.sift_down(i);
        }
    }

    #[inline]
    fn less(&self, a: u32, b: u32) -> bool {
        let (ta, tb) = (self.time[a as usize], self.time[b as usize]);
        ta < tb || (ta == tb && a < b)
    }

    fn sift_up(&mut self, mut i: usize) {
        let s = self.heap[i];
        while i > 0 {
            let parent = (i - 1) / 2;
            let p = self.heap[parent];
            if !self.less(s, p) {
                break;
            }
            self.heap[i] = p;
            self.pos[p as usize] = i as u32;
            i = parent;
        }
        self.heap[i] = s;
        self.pos[s as usize] = i as u32;
    }

    fn sift_down(&mut self, mut i: usize) {
        let n = self.heap.len();
        let s = self.heap[i];
        loop {
            let l = 2 * i + 1;
            if l >= n {
                break;
            }
            let r = l + 1;
            let c = if r < n && self.less(self.heap[r], self.heap[l]) {
                r
            } else {
                l
            };
            let child = self.heap[c];
            if !self.less(child, s) {
                break;
            }
            self.heap[i] = child;
            self.pos[child as usize] = i as u32;
            i = c;
        }
        self.heap[i] = s;
        self.pos[s as usize] = i as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn an_empty_calendar_has_nothing_pending() {
        let c = Calendar::new(3);
        assert_eq!(c.peek().map(|(_, t)| t), Some(f64::INFINITY));
        assert!(Calendar::new(0).peek().is_none());
    }

    #[test]
    fn ties_go_to_the_lower_slot() {
        let mut c = Calendar::new(4);
        c.set(3, 1.0);
        c.set(1, 1.0);
        c.set(2, 1.0);
        assert_eq!(c.peek(), Some((1, 1.0)));
    }

    proptest! {
        #[test]
        fn peek_is_always_the_minimum(ops in prop::collection::vec((0usize..16, 0.0f64..100.0), 1..200)) {
            let mut c = Calendar::new(16);
            let mut reference = [f64::INFINITY; 16];
            for (slot, t) in ops {
                c.set(slot, t);
                reference[slot] = t;
                let (s, tmin) = c.peek().unwrap();
                let best = reference.iter().cloned().fold(f64::INFINITY, f64::min);
                prop_assert_eq!(tmin, best);
                prop_assert_eq!(reference[s], best);
                prop_assert_eq!(c.time_of(s), best);
            }
        }
    }
}
