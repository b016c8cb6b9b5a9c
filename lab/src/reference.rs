//! The yardstick: the model of `model.md` computed again, in 320-bit
//! arithmetic, by code written from the formulas alone (none of it is the
//! engine's). Discs slide with constant deceleration `mu g`, hit each
//! other, points and lines (ends of rays and segments act as points) with
//! restitution impulses, and fall off a Chapaev board when their centre
//! leaves it. Every contact time is the first approaching root of the
//! exact contact function on each piece of the two trajectories (moving,
//! then at rest), found by [`hp::roots_from`]. Events are picked by a plain
//! scan of every body's next event; only a conservative `f64` test on the
//! bodies' whole paths (with a margin) skips pairs that cannot meet. It is
//! slow, and only for measuring.

use crate::hp::{self, big, zero, F};
use crate::outcome::{BodyEnd, Outcome};
use crate::scenes::{Board, Case};
use engine::LineKind;
use glam::DVec2;
use std::time::Instant;

type V = [F; 2];

fn add(a: &V, b: &V) -> V {
    [a[0].clone() + &b[0], a[1].clone() + &b[1]]
}
fn sub(a: &V, b: &V) -> V {
    [a[0].clone() - &b[0], a[1].clone() - &b[1]]
}
fn scale(a: &V, k: &F) -> V {
    [a[0].clone() * k, a[1].clone() * k]
}
fn dot(a: &V, b: &V) -> F {
    a[0].clone() * &b[0] + a[1].clone() * &b[1]
}
fn vbig(p: DVec2) -> V {
    [big(p.x), big(p.y)]
}
fn vf64(p: &V) -> DVec2 {
    DVec2::new(hp::to_f64(&p[0]), hp::to_f64(&p[1]))
}
fn is_zero(v: &V) -> bool {
    v[0] == F::ZERO && v[1] == F::ZERO
}

/// A disc's trajectory since its last event.
#[derive(Clone)]
struct Body {
    id: u64,
    r: F,
    inv_m: F,
    e: F,
    alpha: F,
    tau: F,
    p: V,
    u: V,
    /// Unit direction of motion (zero at rest).
    d: V,
    /// When it stops (`None`: never, it moves without friction or rests).
    stop: Option<F>,
    removed: bool,
    /// The whole remaining path in `f64`, for the conservative pair filter.
    path: (DVec2, DVec2),
}

/// Position, velocity and acceleration at one time.
struct State {
    p: V,
    v: V,
    a: V,
}

impl Body {
    fn moving(&self) -> bool {
        !is_zero(&self.u)
    }

    fn state(&self, t: &F) -> State {
        if !self.moving() {
            return State {
                p: self.p.clone(),
                v: [zero(), zero()],
                a: [zero(), zero()],
            };
        }
        let mut s = t.clone() - &self.tau;
        let mut stopped = false;
        if let Some(ts) = &self.stop {
            if t >= ts {
                s = ts.clone() - &self.tau;
                stopped = true;
            }
        }
        let half_a = self.alpha.clone() * big(0.5);
        let p = sub(
            &add(&self.p, &scale(&self.u, &s)),
            &scale(&self.d, &(half_a * &s * &s)),
        );
        if stopped {
            return State {
                p,
                v: [zero(), zero()],
                a: [zero(), zero()],
            };
        }
        let acc = scale(&self.d, &(-self.alpha.clone()));
        State {
            v: add(&self.u, &scale(&acc, &s)),
            p,
            a: acc,
        }
    }

    /// Starts a new trajectory at `t` from `p` with velocity `u`.
    fn restart(&mut self, t: &F, p: V, u: V, until: f64) {
        let speed = hp::sqrt(&dot(&u, &u));
        self.tau = t.clone();
        self.p = p;
        if speed == F::ZERO {
            self.u = [zero(), zero()];
            self.d = [zero(), zero()];
            self.stop = None;
        } else {
            self.d = scale(&u, &(big(1.0) / &speed));
            self.u = u;
            self.stop = (self.alpha > F::ZERO).then(|| t.clone() + speed / &self.alpha);
        }
        let start = vf64(&self.p);
        let end = match &self.stop {
            Some(ts) => vf64(&self.state(ts).p),
            None if self.moving() => {
                let horizon = (until - hp::to_f64(t)).max(0.0);
                start + vf64(&self.u) * horizon
            }
            None => start,
        };
        self.path = (start, end);
    }
}

