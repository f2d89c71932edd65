//! 3D Perlin noise for `no_std` (the Per_k of chen eq. 8): Ken Perlin's "improved noise"
//! (2002) with his reference permutation table, the 12 cube-edge gradients and the quintic
//! fade, returning the value together with its analytic gradient (eq. 9 needs derivatives; no
//! finite differences).
//!
//! Integer-only lattice hashing (`& 255` wrapping, so every table index is in bounds), so the
//! same corners and gradients are chosen for `f32` and [`Fx`](crate::Fx).

use crate::{Scalar, Vec3};

/// Ken Perlin's reference permutation of 0..=255.
#[rustfmt::skip]
const PERM: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,
    142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252,
    219, 203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168,
    68, 175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211,
    133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216, 80,
    73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100,
    109, 198, 173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82,
    85, 212, 207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248,
    152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108,
    110, 79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210,
    144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199,
    106, 157, 184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114,
    67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,
];

/// The 12 cube-edge gradients, padded to 16 with four of them repeated, as in the reference
/// `grad(hash & 15, …)`.
#[rustfmt::skip]
const GRAD: [[i8; 3]; 16] = [
    [1, 1, 0], [-1, 1, 0], [1, -1, 0], [-1, -1, 0],
    [1, 0, 1], [-1, 0, 1], [1, 0, -1], [-1, 0, -1],
    [0, 1, 1], [0, -1, 1], [0, 1, -1], [0, -1, -1],
    [1, 1, 0], [0, -1, 1], [-1, 1, 0], [0, -1, -1],
];

wire_type! {
    /// A noise value and its gradient with respect to the noise's argument.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Noise<S> {
        /// The value, in about [−1.04, 1.04].
        pub value: S,
        /// ∂value/∂(x, y, z).
        pub grad: Vec3<S>,
    }
}

/// The permutation table at `i` wrapped into 0..=255.
#[inline]
fn perm(i: i32) -> i32 {
    i32::from(PERM[(i & 255) as usize])
}

/// [`GRAD`] as `f32` (the same values).
const GRAD_F32: [[f32; 3]; 16] = {
    let mut t = [[0.0; 3]; 16];
    let mut i = 0;
    while i < 16 {
        let mut k = 0;
        while k < 3 {
            t[i][k] = GRAD[i][k] as f32;
            k += 1;
        }
        i += 1;
    }
    t
};

/// Component `k` of gradient `i` as a scalar: from [`GRAD_F32`] for `f32` (a load, no
/// conversion at run time), through `i32` otherwise; exact either way.
#[inline]
fn grad_component<S: Scalar>(i: usize, k: usize) -> S {
    if S::KIND == crate::ScalarKind::F32 {
        S::from_f32(GRAD_F32[i][k])
    } else {
        S::from_i32(GRAD[i][k].into())
    }
}

/// Quintic fade 6t⁵ − 15t⁴ + 10t³ and its derivative 30t²(t − 1)².
#[inline]
fn fade<S: Scalar>(t: S) -> (S, S) {
    let f = t * t * t * (t * (t * S::from_i32(6) - S::from_i32(15)) + S::from_i32(10));
    let u = t * (t - S::ONE);
    (f, S::from_i32(30) * u * u)
}

/// Integer cell and fraction in [0, 1] of one coordinate.
#[inline]
fn split<S: Scalar>(x: S) -> (i32, S) {
    let i = x.floor_i32();
    (i, (x - S::from_i32(i)).clamp_to(S::ZERO, S::ONE))
}

/// The part of Perlin noise at a point that does not depend on the seed: for each of the 8
/// corners of the lattice cell (corner `c` = (c & 1, c >> 1 & 1, c >> 2), offsets 0 or 1), its
/// hash before the seed, the offset f − c of the point from it, its weight
/// w_c = U(f_x)·V(f_y)·W(f_z) (each factor the fade s or 1 − s) and the weight's gradient.
///
/// The noise is n = Σ_c w_c (g_c · (f − c)), the nested linear interpolations of the reference
/// written out; its gradient is Σ_c w_c g_c + Σ_c ∇w_c (g_c · (f − c)). Several seeds at one
/// point (the three potentials of eq. 8) share all of this and differ only in the corner
/// gradients g_c.
#[derive(Clone, Copy, Debug)]
pub struct Lattice<S> {
    hash: [i32; 8],
    /// The offsets f − c, by axis.
    offset: [[S; 8]; 3],
    weight: [S; 8],
    /// ∇w_c, by axis.
    dweight: [[S; 8]; 3],
}

