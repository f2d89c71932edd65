//! The SPH repulsion between bees and toward target particles (chen §V-B, eq. 10-11).
//!
//! Bees are capsules of radius r: kernels are evaluated at the gap s = |r_i − r_j| − 2r
//! (clamped to ≥ 0). Kernels are written on q = s/h with their constants divided by h one
//! factor at a time, so no h³, h⁴ or h⁹ is ever formed (fixed-point range).

use super::frame::BeeNeighbor;
use super::params::{BeeParams, LIMIT};
use crate::scalar::pi;
use crate::{Scalar, Vec3};

/// The capsule gap s = |r_i − r_j| − 2r of eq. 10, clamped to ≥ 0.
pub fn gap<S: Scalar>(dist: S, radius: S) -> S {
    (dist - radius - radius).max(S::ZERO)
}

/// The two kernels for one smoothing radius h, with their normalisations computed once (a
/// step evaluates them for every neighbour; the results are the same bits as [`poly6`] and
/// [`spiky_grad`]).
#[derive(Clone, Copy, Debug)]
pub struct Kernels<S> {
    h: S,
    inv_h: S,
    poly6_c: S,
    spiky_c: S,
}

impl<S: Scalar> Kernels<S> {
    /// The kernels of radius `h`.
    pub fn new(h: S) -> Self {
        Kernels {
            h,
            inv_h: S::ONE / h,
            poly6_c: S::from_f32(315.0) / (S::from_i32(64) * pi::<S>()) / h / h / h,
            spiky_c: S::from_i32(45) / pi::<S>() / h / h / h / h,
        }
    }

    /// q = s/h for 0 ≤ s < h (as s·(1/h): one division per step, not per neighbour), else
    /// `None`: the kernels vanish.
    #[inline]
    fn q(&self, s: S) -> Option<S> {
        (s >= S::ZERO && s < self.h).then(|| (s * self.inv_h).min(S::ONE))
    }

    /// Müller's poly6 kernel (eq. 10, \[61\]): W(s, h) = 315/(64π h³)·(1 − q²)³ for
    /// q = s/h < 1, else 0 (s ≥ 0).
    pub fn poly6(&self, s: S) -> S {
        let Some(q) = self.q(s) else {
            return S::ZERO;
        };
        let w = S::ONE - q * q;
        self.poly6_c * w * w * w
    }

    /// Magnitude of Desbrun's spiky-kernel gradient (eq. 11, \[61\]):
    /// |∇W_spiky(s, h)| = 45/(π h⁴)·(1 − q)² for q = s/h < 1, else 0 (s ≥ 0).
    pub fn spiky_grad(&self, s: S) -> S {
        let Some(q) = self.q(s) else {
            return S::ZERO;
        };
        let w = S::ONE - q;
        self.spiky_c * w * w
    }
}

/// [`Kernels::poly6`] for one evaluation.
pub fn poly6<S: Scalar>(s: S, h: S) -> S {
    Kernels::new(h).poly6(s)
}

/// [`Kernels::spiky_grad`] for one evaluation.
pub fn spiky_grad<S: Scalar>(s: S, h: S) -> S {
    Kernels::new(h).spiky_grad(s)
}

/// Pressure from density (§V-B: "use the density to update the pressure"):
/// p = k·max(ρ − ρ0, 0). Clamped at zero so that the force only repels.
pub fn pressure<S: Scalar>(rho: S, p: &BeeParams<S>) -> S {
    p.stiffness * (rho - p.rest_density).max(S::ZERO)
}

/// The density of eq. 10: ρ_i = Σ_j m_j W_poly6(|r_i − r_j| − 2r, h) over the bee itself (as in
/// Müller et al. \[61\]: the self term m·W(0, h) keeps ρ bounded away from 0) and the
/// neighbours and target particles (each of mass m). Limited to ±`LIMIT` so the result is
/// always a valid input for the next step.
pub fn density<S: Scalar>(
    pos: Vec3<S>,
    neighbours: &[BeeNeighbor<S>],
    targets: &[Vec3<S>],
    p: &BeeParams<S>,
) -> S {
    let others = neighbours
        .iter()
        .map(|n| n.pos)
        .chain(targets.iter().copied());
    let k = Kernels::new(p.h);
    others
        .fold(self_density(p), |rho, r_j| {
            rho + p.mass * k.poly6(gap((pos - r_j).length(), p.radius))
        })
        .min(S::from_f32(LIMIT))
}

