//! The slingshot: press on one of your pieces, drag back, release to flick
//! it the opposite way. The pull beyond the piece's rim sets the speed
//! (linearly, clamped at the maximum); dragging back onto the piece
//! cancels. Pure geometry in world metres, so it is the same for mouse and
//! touch, flipped board or not.

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

/// The slingshot of a piece of `radius` on a board of `square`-sized
/// squares with `max_speed`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slingshot {
    pub radius: f64,
    pub square: f64,
    pub max_speed: f64,
}

impl Slingshot {
    /// The shot for a piece at `piece` pulled to the pointer at `pointer`.
    pub fn aim(&self, piece: DVec2, pointer: DVec2) -> Aim {
        let pull = pointer - piece;
        let d = pull.length();
        if !d.is_finite() || d <= self.radius {
            return Aim::Cancel;
        }
        let power = ((d - self.radius) / (FULL_PULL_SQUARES * self.square)).min(1.0);
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

    fn sling() -> Slingshot {
        Slingshot {
            radius: 0.016,
            square: 0.04,
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
        let full = FULL_PULL_SQUARES * s.square;
        assert!((at(full / 4.0) - 0.25).abs() < 1e-12);
        assert!((at(full / 2.0) - 0.5).abs() < 1e-12);
    }
}