/// Σ_c a_c·b_c + e_c·f_c over the 8 corners, summed as a balanced tree (a fixed order, so the
/// same bits everywhere, and one the compiler can evaluate several corners at a time).
#[inline(always)]
fn corner_sum<S: Scalar>(a: &[S; 8], b: &[S; 8], e: &[S; 8], f: &[S; 8]) -> S {
    let mut t = [S::ZERO; 8];
    for (c, t) in t.iter_mut().enumerate() {
        *t = a[c] * b[c] + e[c] * f[c];
    }
    ((t[0] + t[1]) + (t[2] + t[3])) + ((t[4] + t[5]) + (t[6] + t[7]))
}

impl<S: Scalar> Lattice<S> {
    /// The lattice cell of `p` (lattice units: one cell per unit).
    #[inline(always)]
    pub fn new(p: Vec3<S>) -> Self {
        let ((ix, fx), (iy, fy), (iz, fz)) = (split(p.x), split(p.y), split(p.z));
        let (u, du) = fade(fx);
        let (v, dv) = fade(fy);
        let (w, dw) = fade(fz);
        // Per axis: (factor, its derivative, offset) for the corner offsets 0 and 1.
        let axis = |f: S, s: S, ds: S| [(S::ONE - s, -ds, f), (s, ds, f - S::ONE)];
        let (ax, ay, az) = (axis(fx, u, du), axis(fy, v, dv), axis(fz, w, dw));
        let px = [perm(ix), perm(ix.wrapping_add(1))];
        let mut lattice = Lattice {
            hash: [0; 8],
            offset: [[S::ZERO; 8]; 3],
            weight: [S::ZERO; 8],
            dweight: [[S::ZERO; 8]; 3],
        };
        for c in 0..8 {
            let (cx, cy, cz) = (c & 1, c >> 1 & 1, c >> 2);
            let ((a, da, ox), (b, db, oy), (e, de, oz)) = (ax[cx], ay[cy], az[cz]);
            lattice.hash[c] = perm(
                perm(px[cx].wrapping_add(iy.wrapping_add(cy as i32)))
                    .wrapping_add(iz.wrapping_add(cz as i32)),
            );
            (
                lattice.offset[0][c],
                lattice.offset[1][c],
                lattice.offset[2][c],
            ) = (ox, oy, oz);
            let be = b * e;
            lattice.weight[c] = a * be;
            lattice.dweight[0][c] = da * be;
            lattice.dweight[1][c] = a * db * e;
            lattice.dweight[2][c] = a * b * de;
        }
        lattice
    }

    /// The corners' gradients g_c for `seed`, by axis, and their dot products with the
    /// corners' offsets.
    #[inline(always)]
    fn corners(&self, seed: u8) -> ([[S; 8]; 3], [S; 8]) {
        let mut g = [[S::ZERO; 8]; 3];
        for (c, &h) in self.hash.iter().enumerate() {
            let i = (perm(h + i32::from(seed)) & 15) as usize;
            (g[0][c], g[1][c], g[2][c]) = (
                grad_component(i, 0),
                grad_component(i, 1),
                grad_component(i, 2),
            );
        }
        let o = &self.offset;
        let mut dot = [S::ZERO; 8];
        for (c, d) in dot.iter_mut().enumerate() {
            *d = g[0][c] * o[0][c] + g[1][c] * o[1][c] + g[2][c] * o[2][c];
        }
        (g, dot)
    }

    /// The gradient of the noise for `seed` with respect to the point.
    #[inline(always)]
    pub fn grad(&self, seed: u8) -> Vec3<S> {
        let (g, dot) = self.corners(seed);
        self.grad_of(&g, &dot)
    }