/// The density of an isolated bee, m·W_poly6(0, h): the self term of eq. 10.
pub fn self_density<S: Scalar>(p: &BeeParams<S>) -> S {
    p.mass * poly6(S::ZERO, p.h)
}

/// The repulsion force on bee i (eq. 11), given its new density `rho_i`.
///
/// The printed eq. 11, Σ_j (p_i − p_j)/(2ρ_j) ∇W_spiky, vanishes between two bees of equal
/// pressure (e.g. any isolated pair) and so cannot give the repulsion §V-B describes. We use
/// the symmetric pressure force of Müller et al. 2003 (the paper's \[61\], which §V-B says it
/// extends):
///
/// F_i = Σ_j m_j·(p_i + p_j)/(2ρ_j)·|∇W_spiky(s_ij, h)|·r̂_ji,
///
/// with r̂_ji the unit vector from r_j to r_i (repulsive). It is antisymmetric for equal
/// densities (F_ij = −F_ji).
///
/// A neighbour's ρ_j is the density it broadcast, at least the self term m·W(0, h) (a real
/// neighbour's density includes itself; the floor keeps 1/ρ_j bounded whatever a frame says),
/// and p_j = k·max(ρ_j − ρ0, 0). Coincident positions have no direction and are skipped.
///
/// Target particles are "virtual static particles" (§V-B): bees that do not move and sense
/// nothing, so each has the density of an isolated particle, ρ_j = m·W(0, h) (the floor
/// above), and p_j = k·max(ρ_j − ρ0, 0). Their term is then m·(p_i + p_j)/(2ρ_j)·|∇W|, which
/// grows with the bee's own density ρ_i: the more particles a bee crowds, the harder they push
/// back, enough to stop a bee at the speed limit before it reaches the target's surface.
/// (Mirroring the bee's own density instead, ρ_j = ρ_i and p_j = p_i as in Akinci et al.'s
/// boundary handling, gives every particle a fixed m·k·|∇W| whatever the crowding: too weak to
/// stop a bee at full speed, which then flies through the target.)
pub fn repulsion<S: Scalar>(
    pos: Vec3<S>,
    rho_i: S,
    neighbours: &[BeeNeighbor<S>],
    targets: &[Vec3<S>],
    p: &BeeParams<S>,
) -> Vec3<S> {
    let p_i = pressure(rho_i, p);
    let floor = self_density(p);
    let k = Kernels::new(p.h);
    let from_bees = neighbours.iter().map(|n| {
        let rho_j = n.density.max(floor);
        pair_force(&k, pos, n.pos, p_i, pressure(rho_j, p), rho_j, p)
    });
    let p_floor = pressure(floor, p);
    let from_targets = targets
        .iter()
        .map(|&t| pair_force(&k, pos, t, p_i, p_floor, floor, p));
    from_bees
        .chain(from_targets)
        .fold(Vec3::zero(), |f, t| f + t)
}

/// [`density`] and then [`repulsion`] with that density, the same bits, with each offset
/// r_i − r_j and its length computed once for both (what a step needs).
pub fn interact<S: Scalar, const N: usize, const P: usize>(
    pos: Vec3<S>,
    neighbours: &heapless::Vec<BeeNeighbor<S>, N>,
    targets: &heapless::Vec<Vec3<S>, P>,
    p: &BeeParams<S>,
) -> (S, Vec3<S>) {
    interact_with(pos, neighbours, targets, p, &Kernels::new(p.h))
}