/// A solid line in high precision.
struct LineHp {
    a: V,
    tangent: V,
    n: V,
    c: F,
    lo: Option<F>,
    hi: Option<F>,
    ends: Vec<V>,
}

impl LineHp {
    fn new(a: DVec2, b: DVec2, kind: LineKind) -> LineHp {
        let (a, b) = (vbig(a), vbig(b));
        let t = sub(&b, &a);
        let len = hp::sqrt(&dot(&t, &t));
        let tangent = scale(&t, &(big(1.0) / &len));
        let n = [-tangent[1].clone(), tangent[0].clone()];
        let c = -dot(&n, &a);
        let (lo, hi, ends) = match kind {
            LineKind::Line => (None, None, vec![]),
            LineKind::Ray => (Some(zero()), None, vec![a.clone()]),
            LineKind::Segment => (Some(zero()), Some(len), vec![a.clone(), b]),
        };
        LineHp {
            a,
            tangent,
            n,
            c,
            lo,
            hi,
            ends,
        }
    }

    fn covers(&self, p: &V) -> bool {
        let along = dot(&sub(p, &self.a), &self.tangent);
        self.lo.as_ref().is_none_or(|l| along >= *l) && self.hi.as_ref().is_none_or(|h| along <= *h)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    None,
    Pair(usize),
    Line(usize),
    Point(usize, usize),
    FixedPoint(usize),
    Exit,
}

/// Distance between segments `[a0, a1]` and `[b0, b1]` (for the filter).
fn segment_distance(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2) -> f64 {
    fn point_seg(p: DVec2, a: DVec2, b: DVec2) -> f64 {
        let d = b - a;
        let l = d.length_squared();
        let t = if l > 0.0 {
            ((p - a).dot(d) / l).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a + d * t - p).length()
    }
    let (da, db) = (a1 - a0, b1 - b0);
    let den = da.perp_dot(db);
    if den != 0.0 {
        let s = (b0 - a0).perp_dot(db) / den;
        let t = (b0 - a0).perp_dot(da) / den;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            return 0.0;
        }
    }
    point_seg(a0, b0, b1)
        .min(point_seg(a1, b0, b1))
        .min(point_seg(b0, a0, a1))
        .min(point_seg(b1, a0, a1))
}

/// The reference computation of one case.
pub struct Reference {
    now: F,
    until: f64,
    bodies: Vec<Body>,
    lines: Vec<LineHp>,
    points: Vec<V>,
    board: Option<(V, V)>,
    next: Vec<(Option<F>, Kind)>,
    collisions: u64,
}

/// Below this fraction of `S^2` a contact function counts as touching now.
fn touch_tol(s2: &F) -> F {
    s2.clone() * hp::pow2(-200)
}

/// The first root `>= 0` (and `< end`) of `a` where `a` decreases, or 0 if
/// `a(0)` is at most `tol` while decreasing.
fn first_approach(a: &[F], end: Option<&F>, tol: &F) -> Option<F> {
    let d: Vec<F> = (1..a.len()).map(|i| a[i].clone() * big(i as f64)).collect();
    if a[0] <= *tol && d[0] < F::ZERO {
        return Some(zero());
    }
    hp::roots_from(a, &zero(), end)
        .into_iter()
        .find(|r| hp::eval(&d, r) < F::ZERO)
}

impl Reference {
    /// Sets up the computation of `case` (validated by the caller).
    pub fn new(case: &Case) -> Reference {
        let g = big(case.scene.g);
        let t0 = big(case.scene.t);
        let bodies = case
            .scene
            .bodies
            .iter()
            .map(|b| {
                let mut body = Body {
                    id: b.id.0,
                    r: big(b.radius),
                    inv_m: big(1.0) / big(b.mass),
                    e: big(b.restitution),
                    alpha: big(b.mu) * &g,
                    tau: t0.clone(),
                    p: vbig(b.pos),
                    u: vbig(b.vel),
                    d: [zero(), zero()],
                    stop: None,
                    removed: false,
                    path: (b.pos, b.pos),
                };
                let (p, u) = (body.p.clone(), body.u.clone());
                body.restart(&t0, p, u, case.until);
                body
            })
            .collect::<Vec<_>>();
        let lines = case
            .scene
            .lines
            .iter()
            .filter(|l| !l.sensor)
            .map(|l| LineHp::new(l.a, l.b, l.kind))
            .collect();
        let points = case.scene.points.iter().map(|p| vbig(p.pos)).collect();
        let board = case.board().map(|b: Board| (vbig(b.lo), vbig(b.hi)));
        let n = bodies.len();
        let mut r = Reference {
            now: t0,
            until: case.until,
            bodies,
            lines,
            points,
            board,
            next: vec![(None, Kind::None); n],
            collisions: 0,
        };
        for i in 0..n {
            r.predict(i);
        }
        r
    }

