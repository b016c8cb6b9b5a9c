//! Closed-form motion of one disc between two events.
//!
//! A disc sliding under Coulomb friction decelerates at the constant magnitude
//! `alpha = mu * g` against its velocity, so it moves along a straight line:
//! `r(s) = p + d * sigma(s)` with `sigma(s) = |u| s - alpha s^2 / 2` until it
//! stops at `s_stop = |u| / alpha`, then rests. A `Trajectory` is that formula
//! anchored at its own start time `t0`; an event replaces the trajectories of
//! the bodies it involves and leaves every other body's untouched, so no
//! rounding accumulates from re-basing bodies that nothing touched.
//! Frictionless motion (`alpha = 0`) uses `p + u s` directly, which is exact
//! to one rounding per coordinate.

use glam::DVec2;
use serde::{Deserialize, Serialize};

/// The motion of one disc from time `t0` on, until something changes it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(from = "TrajectoryData", into = "TrajectoryData")]
pub struct Trajectory {
    t0: f64,
    #[schemars(with = "[f64; 2]")]
    p: DVec2,
    #[schemars(with = "[f64; 2]")]
    u: DVec2,
    alpha: f64,
    // Derived, cached: |u|, u/|u| (only with friction: frictionless motion
    // needs neither, and skipping them keeps a frictionless event cheap), and
    // the absolute stop time.
    speed: f64,
    #[schemars(with = "[f64; 2]")]
    dir: DVec2,
    t_stop: f64,
}

/// The serialised form: only what defines the motion.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, schemars::JsonSchema)]
struct TrajectoryData {
    t0: f64,
    #[schemars(with = "[f64; 2]")]
    pos: DVec2,
    #[schemars(with = "[f64; 2]")]
    vel: DVec2,
    alpha: f64,
}

impl From<TrajectoryData> for Trajectory {
    fn from(d: TrajectoryData) -> Self {
        Trajectory::new(d.t0, d.pos, d.vel, d.alpha)
    }
}

impl From<Trajectory> for TrajectoryData {
    fn from(t: Trajectory) -> Self {
        TrajectoryData {
            t0: t.t0,
            pos: t.p,
            vel: t.u,
            alpha: t.alpha,
        }
    }
}

impl Trajectory {
    /// Motion starting at time `t0` at position `p` with velocity `u`, slowing
    /// at `alpha >= 0` (units of acceleration).
    pub fn new(t0: f64, p: DVec2, u: DVec2, alpha: f64) -> Self {
        if alpha == 0.0 {
            if u == DVec2::ZERO {
                return Self::at_rest(t0, p, alpha);
            }
            return Trajectory {
                t0,
                p,
                u,
                alpha,
                speed: 0.0,
                dir: DVec2::ZERO,
                t_stop: f64::INFINITY,
            };
        }
        let speed = u.length();
        if speed == 0.0 {
            return Self::at_rest(t0, p, alpha);
        }
        let dir = u / speed;
        let t_stop = if alpha > 0.0 {
            t0 + speed / alpha
        } else {
            f64::INFINITY
        };
        Trajectory {
            t0,
            p,
            u,
            alpha,
            speed,
            dir,
            t_stop,
        }
    }

    /// A disc resting at `p` from `t0` on.
    pub(crate) fn at_rest(t0: f64, p: DVec2, alpha: f64) -> Self {
        Trajectory {
            t0,
            p,
            u: DVec2::ZERO,
            alpha,
            speed: 0.0,
            dir: DVec2::ZERO,
            t_stop: t0,
        }
    }