/// [`interact`] with the kernels of radius `p.h` computed beforehand.
pub fn interact_with<S: Scalar, const N: usize, const P: usize>(
    pos: Vec3<S>,
    neighbours: &heapless::Vec<BeeNeighbor<S>, N>,
    targets: &heapless::Vec<Vec3<S>, P>,
    p: &BeeParams<S>,
    k: &Kernels<S>,
) -> (S, Vec3<S>) {
    let offset = |r_j: Vec3<S>| {
        let diff = pos - r_j;
        (diff, diff.length())
    };
    let mut bees = [(Vec3::zero(), S::ZERO); N];
    for (o, n) in bees.iter_mut().zip(neighbours) {
        *o = offset(n.pos);
    }
    let mut particles = [(Vec3::zero(), S::ZERO); P];
    for (o, &t) in particles.iter_mut().zip(targets) {
        *o = offset(t);
    }
    let (bees, particles) = (&bees[..neighbours.len()], &particles[..targets.len()]);
    let floor = p.mass * k.poly6(S::ZERO);
    let rho_i = bees
        .iter()
        .chain(particles)
        .fold(floor, |rho, &(_, dist)| {
            rho + p.mass * k.poly6(gap(dist, p.radius))
        })
        .min(S::from_f32(LIMIT));
    let p_i = pressure(rho_i, p);
    let p_floor = pressure(floor, p);
    let from_bees = bees.iter().zip(neighbours).map(|(&(diff, dist), n)| {
        let rho_j = n.density.max(floor);
        term(k, diff, dist, p_i, pressure(rho_j, p), rho_j, p)
    });
    let from_targets = particles
        .iter()
        .map(|&(diff, dist)| term(k, diff, dist, p_i, p_floor, floor, p));
    let force = from_bees
        .chain(from_targets)
        .fold(Vec3::zero(), |f, t| f + t);
    (rho_i, force)
}

/// One term of [`repulsion`]: m·(p_i + p_j)/(2ρ_j)·|∇W_spiky|·r̂_ji.
fn pair_force<S: Scalar>(
    k: &Kernels<S>,
    r_i: Vec3<S>,
    r_j: Vec3<S>,
    p_i: S,
    p_j: S,
    rho_j: S,
    p: &BeeParams<S>,
) -> Vec3<S> {
    let diff = r_i - r_j;
    term(k, diff, diff.length(), p_i, p_j, rho_j, p)
}