    /// First approaching contact of bodies `i` and `j` from now.
    fn pair_time(&self, i: usize, j: usize) -> Option<F> {
        let (bi, bj) = (&self.bodies[i], &self.bodies[j]);
        if !bi.moving() && !bj.moving() {
            return None;
        }
        let s = bi.r.clone() + &bj.r;
        let sf = hp::to_f64(&s);
        let margin = 1e-9 * (sf + bi.path.0.abs().max_element() + bj.path.0.abs().max_element());
        if segment_distance(bi.path.0, bi.path.1, bj.path.0, bj.path.1) > sf + margin {
            return None;
        }
        let s2 = s.clone() * &s;
        let tol = touch_tol(&s2);
        let mut stops: Vec<F> = [&bi.stop, &bj.stop]
            .into_iter()
            .flatten()
            .filter(|t| **t > self.now)
            .cloned()
            .collect();
        stops.sort();
        let mut t0 = self.now.clone();
        let mut k = 0;
        loop {
            let t1 = stops.get(k).cloned();
            let (si, sj) = (bi.state(&t0), bj.state(&t0));
            if is_zero(&si.v) && is_zero(&sj.v) {
                return None;
            }
            let dp = sub(&si.p, &sj.p);
            let dv = sub(&si.v, &sj.v);
            let da = sub(&si.a, &sj.a);
            let c = [
                dot(&dp, &dp) - &s2,
                dot(&dp, &dv) * big(2.0),
                dot(&dv, &dv) + dot(&dp, &da),
                dot(&dv, &da),
                dot(&da, &da) * big(0.25),
            ];
            let end = t1.as_ref().map(|t| t.clone() - &t0);
            if let Some(r) = first_approach(&c, end.as_ref(), &tol) {
                return Some(t0 + r);
            }
            match t1 {
                Some(t) => t0 = t,
                None => return None,
            }
            k += 1;
        }
    }

    /// First approaching contact of moving body `i` with the fixed point `q`
    /// at centre distance `s`.
    fn point_time(&self, i: usize, q: &V, s: &F) -> Option<F> {
        let b = &self.bodies[i];
        let st = b.state(&self.now);
        let dp = sub(&st.p, q);
        let s2 = s.clone() * s;
        let c = [
            dot(&dp, &dp) - &s2,
            dot(&dp, &st.v) * big(2.0),
            dot(&st.v, &st.v) + dot(&dp, &st.a),
            dot(&st.v, &st.a),
            dot(&st.a, &st.a) * big(0.25),
        ];
        let end = b.stop.as_ref().map(|t| t.clone() - &self.now);
        first_approach(&c, end.as_ref(), &touch_tol(&s2)).map(|r| self.now.clone() + r)
    }

    /// First approaching contact of moving body `i` with the straight part
    /// of line `k`.
    fn line_time(&self, i: usize, k: usize) -> Option<F> {
        let b = &self.bodies[i];
        let l = &self.lines[k];
        let st = b.state(&self.now);
        let h = dot(&l.n, &st.p) + &l.c;
        let rate = dot(&l.n, &st.v);
        let side = if h > F::ZERO || (h == F::ZERO && rate < F::ZERO) {
            big(1.0)
        } else {
            big(-1.0)
        };
        let c = [
            side.clone() * &h - &b.r,
            side.clone() * &rate,
            side * dot(&l.n, &st.a) * big(0.5),
        ];
        let end = b.stop.as_ref().map(|t| t.clone() - &self.now);
        let tol = b.r.clone() * hp::pow2(-200);
        let r = first_approach(&c, end.as_ref(), &tol)?;
        let t = self.now.clone() + r;
        l.covers(&b.state(&t).p).then_some(t)
    }

