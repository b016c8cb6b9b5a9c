//! The broad phase: a uniform grid of cells at least one contact distance
//! wide, so a disc can only touch discs in its own or the eight neighbouring
//! cells. A disc's move into another cell is an internal event of the
//! calendar (the classic cell-crossing of event-driven molecular dynamics),
//! so only neighbours are ever solved against each other.
//!
//! The grid covers the scene's initial extent; cells on the border extend to
//! infinity, so a disc that leaves the covered area is still filed (in a
//! border cell) and nothing is missed, only less well pruned.

use crate::contact::Mover;
use glam::DVec2;

/// A uniform grid of body slots.
#[derive(Clone, Debug)]
pub(crate) struct Grid {
    origin: DVec2,
    cell: f64,
    nx: i32,
    ny: i32,
    cells: Vec<Vec<u32>>,
    /// Cell of each slot (`u32::MAX` when not filed).
    cell_of: Vec<u32>,
}

/// Which way a disc leaves its cell: `(dx, dy)`, each -1, 0 or 1.
pub(crate) type Step = (i8, i8);

impl Grid {
    /// A grid over `[lo, hi]` with cells no narrower than `min_cell`, aiming
    /// for about `target_cells` cells.
    pub(crate) fn new(lo: DVec2, hi: DVec2, min_cell: f64, target_cells: usize) -> Grid {
        let size = (hi - lo).max(DVec2::splat(min_cell));
        let ideal = (size.x * size.y / target_cells.max(1) as f64).sqrt();
        let cell = ideal.max(min_cell);
        let nx = ((size.x / cell).ceil() as i64).clamp(1, 1 << 15) as i32;
        let ny = ((size.y / cell).ceil() as i64).clamp(1, 1 << 15) as i32;
        Grid {
            origin: lo,
            cell,
            nx,
            ny,
            cells: vec![Vec::new(); (nx * ny) as usize],
            cell_of: Vec::new(),
        }
    }

    fn coords_of(&self, p: DVec2) -> (i32, i32) {
        let q = (p - self.origin) / self.cell;
        let cx = (q.x.floor().clamp(0.0, (self.nx - 1) as f64)) as i32;
        let cy = (q.y.floor().clamp(0.0, (self.ny - 1) as f64)) as i32;
        (cx, cy)
    }

    fn index(&self, cx: i32, cy: i32) -> u32 {
        (cy * self.nx + cx) as u32
    }

    /// Files `slot` at position `p`.
    pub(crate) fn insert(&mut self, slot: usize, p: DVec2) {
        if self.cell_of.len() <= slot {
            self.cell_of.resize(slot + 1, u32::MAX);
        }
        let (cx, cy) = self.coords_of(p);
        let c = self.index(cx, cy);
        self.cells[c as usize].push(slot as u32);
        self.cell_of[slot] = c;
    }

    /// Takes `slot` out of the grid.
    pub(crate) fn remove(&mut self, slot: usize) {
        let c = self.cell_of[slot];
        if c == u32::MAX {
            return;
        }
        let list = &mut self.cells[c as usize];
        if let Some(k) = list.iter().position(|&s| s as usize == slot) {
            list.swap_remove(k);
        }
        self.cell_of[slot] = u32::MAX;
    }

    /// Moves `slot` one cell in direction `step` (after a crossing event).
    pub(crate) fn step(&mut self, slot: usize, step: Step) {
        let c = self.cell_of[slot];
        let (cx, cy) = ((c as i32) % self.nx, (c as i32) / self.nx);
        let nx = (cx + step.0 as i32).clamp(0, self.nx - 1);
        let ny = (cy + step.1 as i32).clamp(0, self.ny - 1);
        self.remove(slot);
        let nc = self.index(nx, ny);
        self.cells[nc as usize].push(slot as u32);
        self.cell_of[slot] = nc;
    }