    /// The gradient from the corners' gradients and dot products ([`Lattice::corners`]).
    #[inline(always)]
    fn grad_of(&self, g: &[[S; 8]; 3], dot: &[S; 8]) -> Vec3<S> {
        let component = |k: usize| corner_sum(&self.weight, &g[k], &self.dweight[k], dot);
        Vec3::new(component(0), component(1), component(2))
    }

    /// The noise value and its gradient for `seed` (the corners computed once for both).
    #[inline(always)]
    pub fn noise(&self, seed: u8) -> Noise<S> {
        let (g, dot) = self.corners(seed);
        let zero = [S::ZERO; 8];
        Noise {
            value: corner_sum(&self.weight, &dot, &zero, &zero),
            grad: self.grad_of(&g, &dot),
        }
    }
}

/// Perlin noise at `p` (in lattice units: one cell per unit) for `seed`, with its analytic
/// gradient: the reference hash `P[P[P[x] + y] + z]` with the seed folded in by one more
/// permutation, `P[hash + seed]` (each seed relabels the corners' gradients, not a mere
/// translation of the noise). See [`Lattice`] for several seeds at one point.
#[inline]
pub fn perlin<S: Scalar>(p: Vec3<S>, seed: u8) -> Noise<S> {
    Lattice::new(p).noise(seed)
}

/// `n` deterministic test points in [−span, span]³ drawn from `seed` (the inputs of the noise
/// and curl tests).
#[cfg(test)]
pub(crate) fn test_points(seed: u32, n: usize, span: f32) -> impl Iterator<Item = Vec3<f32>> {
    let mut s = seed;
    let mut next = move || {
        s = crate::rand::mix32(s.wrapping_add(0x9e37_79b9));
        (s as f32 / u32::MAX as f32 * 2.0 - 1.0) * span
    };
    (0..n).map(move |_| Vec3::new(next(), next(), next()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    /// The noise tests' points, from their own seed.
    fn points(n: usize, span: f32) -> impl Iterator<Item = Vec3<f32>> {
        test_points(0x1234_5678, n, span)
    }

    #[test]
    fn permutation_is_a_bijection() {
        let mut seen = [false; 256];
        for &p in PERM.iter() {
            seen[p as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn zero_on_lattice_and_bounded() {
        for seed in [0u8, 7, 200] {
            assert_eq!(
                perlin(Vec3::<f32>::from_f32(3.0, -4.0, 17.0), seed).value,
                0.0
            );
            for p in points(2000, 50.0) {
                let n = perlin(p, seed).value;
                assert!((-1.1..=1.1).contains(&n), "noise({p:?}) = {n}");
            }
        }
    }

    #[test]
    fn analytic_gradient_matches_finite_differences() {
        let h = 1e-3f32;
        for p in points(300, 20.0) {
            let g = perlin(p, 5).grad;
            let fd = |e: Vec3<f32>| {
                (perlin(p + e * h, 5).value - perlin(p - e * h, 5).value) / (2.0 * h)
            };
            let fd = Vec3::new(
                fd(Vec3::new(1.0, 0.0, 0.0)),
                fd(Vec3::up()),
                fd(Vec3::new(0.0, 0.0, 1.0)),
            );
            assert!(
                (g - fd).length() < 2e-3,
                "at {p:?}: analytic {g:?}, numeric {fd:?}"
            );
        }
    }

    #[test]
    fn seeds_decorrelate_and_fixed_point_agrees() {
        let mut differ = 0;
        for p in points(200, 30.0) {
            let (a, b) = (perlin(p, 1).value, perlin(p, 2).value);
            if (a - b).abs() > 0.05 {
                differ += 1;
            }
            let f = perlin(p.cast::<Fx>(), 1);
            let q = perlin(p.cast::<Fx>().to_f32(), 1);
            assert!((f.value.to_f32() - q.value).abs() < 2e-4);
            assert!((f.grad.to_f32() - q.grad).length() < 2e-3);
        }
        assert!(differ > 150, "seeds too alike: {differ}/200 differ");
    }
}