    /// When moving body `i`'s centre leaves the board.
    fn exit_time(&self, i: usize) -> Option<F> {
        let (lo, hi) = self.board.as_ref()?;
        let b = &self.bodies[i];
        let st = b.state(&self.now);
        let end = b.stop.as_ref().map(|t| t.clone() - &self.now);
        let mut best: Option<F> = None;
        for k in 0..2 {
            let half_a = st.a[k].clone() * big(0.5);
            // x - lo decreasing through 0, and hi - x decreasing through 0.
            let below = [st.p[k].clone() - &lo[k], st.v[k].clone(), half_a.clone()];
            let above = [hi[k].clone() - &st.p[k], -st.v[k].clone(), -half_a];
            for c in [below, above] {
                if c[0] < F::ZERO {
                    return Some(self.now.clone());
                }
                if let Some(r) = first_approach(&c, end.as_ref(), &F::ZERO) {
                    if r > F::ZERO && best.as_ref().is_none_or(|x| r < *x) {
                        best = Some(r);
                    }
                }
            }
        }
        best.map(|r| self.now.clone() + r)
    }

    fn predict(&mut self, i: usize) {
        let mut best: (Option<F>, Kind) = (None, Kind::None);
        let offer = |t: Option<F>, k: Kind, best: &mut (Option<F>, Kind)| {
            if let Some(t) = t {
                if best.0.as_ref().is_none_or(|b| t < *b) {
                    *best = (Some(t), k);
                }
            }
        };
        if self.bodies[i].removed {
            self.next[i] = best;
            return;
        }
        for j in 0..self.bodies.len() {
            if j != i && !self.bodies[j].removed {
                offer(self.pair_time(i, j), Kind::Pair(j), &mut best);
            }
        }
        if self.bodies[i].moving() {
            let r = self.bodies[i].r.clone();
            for k in 0..self.lines.len() {
                offer(self.line_time(i, k), Kind::Line(k), &mut best);
                for e in 0..self.lines[k].ends.len() {
                    let q = self.lines[k].ends[e].clone();
                    offer(self.point_time(i, &q, &r), Kind::Point(k, e), &mut best);
                }
            }
            for k in 0..self.points.len() {
                let q = self.points[k].clone();
                offer(self.point_time(i, &q, &r), Kind::FixedPoint(k), &mut best);
            }
            offer(self.exit_time(i), Kind::Exit, &mut best);
        }
        self.next[i] = best;
    }

    /// Reflects body `i` off a fixed normal `n` at time `t`.
    fn bounce(&mut self, i: usize, t: &F, n: V) {
        let st = self.bodies[i].state(t);
        let w = dot(&st.v, &n);
        if w < F::ZERO {
            let k = (big(1.0) + &self.bodies[i].e) * w;
            let v = sub(&st.v, &scale(&n, &k));
            self.bodies[i].restart(t, st.p, v, self.until);
        } else {
            self.bodies[i].restart(t, st.p, st.v, self.until);
        }
    }

    fn unit(v: V) -> V {
        let l = hp::sqrt(&dot(&v, &v));
        if l == F::ZERO {
            v
        } else {
            scale(&v, &(big(1.0) / l))
        }
    }