    /// When this motion began.
    pub fn start_time(&self) -> f64 {
        self.t0
    }
    /// Position at the start.
    pub(crate) fn start_position(&self) -> DVec2 {
        self.p
    }
    /// Velocity at the start.
    pub fn start_velocity(&self) -> DVec2 {
        self.u
    }
    /// Deceleration magnitude `mu * g`.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// Speed at the start.
    pub fn speed(&self) -> f64 {
        if self.alpha == 0.0 {
            self.u.length()
        } else {
            self.speed
        }
    }
    /// Unit direction of travel (zero at rest).
    pub fn direction(&self) -> DVec2 {
        if self.alpha == 0.0 {
            self.u.normalize_or_zero()
        } else {
            self.dir
        }
    }
    /// Absolute time the disc comes to rest (`t0` if it starts at rest,
    /// infinite without friction).
    pub fn stop_time(&self) -> f64 {
        self.t_stop
    }
    /// Whether the disc moves at time `t` (at or after `t0`).
    pub fn is_moving_at(&self, t: f64) -> bool {
        t < self.t_stop
    }
    /// Whether the disc moves at all.
    pub(crate) fn is_moving(&self) -> bool {
        self.t_stop > self.t0
    }
    /// Whether it moves without friction (never stops).
    pub fn is_frictionless(&self) -> bool {
        self.alpha == 0.0
    }

    /// Distance travelled along `direction()` after `s >= 0` seconds
    /// (clamped at the stop).
    pub(crate) fn sigma(&self, s: f64) -> f64 {
        if self.alpha == 0.0 {
            return self.speed() * s;
        }
        let s = s.min(self.t_stop - self.t0);
        s * (self.speed - 0.5 * self.alpha * s)
    }

    /// Total distance it will travel (infinite without friction).
    pub(crate) fn stopping_distance(&self) -> f64 {
        if !self.is_moving() {
            0.0
        } else if self.alpha == 0.0 {
            f64::INFINITY
        } else {
            self.speed * self.speed / (2.0 * self.alpha)
        }
    }

    /// Position at absolute time `t >= t0`.
    pub fn position(&self, t: f64) -> DVec2 {
        let s = t - self.t0;
        if self.alpha == 0.0 {
            return self.p + self.u * s;
        }
        if self.speed == 0.0 {
            return self.p;
        }
        self.p + self.dir * self.sigma(s)
    }

    /// Velocity at absolute time `t >= t0`.
    pub fn velocity(&self, t: f64) -> DVec2 {
        if self.alpha == 0.0 {
            return self.u;
        }
        if t >= self.t_stop {
            return DVec2::ZERO;
        }
        self.dir * (self.speed - self.alpha * (t - self.t0))
    }

    /// Acceleration at absolute time `t` (constant while moving).
    pub fn acceleration(&self, t: f64) -> DVec2 {
        if t >= self.t_stop {
            DVec2::ZERO
        } else {
            -self.alpha * self.dir
        }
    }

    /// Absolute time at which the disc has travelled `sigma` along its
    /// direction, or `None` if it stops first.
    pub(crate) fn time_at_distance(&self, sigma: f64) -> Option<f64> {
        if !self.is_moving() || sigma < 0.0 {
            return None;
        }
        if self.alpha == 0.0 {
            return Some(self.t0 + sigma / self.speed());
        }
        // sigma = v s - a s^2/2  =>  s = 2 sigma / (v + sqrt(v^2 - 2 a sigma)),
        // the cancellation-free root.
        let disc = self.speed * self.speed - 2.0 * self.alpha * sigma;
        if disc < 0.0 {
            return None;
        }
        let s = 2.0 * sigma / (self.speed + disc.sqrt());
        Some((self.t0 + s).min(self.t_stop))
    }

    /// The same motion on another clock: its start and stop times mapped by
    /// `map`, an increasing change of clock (the world's working time moving
    /// its origin, or back to absolute time; see `clock`). Position and
    /// velocity are kept as they are.
    pub(crate) fn retimed(&self, map: impl Fn(f64) -> f64) -> Trajectory {
        let t0 = map(self.t0);
        // A disc at rest stays at rest (its stop is its start).
        let t_stop = if self.t_stop == self.t0 {
            t0
        } else {
            map(self.t_stop)
        };
        Trajectory {
            t0,
            t_stop,
            ..*self
        }
    }

