//! The slingshot: press on one of your pieces, drag back, release to flick
//! it the opposite way. The pull beyond the piece's rim sets the speed
//! (linearly, clamped at the maximum); dragging back onto the piece
//! cancels. Full power takes a pull of 3.5 squares, or, where the window
//! leaves less room than that in the pull's direction, all the room there
//! is: full power is always reachable inside the window. Pure geometry in
//! world metres, so it is the same for mouse and touch, flipped board or
//! not.

use ::glam::DVec2;

/// The pull (beyond the rim) that gives full speed, in board squares.
pub const FULL_PULL_SQUARES: f64 = 3.5;

/// What a pull means.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Aim {
    /// Released here, nothing would be shot.
    Cancel,
    /// The velocity the release would shoot, and its fraction of the
    /// maximum speed (0..=1, for the power meter).
    Shoot { velocity: DVec2, power: f64 },
}

/// The slingshot of a piece of `radius` with `max_speed`, reaching full
/// power at a pull of `full_pull` beyond the rim.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slingshot {
    pub radius: f64,
    pub full_pull: f64,
    pub max_speed: f64,
}

/// How far a ray from `from` along `dir` runs inside the box `lo`..`hi`
/// (0 when `from` is outside or `dir` is zero).
pub fn room_along(from: DVec2, dir: DVec2, lo: DVec2, hi: DVec2) -> f64 {
    let dir = dir.normalize_or_zero();
    let inside = from.cmpge(lo).all() && from.cmple(hi).all();
    if dir == DVec2::ZERO || !inside {
        return 0.0;
    }
    let exit = |p: f64, d: f64, lo: f64, hi: f64| {
        if d > 0.0 {
            (hi - p) / d
        } else if d < 0.0 {
            (lo - p) / d
        } else {
            f64::INFINITY
        }
    };
    exit(from.x, dir.x, lo.x, hi.x).min(exit(from.y, dir.y, lo.y, hi.y))
}

/// The pull beyond the rim that gives full power: 3.5 squares, or, when
/// the piece's centre has only `room` to the window's edge in the pull's
/// direction, nine tenths of what lies beyond the rim (never less than a
/// tenth of a square, so a pull stays readable).
pub fn full_pull(square: f64, radius: f64, room: f64) -> f64 {
    let most = FULL_PULL_SQUARES * square;
    let usable = (room - radius) * 0.9;
    if usable.is_finite() {
        usable.clamp(square * 0.1, most)
    } else {
        most
    }
}

