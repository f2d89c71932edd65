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

/// The gradient index of lattice corner `(x, y, z)` for `seed`: the reference hash
/// `P[P[P[x] + y] + z]`, with the seed folded in by one more permutation, `P[hash + seed]`, so
/// each seed relabels the corners' gradients (not a mere translation of the noise).
#[inline]
fn corner_gradient(seed: u8, x: i32, y: i32, z: i32) -> [i8; 3] {
    let h = perm(perm(perm(perm(x).wrapping_add(y)).wrapping_add(z)) + i32::from(seed));
    GRAD[(h & 15) as usize]
}

/// Quintic fade 6t⁵ − 15t⁴ + 10t³ and its derivative 30t²(t − 1)².
#[inline]
fn fade<S: Scalar>(t: S) -> (S, S) {
    let f = t * t * t * (t * (t * S::from_i32(6) - S::from_i32(15)) + S::from_i32(10));
    let u = t * (t - S::ONE);
    (f, S::from_i32(30) * u * u)
}

/// Linear interpolation of two (value, gradient) pairs with weight `w` whose gradient is `dw`:
/// the product rule gives ∇(a + w(b − a)) = ∇a + w(∇b − ∇a) + (b − a)∇w.
#[inline]
fn lerp<S: Scalar>(a: Noise<S>, b: Noise<S>, w: S, dw: Vec3<S>) -> Noise<S> {
    let dv = b.value - a.value;
    Noise {
        value: a.value + w * dv,
        grad: a.grad + (b.grad - a.grad) * w + dw * dv,
    }
}

/// Integer cell and fraction in [0, 1] of one coordinate.
#[inline]
fn split<S: Scalar>(x: S) -> (i32, S) {
    let i = x.floor_i32();
    (i, (x - S::from_i32(i)).clamp_to(S::ZERO, S::ONE))
}

/// Perlin noise at `p` (in lattice units: one cell per unit) for `seed`, with its analytic
/// gradient.
pub fn perlin<S: Scalar>(p: Vec3<S>, seed: u8) -> Noise<S> {
    let ((ix, fx), (iy, fy), (iz, fz)) = (split(p.x), split(p.y), split(p.z));
    // Contribution g·(f − corner) of one corner; its gradient is g.
    let corner = |cx: i32, cy: i32, cz: i32| {
        let g = corner_gradient(
            seed,
            ix.wrapping_add(cx),
            iy.wrapping_add(cy),
            iz.wrapping_add(cz),
        );
        let g = Vec3::new(
            S::from_i32(g[0].into()),
            S::from_i32(g[1].into()),
            S::from_i32(g[2].into()),
        );
        let d = Vec3::new(
            fx - S::from_i32(cx),
            fy - S::from_i32(cy),
            fz - S::from_i32(cz),
        );
        Noise {
            value: g.dot(d),
            grad: g,
        }
    };
    let (u, du) = fade(fx);
    let (v, dv) = fade(fy);
    let (w, dw) = fade(fz);
    let (ex, ey, ez) = (
        Vec3::new(du, S::ZERO, S::ZERO),
        Vec3::new(S::ZERO, dv, S::ZERO),
        Vec3::new(S::ZERO, S::ZERO, dw),
    );
    let x = |cy, cz| lerp(corner(0, cy, cz), corner(1, cy, cz), u, ex);
    let y0 = lerp(x(0, 0), x(1, 0), v, ey);
    let y1 = lerp(x(0, 1), x(1, 1), v, ey);
    lerp(y0, y1, w, ez)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    /// A small deterministic generator for test points.
    fn points(n: usize, span: f32) -> impl Iterator<Item = Vec3<f32>> {
        let mut s = 0x1234_5678u32;
        let mut next = move || {
            s = crate::rand::mix32(s.wrapping_add(0x9e37_79b9));
            (s as f32 / u32::MAX as f32 * 2.0 - 1.0) * span
        };
        (0..n).map(move |_| Vec3::new(next(), next(), next()))
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