    /// The same path with a different deceleration from time `t` on.
    pub(crate) fn with_alpha(&self, t: f64, alpha: f64) -> Trajectory {
        Trajectory::new(t, self.position(t), self.velocity(t), alpha)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sliding_disc_stops_after_v_squared_over_two_mu_g() {
        let (mu, g, v) = (0.3, 9.81, 2.0);
        let tr = Trajectory::new(0.0, DVec2::ZERO, DVec2::new(v, 0.0), mu * g);
        let expected = v * v / (2.0 * mu * g);
        let stop = tr.position(100.0);
        assert!((stop.x - expected).abs() <= 4.0 * f64::EPSILON * expected);
        assert_eq!(stop.y, 0.0);
        assert!((tr.stop_time() - v / (mu * g)).abs() < 1e-15);
        assert_eq!(tr.velocity(tr.stop_time()), DVec2::ZERO);
        assert_eq!(tr.stopping_distance(), expected);
    }

    #[test]
    fn position_is_continuous_at_the_stop() {
        let tr = Trajectory::new(1.0, DVec2::new(1.0, 2.0), DVec2::new(0.3, -0.4), 0.7);
        let before = tr.position(tr.stop_time() - 1e-12);
        let after = tr.position(tr.stop_time());
        assert!((before - after).length() < 1e-12);
    }

    #[test]
    fn time_at_distance_inverts_sigma() {
        let tr = Trajectory::new(0.5, DVec2::ZERO, DVec2::new(3.0, 4.0), 2.0);
        for k in 1..10 {
            let s = 0.2 * k as f64;
            let sigma = tr.sigma(s);
            let t = tr.time_at_distance(sigma).unwrap();
            assert!((t - (0.5 + s)).abs() < 1e-13, "k={k}: {t}");
        }
        assert_eq!(tr.time_at_distance(tr.stopping_distance() * 1.01), None);
    }

    #[test]
    fn frictionless_motion_is_linear_and_never_stops() {
        let tr = Trajectory::new(0.0, DVec2::new(1.0, 1.0), DVec2::new(-2.0, 0.5), 0.0);
        assert_eq!(tr.position(2.0), DVec2::new(-3.0, 2.0));
        assert_eq!(tr.velocity(1e9), DVec2::new(-2.0, 0.5));
        assert!(tr.stop_time().is_infinite());
    }

    #[test]
    fn a_retimed_motion_is_the_same_motion_on_the_new_clock() {
        let tr = Trajectory::new(3.0, DVec2::new(1.0, 2.0), DVec2::new(0.3, -0.4), 0.7);
        let shifted = tr.retimed(|t| t - 2.0);
        assert_eq!(shifted.start_time(), 1.0);
        assert_eq!(shifted.stop_time(), tr.stop_time() - 2.0);
        assert_eq!(shifted.position(1.25), tr.position(3.25));
        assert_eq!(shifted.velocity(1.25), tr.velocity(3.25));
        let rest = Trajectory::at_rest(3.0, DVec2::ZERO, 0.7).retimed(|t| t * 0.5);
        assert!(!rest.is_moving());
        let free = Trajectory::new(3.0, DVec2::ZERO, DVec2::X, 0.0).retimed(|t| t - 3.0);
        assert_eq!(free.stop_time(), f64::INFINITY);
        assert_eq!(free.position(2.0), DVec2::new(2.0, 0.0));
    }

    #[test]
    fn serialises_only_the_defining_numbers() {
        let tr = Trajectory::new(0.25, DVec2::new(1.0, 2.0), DVec2::new(3.0, 0.0), 1.5);
        let json = serde_json::to_string(&tr).unwrap();
        assert_eq!(
            json,
            r#"{"t0":0.25,"pos":[1.0,2.0],"vel":[3.0,0.0],"alpha":1.5}"#
        );
        let back: Trajectory = serde_json::from_str(&json).unwrap();
        assert_eq!(back, tr);
    }
}