    /// The cells of the 3x3 block around `slot`'s cell (fewer at the border).
    #[inline]
    pub(crate) fn neighbour_cells(&self, slot: usize) -> impl Iterator<Item = &[u32]> + '_ {
        let c = self.cell_of[slot] as i32;
        let (cx, cy) = (c % self.nx, c / self.nx);
        let xs = (cx - 1).max(0)..=(cx + 1).min(self.nx - 1);
        ((cy - 1).max(0)..=(cy + 1).min(self.ny - 1)).flat_map(move |y| {
            xs.clone()
                .map(move |x| self.cells[self.index(x, y) as usize].as_slice())
        })
    }

    /// After `slot` moved one cell by `step`, the cells that have just come
    /// into its 3x3 block (the leading row or column; none at the border).
    #[inline]
    pub(crate) fn entered_cells(
        &self,
        slot: usize,
        step: Step,
    ) -> impl Iterator<Item = &[u32]> + '_ {
        let c = self.cell_of[slot] as i32;
        let (cx, cy) = (c % self.nx, c / self.nx);
        let (dx, dy) = (step.0 as i32, step.1 as i32);
        // The leading line of the block, at cx + dx (or cy + dy).
        let (x0, x1, y0, y1) = if dx != 0 {
            (cx + dx, cx + dx, cy - 1, cy + 1)
        } else {
            (cx - 1, cx + 1, cy + dy, cy + dy)
        };
        let xs = x0.max(0)..=x1.min(self.nx - 1);
        (y0.max(0)..=y1.min(self.ny - 1)).flat_map(move |y| {
            xs.clone()
                .map(move |x| self.cells[self.index(x, y) as usize].as_slice())
        })
    }

    /// When the moving disc next leaves its cell (at or after now), and
    /// which way. Border cells are unbounded outwards.
    pub(crate) fn next_crossing(&self, slot: usize, m: &Mover) -> Option<(f64, Step)> {
        let c = self.cell_of[slot] as i32;
        let (cx, cy) = (c % self.nx, c / self.nx);
        let (p, w) = (m.pos, m.direction());
        let mut best: Option<(f64, Step)> = None;
        let mut consider = |l: f64, step: Step| {
            if best.is_none_or(|(b, _)| l < b) {
                best = Some((l.max(0.0), step));
            }
        };
        if w.x > 0.0 && cx < self.nx - 1 {
            let edge = self.origin.x + (cx + 1) as f64 * self.cell;
            consider((edge - p.x) / w.x, (1, 0));
        } else if w.x < 0.0 && cx > 0 {
            let edge = self.origin.x + cx as f64 * self.cell;
            consider((edge - p.x) / w.x, (-1, 0));
        }
        if w.y > 0.0 && cy < self.ny - 1 {
            let edge = self.origin.y + (cy + 1) as f64 * self.cell;
            consider((edge - p.y) / w.y, (0, 1));
        } else if w.y < 0.0 && cy > 0 {
            let edge = self.origin.y + cy as f64 * self.cell;
            consider((edge - p.y) / w.y, (0, -1));
        }
        let (l, step) = best?;
        Some((m.time_at(l)?, step))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trajectory::Trajectory;

    #[test]
    fn neighbours_are_the_surrounding_block_only() {
        let mut g = Grid::new(DVec2::ZERO, DVec2::splat(10.0), 1.0, 100);
        g.insert(0, DVec2::new(5.5, 5.5));
        g.insert(1, DVec2::new(6.5, 6.5));
        g.insert(2, DVec2::new(7.5, 5.5));
        let mut seen: Vec<u32> = g.neighbour_cells(0).flatten().copied().collect();
        seen.sort();
        assert_eq!(seen, vec![0, 1]);
    }

    #[test]
    fn a_step_brings_exactly_the_leading_column_into_reach() {
        let mut g = Grid::new(DVec2::ZERO, DVec2::splat(10.0), 1.0, 100);
        g.insert(0, DVec2::new(4.5, 4.5));
        g.insert(1, DVec2::new(6.5, 3.5)); // two columns right: out of reach
        g.insert(2, DVec2::new(3.5, 4.5)); // already a neighbour
        assert_eq!(
            g.neighbour_cells(0).flatten().filter(|&&s| s == 1).count(),
            0
        );
        g.step(0, (1, 0));
        let entered: Vec<u32> = g.entered_cells(0, (1, 0)).flatten().copied().collect();
        assert_eq!(entered, vec![1]);
        assert!(g.neighbour_cells(0).flatten().any(|&s| s == 1));
    }

    #[test]
    fn a_disc_leaving_the_covered_area_stays_filed_in_a_border_cell() {
        let mut g = Grid::new(DVec2::ZERO, DVec2::splat(4.0), 1.0, 16);
        g.insert(0, DVec2::new(100.0, -50.0));
        g.insert(1, DVec2::new(3.5, 0.5));
        assert_eq!(g.neighbour_cells(0).flatten().count(), 2);
    }

    #[test]
    fn crossing_time_is_where_the_centre_reaches_the_cell_edge() {
        let mut g = Grid::new(DVec2::ZERO, DVec2::splat(4.0), 1.0, 16);
        g.insert(0, DVec2::new(0.5, 0.5));
        let tr = Trajectory::new(0.0, DVec2::new(0.5, 0.5), DVec2::new(2.0, 0.5), 0.0);
        let at = |t: f64| Mover::new(&tr, t).unwrap();
        assert_eq!(g.next_crossing(0, &at(0.0)), Some((0.25, (1, 0))));
        g.step(0, (1, 0));
        let (t, step) = g.next_crossing(0, &at(0.25)).unwrap();
        assert_eq!((t, step), (0.75, (1, 0)));
    }
}
