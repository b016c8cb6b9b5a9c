//! The event calendar: which body has the earliest pending event.
//!
//! Every body owns exactly one entry, the time of its own earliest predicted
//! event (infinity if none). The calendar is an indexed min-heap over
//! those entries, so rescheduling a body is `O(log n)` in place and no stale
//! entries pile up. Predictions that an event on *another* body has made
//! obsolete are detected lazily by the world (generation counters) when they
//! reach the top. Ties are broken by body slot, which keeps runs deterministic.
//! The heap is 4-ary: half the depth of a binary heap, for the 10,000-disc
//! scenes where the calendar is deep.

/// An indexed 4-ary min-heap of `(time, slot)` with one entry per slot.
/// Keys live inline in the heap array, so sifting touches one array only.
#[derive(Clone, Debug, Default)]
pub(crate) struct Calendar {
    /// Heap of `(time, slot)`, ordered by time then slot.
    heap: Vec<(f64, u32)>,
    /// Position of each slot in `heap`.
    pos: Vec<u32>,
}

const ARITY: usize = 4;

#[inline(always)]
fn less(a: (f64, u32), b: (f64, u32)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

impl Calendar {
    /// A calendar of `n` slots, all at infinity.
    pub(crate) fn new(n: usize) -> Self {
        Calendar {
            heap: (0..n as u32).map(|s| (f64::INFINITY, s)).collect(),
            pos: (0..n as u32).collect(),
        }
    }

    /// The slot with the earliest time, and that time.
    #[inline]
    pub(crate) fn peek(&self) -> Option<(usize, f64)> {
        self.heap.first().map(|&(t, s)| (s as usize, t))
    }

    /// The time of `slot`'s entry (what the tests check the heap against).
    #[cfg(test)]
    pub(crate) fn time_of(&self, slot: usize) -> f64 {
        self.heap[self.pos[slot] as usize].0
    }

    /// Sets `slot`'s time and restores the heap order.
    #[inline]
    pub(crate) fn set(&mut self, slot: usize, t: f64) {
        let i = self.pos[slot] as usize;
        let old = self.heap[i].0;
        let entry = (t, slot as u32);
        if t < old {
            self.sift_up(i, entry);
        } else if t > old {
            self.sift_down(i, entry);
        }
    }

    /// Moves every time `by` seconds earlier (the world's working time
    /// moving its origin, see `clock`), infinity staying infinity. Times
    /// that rounding makes equal are ordered by slot again.
    pub(crate) fn shift(&mut self, by: f64) {
        for entry in &mut self.heap {
            entry.0 -= by;
        }
        let n = self.heap.len();
        for i in (0..n / ARITY + 1).rev().filter(|&i| i < n) {
            let entry = self.heap[i];
            self.sift_down(i, entry);
        }
    }

    #[inline]
    fn sift_up(&mut self, mut i: usize, entry: (f64, u32)) {
        while i > 0 {
            let parent = (i - 1) / ARITY;
            let p = self.heap[parent];
            if !less(entry, p) {
                break;
            }
            self.heap[i] = p;
            self.pos[p.1 as usize] = i as u32;
            i = parent;
        }
        self.heap[i] = entry;
        self.pos[entry.1 as usize] = i as u32;
    }

    #[inline]
    fn sift_down(&mut self, mut i: usize, entry: (f64, u32)) {
        let heap = &mut self.heap[..];
        loop {
            let first = ARITY * i + 1;
            let last = (first + ARITY).min(heap.len());
            if first >= last {
                break;
            }
            // The earliest child (the first of equals).
            let mut c = first;
            let mut child = heap[first];
            for (k, &e) in heap[first + 1..last].iter().enumerate() {
                if less(e, child) {
                    (c, child) = (first + 1 + k, e);
                }
            }
            if !less(child, entry) {
                break;
            }
            heap[i] = child;
            self.pos[child.1 as usize] = i as u32;
            i = c;
        }
        heap[i] = entry;
        self.pos[entry.1 as usize] = i as u32;
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

    #[test]
    fn a_shift_keeps_the_order_and_breaks_new_ties_by_slot() {
        let mut c = Calendar::new(5);
        c.set(4, 3.2);
        c.set(3, 3.2 + 4.4e-16);
        c.set(0, 7.0);
        c.shift(3.0);
        // 0.2 and 0.2 + 4.4e-16 stay apart; nothing else moved past them.
        assert_eq!(c.peek(), Some((4, 3.2 - 3.0)));
        c.set(4, f64::INFINITY);
        assert_eq!(c.peek(), Some((3, (3.2 + 4.4e-16) - 3.0)));
        assert_eq!(c.time_of(0), 4.0);
        assert_eq!(c.time_of(1), f64::INFINITY);
        // Made equal by rounding, two entries go by slot.
        let mut c = Calendar::new(3);
        c.set(2, 1.0);
        c.set(1, 1.0 + 2.0 * f64::EPSILON);
        c.shift(-1e20);
        assert_eq!(c.peek(), Some((1, 1e20)));
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
