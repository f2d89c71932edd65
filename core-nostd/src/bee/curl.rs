//! The curl-noise force (chen §V-A, eq. 8-9).

use super::perlin::{Lattice, Noise};
use crate::{Scalar, Vec3};

/// The three seeds of Per_1, Per_2, Per_3 (eq. 8: "a Perlin noise function with three random
/// seeds"). Ours: any three distinct bytes.
pub const SEEDS: [u8; 3] = [17, 101, 211];

/// The potential ψ of eq. 8 and its derivatives: component k is ψ_k(r) = ε·Per_k(r/L).
///
/// Eq. 8 prints ψ = (Per_1(r)/L, Per_2(r)/L, Per_3(r)/L)·ε while calling L "the edge length of
/// a unit grid". We read it as noise on a lattice of edge L, i.e. Per_k evaluated at r/L; the
/// 1/L of eq. 8 then appears in the derivatives through the chain rule,
/// ∂ψ_k/∂r = (ε/L)·∇Per_k(r/L), which is what eq. 9 uses. The curl magnitude thus scales as
/// ε/L: a smaller L gives finer, more abrupt turns (§VI).
#[inline]
pub fn potential<S: Scalar>(pos: Vec3<S>, grid_edge: S, epsilon: S) -> [Noise<S>; 3] {
    let lattice = Lattice::new(lattice_point(pos, grid_edge));
    let scale = epsilon / grid_edge;
    SEEDS.map(|seed| {
        let n = lattice.noise(seed);
        Noise {
            value: epsilon * n.value,
            grad: n.grad * scale,
        }
    })
}

/// r/L: the point in lattice units.
#[inline]
fn lattice_point<S: Scalar>(pos: Vec3<S>, grid_edge: S) -> Vec3<S> {
    Vec3::new(pos.x / grid_edge, pos.y / grid_edge, pos.z / grid_edge)
}

/// The curl-noise force of eq. 9, F_curl = ∇ × ψ:
/// (∂ψ_z/∂y − ∂ψ_y/∂z, ∂ψ_x/∂z − ∂ψ_z/∂x, ∂ψ_y/∂x − ∂ψ_x/∂y), with ψ = (ψ_1, ψ_2, ψ_3) from
/// [`potential`] and analytic derivatives. Divergence-free by construction (§V-A). The three
/// potentials share one lattice cell ([`Lattice`]); their values are not needed.
#[inline]
pub fn curl_force<S: Scalar>(pos: Vec3<S>, grid_edge: S, epsilon: S) -> Vec3<S> {
    let lattice = Lattice::new(lattice_point(pos, grid_edge));
    let scale = epsilon / grid_edge;
    let [px, py, pz] = SEEDS.map(|seed| lattice.grad(seed) * scale);
    Vec3::new(pz.y - py.z, px.z - pz.x, py.x - px.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    /// The curl tests' points, from their own seed.
    fn points(n: usize, span: f32) -> impl Iterator<Item = Vec3<f32>> {
        crate::bee::perlin::test_points(0xdead_beef, n, span)
    }

    /// Central differences of F_curl (f32, step 1e-3, 100 points in [−20, 20]³) give a
    /// divergence that is only rounding noise. Bound: |div| ≤ 1e-2·ε/L² (= 2.3e-3 here;
    /// observed ≤ 1.3e-3), where ε/L² is the scale of each partial derivative ∂F_i/∂x_i. Those
    /// are typically 0.1-2·ε/L² and do not vanish on their own: also checked, the sum cancels
    /// them by a factor of 100 or more on average.
    #[test]
    fn curl_noise_is_divergence_free() {
        let (l, eps, h) = (2.7f32, 1.7f32, 1e-3f32);
        let scale = eps / (l * l);
        let f = |p: Vec3<f32>| curl_force(p, l, eps);
        let (mut sum_div, mut sum_terms) = (0.0f32, 0.0f32);
        for p in points(100, 20.0) {
            let dx =
                (f(p + Vec3::new(h, 0.0, 0.0)).x - f(p - Vec3::new(h, 0.0, 0.0)).x) / (2.0 * h);
            let dy =
                (f(p + Vec3::new(0.0, h, 0.0)).y - f(p - Vec3::new(0.0, h, 0.0)).y) / (2.0 * h);
            let dz =
                (f(p + Vec3::new(0.0, 0.0, h)).z - f(p - Vec3::new(0.0, 0.0, h)).z) / (2.0 * h);
            let div = dx + dy + dz;
            assert!(
                div.abs() <= 1e-2 * scale,
                "div F_curl at {p:?} = {div} (terms {dx}, {dy}, {dz})"
            );
            sum_div += div.abs();
            sum_terms += dx.abs() + dy.abs() + dz.abs();
        }
        assert!(
            sum_terms > 100.0 * sum_div,
            "terms {sum_terms}, divergence {sum_div}"
        );
    }

    #[test]
    fn curl_matches_definition_and_fixed_point() {
        let (l, eps) = (2.2f32, 2.0f32);
        for p in points(50, 40.0) {
            let [a, b, c] = potential(p, l, eps);
            let want = Vec3::new(
                c.grad.y - b.grad.z,
                a.grad.z - c.grad.x,
                b.grad.x - a.grad.y,
            );
            assert_eq!(curl_force(p, l, eps), want);
            // ψ_k = ε Per_k(r/L).
            assert_eq!(
                a.value,
                eps * crate::bee::perlin::perlin(Vec3::new(p.x / l, p.y / l, p.z / l), SEEDS[0])
                    .value
            );
            let fx = curl_force(p.cast::<Fx>(), Fx::from_f32(l), Fx::from_f32(eps)).to_f32();
            let fl = curl_force(p.cast::<Fx>().to_f32(), l, eps);
            assert!((fx - fl).length() < 5e-3, "Fx {fx:?} vs f32 {fl:?}");
        }
    }
}