    /// Runs to `until` or `max_events` events.
    pub fn run(mut self, max_events: u64) -> Outcome {
        let start = Instant::now();
        let until = big(self.until);
        let mut events = 0u64;
        let mut capped = false;
        loop {
            let mut pick: Option<(usize, F)> = None;
            for (i, (t, _)) in self.next.iter().enumerate() {
                if let Some(t) = t {
                    if pick.as_ref().is_none_or(|(_, b)| t < b) {
                        pick = Some((i, t.clone()));
                    }
                }
            }
            let Some((i, t)) = pick else { break };
            if t > until {
                break;
            }
            if events >= max_events {
                capped = true;
                break;
            }
            events += 1;
            self.now = t.clone();
            let kind = self.next[i].1;
            let mut involved = vec![i];
            match kind {
                Kind::None => {}
                Kind::Pair(j) => {
                    involved.push(j);
                    let (si, sj) = (self.bodies[i].state(&t), self.bodies[j].state(&t));
                    let n = Self::unit(sub(&si.p, &sj.p));
                    let w = dot(&sub(&si.v, &sj.v), &n);
                    let (mut vi, mut vj) = (si.v, sj.v);
                    if w < F::ZERO {
                        let (bi, bj) = (&self.bodies[i], &self.bodies[j]);
                        let e = if bi.e < bj.e { &bi.e } else { &bj.e };
                        let jmp = -(big(1.0) + e) * w / (bi.inv_m.clone() + &bj.inv_m);
                        vi = add(&vi, &scale(&n, &(jmp.clone() * &bi.inv_m)));
                        vj = sub(&vj, &scale(&n, &(jmp * &bj.inv_m)));
                    }
                    self.bodies[i].restart(&t, si.p, vi, self.until);
                    self.bodies[j].restart(&t, sj.p, vj, self.until);
                    self.collisions += 1;
                }
                Kind::Line(k) => {
                    let p = self.bodies[i].state(&t).p;
                    let l = &self.lines[k];
                    let h = dot(&l.n, &p) + &l.c;
                    let n = if h >= F::ZERO {
                        l.n.clone()
                    } else {
                        scale(&l.n, &big(-1.0))
                    };
                    self.bounce(i, &t, n);
                    self.collisions += 1;
                }
                Kind::Point(k, e) => {
                    let p = self.bodies[i].state(&t).p;
                    let n = Self::unit(sub(&p, &self.lines[k].ends[e]));
                    self.bounce(i, &t, n);
                    self.collisions += 1;
                }
                Kind::FixedPoint(k) => {
                    let p = self.bodies[i].state(&t).p;
                    let n = Self::unit(sub(&p, &self.points[k]));
                    self.bounce(i, &t, n);
                    self.collisions += 1;
                }
                Kind::Exit => {
                    let st = self.bodies[i].state(&t);
                    self.bodies[i].restart(&t, st.p, [zero(), zero()], self.until);
                    self.bodies[i].removed = true;
                }
            }
            let mut again: Vec<usize> = involved.clone();
            for (k, (_, kind)) in self.next.iter().enumerate() {
                if let Kind::Pair(j) = kind {
                    if involved.contains(j) && !again.contains(&k) {
                        again.push(k);
                    }
                }
            }
            for k in again {
                self.predict(k);
            }
        }
        let bodies = {
            let mut v: Vec<BodyEnd> = self
                .bodies
                .iter()
                .map(|b| {
                    let st = b.state(&until);
                    BodyEnd {
                        id: b.id,
                        pos: vf64(&st.p),
                        vel: vf64(&st.v),
                        removed: b.removed,
                    }
                })
                .collect();
            v.sort_by_key(|b| b.id);
            v
        };
        Outcome {
            bodies,
            collisions: self.collisions,
            capped,
            max_overlap: 0.0,
            secs: start.elapsed().as_secs_f64(),
        }
    }
}

/// Computes `case` with the reference model.
pub fn run(case: &Case) -> Outcome {
    Reference::new(case).run(case.max_events)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes;

    #[test]
    fn galperin_three_digits_gives_314_collisions() {
        let out = run(&scenes::galperin(3));
        assert_eq!(out.collisions, 314);
        assert!(!out.capped);
    }

    #[test]
    fn head_on_equal_masses_striker_stops_target_slides_the_closed_form_distance() {
        let case = scenes::cradle();
        let out = run(&case);
        // Striker 1.5 m/s, mu g = 0.3 * 9.81: reaches the row at 0.2 - 0.032.
        let a = 0.3 * 9.81;
        let v_hit2 = 1.5f64 * 1.5 - 2.0 * a * (0.2 - 0.032);
        let last = out.bodies.iter().find(|b| b.id == 5).unwrap();
        let expected_x = 0.2 + 3.0 * 0.032 + v_hit2 / (2.0 * a);
        assert!((last.pos.x - expected_x).abs() < 1e-12, "{}", last.pos.x);
        for b in &out.bodies[..4] {
            assert!(b.vel.length() < 1e-12);
        }
        assert_eq!(out.collisions, 4);
    }

    #[test]
    fn fast_tiny_disc_bounces_off_the_segment() {
        let out = run(&scenes::fast_tiny());
        assert_eq!(out.collisions, 1);
        assert!(out.bodies[0].pos.x < 0.5);
    }
}
