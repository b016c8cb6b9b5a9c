//! A touching pair whose straight relative path closes in by less than the
//! rounding of its positions before it turns to parting: a graze, not a
//! contact. A disc sliding along a wall past one lying against it, their
//! line of centres within a few nanoradians of square to its motion,
//! approaches it at a speed far above the rounding of the velocities, but
//! the whole approach still ahead of it, the sagitta of its path over the
//! other disc, is below what a position can show: played as a contact of a
//! ring, its push (a carry the positions cannot hold) is played again at
//! every hit of the discs it drives, each turn picoseconds long. From the
//! eighteenth revision no hit is predicted for a disc moving so against one
//! at rest, and the ring of a hit is played without such a pair
//! (`Revision::passes_grazes_within_rounding`, `contact::disc_point`,
//! `World::cluster_ring`).

use crate::limits::SETTLE;
use glam::DVec2;

/// How far the distance of two discs, centre offset `d` (from the other to
/// the mover) and relative velocity `w`, still shrinks along a straight
/// path before it turns to parting: `|d|` less the path's least distance
/// `|d x w| / |w|`, formed as `(d . w)^2 / |w|^2 / (|d| + |d x w| / |w|)`
/// (free of the cancellation of the two lengths). Zero where the pair does
/// not approach.
pub(crate) fn closing_left(d: DVec2, w: DVec2) -> f64 {
    let u = w.normalize_or_zero();
    let along = d.dot(u);
    if along >= 0.0 {
        return 0.0;
    }
    along * along / (d.length() + d.perp_dot(u).abs())
}

/// Whether a touching pair at positions `pa`, `pb` (centre offset `pa -
/// pb`), relative velocity `w` (of `a` against `b`), approaches but only
/// grazes: its straight path closes in by no more than the rounding of
/// its positions (`SETTLE` of their largest coordinate, as
/// `World::settled` rounds a slide). A pair that parts or slides square
/// to its line of centres does not graze: it does not approach at all.
pub(crate) fn within_rounding(pa: DVec2, pb: DVec2, w: DVec2) -> bool {
    let rounding = SETTLE * pa.abs().max_element().max(pb.abs().max_element());
    let left = closing_left(pa - pb, w);
    left > 0.0 && left <= rounding
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disc_sliding_square_past_its_neighbour_closes_by_the_sagitta_of_its_path() {
        // Offset 2.6e-10 m above the line of centres, sliding down onto it.
        let (s, h): (f64, f64) = (0.038, 2.6e-10);
        let d = DVec2::new(-(s * s - h * h).sqrt(), h);
        let left = closing_left(d, DVec2::new(0.0, -5e-4));
        let sagitta = h * h / (2.0 * s);
        assert!((left - sagitta).abs() <= 1e-9 * sagitta, "{left} {sagitta}");
        assert!(within_rounding(
            d + DVec2::splat(-0.28),
            DVec2::splat(-0.28),
            DVec2::Y * -5e-4
        ));
    }

    #[test]
    fn a_pair_parting_or_approaching_head_on_is_no_graze() {
        let d = DVec2::new(-0.038, 0.0);
        assert_eq!(closing_left(d, DVec2::new(-1e-3, 0.0)), 0.0);
        assert!(!within_rounding(d, DVec2::ZERO, DVec2::new(1e-12, 0.0)));
        // Tilted by 1e-4 of the distance: closes by far more than a
        // position's rounding.
        let d = DVec2::new(-0.038, 3.8e-6);
        assert!(!within_rounding(d, DVec2::ZERO, DVec2::new(0.0, -1.0)));
    }
}