/// [`pair_force`] from the offset `diff` = r_i − r_j and its length `dist`.
#[inline]
fn term<S: Scalar>(
    k: &Kernels<S>,
    diff: Vec3<S>,
    dist: S,
    p_i: S,
    p_j: S,
    rho_j: S,
    p: &BeeParams<S>,
) -> Vec3<S> {
    let grad = k.spiky_grad(gap(dist, p.radius));
    if dist <= S::ZERO || grad <= S::ZERO {
        return Vec3::zero();
    }
    // One division for the direction: r̂_ji = diff·(1/|diff|).
    let dir = diff * (S::ONE / dist);
    dir * (p.mass * grad * ((p_i + p_j) / (rho_j + rho_j)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    #[test]
    fn kernels_match_the_unnormalized_formulas() {
        let h = 3.0f64;
        for s in [0.0f64, 0.5, 1.0, 2.0, 2.9] {
            let w = 315.0 / (64.0 * core::f64::consts::PI * h.powi(9)) * (h * h - s * s).powi(3);
            let g = 45.0 / (core::f64::consts::PI * h.powi(6)) * (h - s).powi(2);
            assert!((poly6(s as f32, h as f32) as f64 - w).abs() < 1e-6 * w.max(1.0));
            assert!((spiky_grad(s as f32, h as f32) as f64 - g).abs() < 1e-6 * g.max(1.0));
            let wf = poly6(Fx::from_f32(s as f32), Fx::from_f32(3.0)).to_f32() as f64;
            let gf = spiky_grad(Fx::from_f32(s as f32), Fx::from_f32(3.0)).to_f32() as f64;
            assert!(
                (wf - w).abs() < 2e-4 && (gf - g).abs() < 2e-4,
                "Fx kernels at {s}"
            );
        }
        assert_eq!(poly6(3.0f32, 3.0), 0.0);
        assert_eq!(spiky_grad(7.0f32, 3.0), 0.0);
        // Tiny h in fixed point saturates instead of overflowing.
        let _ = poly6(Fx::ZERO, Fx::from_f32(0.01));
    }

    fn pair_case<S: Scalar>(tol: f32) {
        let p = BeeParams::<S>::default();
        let (a, b) = (
            Vec3::<S>::from_f32(0.3, 1.0, -0.2),
            Vec3::<S>::from_f32(1.1, 1.4, 0.5),
        );
        let rho_a = density(
            a,
            &[BeeNeighbor {
                pos: b,
                vel: Vec3::zero(),
                density: S::ZERO,
            }],
            &[],
            &p,
        );
        let rho_b = density(
            b,
            &[BeeNeighbor {
                pos: a,
                vel: Vec3::zero(),
                density: S::ZERO,
            }],
            &[],
            &p,
        );
        assert_eq!(rho_a, rho_b);
        assert!(rho_a > S::ZERO);
        let f_a = repulsion(
            a,
            rho_a,
            &[BeeNeighbor {
                pos: b,
                vel: Vec3::zero(),
                density: rho_b,
            }],
            &[],
            &p,
        );
        let f_b = repulsion(
            b,
            rho_b,
            &[BeeNeighbor {
                pos: a,
                vel: Vec3::zero(),
                density: rho_a,
            }],
            &[],
            &p,
        );
        assert!(
            (f_a + f_b).to_f32().length() <= tol,
            "F_A = {f_a:?}, F_B = {f_b:?}"
        );
        // Pushes them apart: F_A points from B to A.
        assert!(f_a.dot(a - b) > S::ZERO && f_b.dot(b - a) > S::ZERO);
    }

    /// [`interact`] is [`density`] then [`repulsion`], bit for bit.
    fn interact_case<S: Scalar>() {
        let p = BeeParams::<S>::default();
        let mut s = 0x5eed_u32;
        let mut next = move || {
            s = crate::rand::mix32(s.wrapping_add(0x9e37_79b9));
            s as f32 / u32::MAX as f32 * 6.0 - 3.0
        };
        for _ in 0..50 {
            let me = Vec3::<S>::from_f32(next(), next(), next());
            let mut nb: heapless::Vec<BeeNeighbor<S>, 6> = heapless::Vec::new();
            let mut tg: heapless::Vec<Vec3<S>, 5> = heapless::Vec::new();
            for _ in 0..6 {
                let _ = nb.push(BeeNeighbor {
                    pos: Vec3::from_f32(next(), next(), next()),
                    vel: Vec3::zero(),
                    density: S::from_f32(next().abs() * 0.1),
                });
            }
            for _ in 0..5 {
                let _ = tg.push(Vec3::from_f32(next(), next(), next()));
            }
            let rho = density(me, &nb, &tg, &p);
            assert_eq!(
                interact(me, &nb, &tg, &p),
                (rho, repulsion(me, rho, &nb, &tg, &p))
            );
        }
    }

    #[test]
    fn interact_is_density_then_repulsion() {
        interact_case::<f32>();
        interact_case::<Fx>();
    }

    #[test]
    fn two_bees_repel_equal_and_opposite() {
        pair_case::<f32>(1e-6);
        pair_case::<Fx>(1e-4);
    }

    #[test]
    fn targets_repel_and_degenerate_terms_are_skipped() {
        let p = BeeParams::<f32>::default();
        let me = Vec3::new(0.0, 0.0, 0.0);
        let target = [Vec3::new(1.0, 0.0, 0.0)];
        let rho = density(me, &[], &target, &p);
        let f = repulsion(me, rho, &[], &target, &p);
        assert!(f.x < 0.0 && f.y == 0.0 && f.z == 0.0);
        // Coincident and out-of-range neighbours give nothing.
        let nb = |x: f32, density: f32| BeeNeighbor {
            pos: Vec3::new(x, 0.0, 0.0),
            vel: Vec3::zero(),
            density,
        };
        assert_eq!(
            repulsion(me, 1.0, &[nb(0.0, 1.0), nb(3.6, 1.0)], &[], &p),
            Vec3::zero()
        );
        // A neighbour that reports ρ_j = 0 (or a tiny ρ_j near the kernel edge) is floored at
        // the self density: finite and repulsive, no blow-up.
        let silent = repulsion(me, 1.0, &[nb(1.0, 0.0)], &[], &p);
        let floored = repulsion(me, 1.0, &[nb(1.0, self_density(&p))], &[], &p);
        assert!(silent.x < 0.0 && silent == floored);
        let edge = repulsion(me, 1.0, &[nb(2.0 * p.radius + 2.999, 1e-9)], &[], &p);
        assert!(edge.x.is_finite() && edge.x.abs() < 1.0);
        // Density: the self term alone when nothing is near; overlapping capsules: gap clamped
        // to 0, maximum kernel.
        assert_eq!(density(me, &[nb(3.6, 1.0)], &[], &p), self_density(&p));
        assert_eq!(density(me, &[nb(0.4, 1.0)], &[], &p), 2.0 * poly6(0.0, 3.0));
    }
}