impl Slingshot {
    /// The shot for a piece at `piece` pulled to the pointer at `pointer`.
    pub fn aim(&self, piece: DVec2, pointer: DVec2) -> Aim {
        let pull = pointer - piece;
        let d = pull.length();
        if !d.is_finite() || d <= self.radius {
            return Aim::Cancel;
        }
        let power = ((d - self.radius) / self.full_pull.max(1e-9)).min(1.0);
        let speed = power * self.max_speed;
        if speed <= 0.0 {
            return Aim::Cancel;
        }
        // Rounding can put the length a hair above the limit the server
        // enforces; shave it off.
        let mut velocity = -pull / d * speed;
        while velocity.length() > self.max_speed {
            velocity *= 1.0 - 2.0 * f64::EPSILON;
        }
        Aim::Shoot { velocity, power }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: f64 = 0.04;

    fn sling() -> Slingshot {
        Slingshot {
            radius: 0.016,
            full_pull: FULL_PULL_SQUARES * SQUARE,
            max_speed: 2.0,
        }
    }

    #[test]
    fn pulling_back_shoots_the_opposite_way() {
        let p = DVec2::new(0.1, 0.1);
        match sling().aim(p, p + DVec2::new(0.0, -0.05)) {
            Aim::Shoot { velocity, power } => {
                assert!(velocity.x.abs() < 1e-12 && velocity.y > 0.0);
                assert!(power > 0.0 && power < 1.0);
            }
            Aim::Cancel => panic!("a pull beyond the rim shoots"),
        }
    }

    #[test]
    fn a_long_pull_is_clamped_at_the_maximum_speed() {
        let p = DVec2::ZERO;
        let Aim::Shoot { velocity, power } = sling().aim(p, DVec2::new(3.0, 4.0)) else {
            panic!("shoots")
        };
        assert_eq!(power, 1.0);
        assert!((velocity.length() - 2.0).abs() < 1e-12);
        assert!(velocity.length() <= 2.0, "never above the server's limit");
    }

    #[test]
    fn dragging_back_onto_the_piece_cancels() {
        let p = DVec2::new(0.2, 0.3);
        assert_eq!(sling().aim(p, p + DVec2::new(0.01, 0.0)), Aim::Cancel);
        assert_eq!(sling().aim(p, p), Aim::Cancel);
        assert_eq!(sling().aim(p, DVec2::new(f64::NAN, 0.0)), Aim::Cancel);
    }

    #[test]
    fn power_grows_linearly_with_the_pull() {
        let s = sling();
        let at = |d: f64| match s.aim(DVec2::ZERO, DVec2::new(0.0, -(s.radius + d))) {
            Aim::Shoot { power, .. } => power,
            Aim::Cancel => 0.0,
        };
        let full = s.full_pull;
        assert!((at(full / 4.0) - 0.25).abs() < 1e-12);
        assert!((at(full / 2.0) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn with_room_to_spare_full_power_takes_three_and_a_half_squares() {
        assert_eq!(full_pull(SQUARE, 0.016, 10.0), FULL_PULL_SQUARES * SQUARE);
        assert_eq!(
            full_pull(SQUARE, 0.016, f64::INFINITY),
            FULL_PULL_SQUARES * SQUARE
        );
    }

    #[test]
    fn any_piece_reaches_full_power_inside_the_window_in_any_direction() {
        // A window barely larger than the board, pieces near its edges.
        let (lo, hi) = (DVec2::new(-0.02, -0.03), DVec2::new(0.34, 0.35));
        let radius = 0.016;
        for piece in [
            DVec2::new(0.02, 0.02),
            DVec2::new(0.30, 0.02),
            DVec2::new(0.16, 0.30),
            DVec2::new(0.16, 0.16),
        ] {
            for k in 0..16 {
                let angle = k as f64 * std::f64::consts::TAU / 16.0;
                let dir = DVec2::new(angle.cos(), angle.sin());
                let room = room_along(piece, dir, lo, hi);
                let s = Slingshot {
                    radius,
                    full_pull: full_pull(SQUARE, radius, room),
                    max_speed: 2.0,
                };
                let pointer = piece + dir * (radius + s.full_pull);
                assert!(
                    pointer.cmpge(lo).all() && pointer.cmple(hi).all(),
                    "the full pull from {piece} towards {dir} leaves the window"
                );
                match s.aim(piece, pointer) {
                    Aim::Shoot { power, .. } => assert!(power > 1.0 - 1e-9, "power {power}"),
                    Aim::Cancel => panic!("a pull to the edge shoots"),
                }
            }
        }
    }

    #[test]
    fn the_room_along_a_ray_ends_at_the_first_edge_it_meets() {
        let (lo, hi) = (DVec2::ZERO, DVec2::new(4.0, 2.0));
        let from = DVec2::new(1.0, 1.0);
        assert!((room_along(from, DVec2::X, lo, hi) - 3.0).abs() < 1e-12);
        assert!((room_along(from, -DVec2::Y, lo, hi) - 1.0).abs() < 1e-12);
        assert!((room_along(from, DVec2::new(1.0, 1.0), lo, hi) - 2f64.sqrt()).abs() < 1e-12);
        assert_eq!(room_along(DVec2::new(9.0, 1.0), DVec2::X, lo, hi), 0.0);
    }
}
