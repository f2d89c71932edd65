//! The repulsion value g of wang2014 eq. 6: Wyvill's "soft object" bell.

use crate::Scalar;

/// h(r) of eq. 6, the repulsion value g at a signed distance r = φ/(2a) from the nearest
/// obstacle surface (in units of the repulsion reach 2a):
///
/// h(r) = 1 for r < 0 (inside an obstacle), 1 − 4/9 r⁶ + 17/9 r⁴ − 22/9 r² for 0 ≤ r ≤ 1,
/// 0 for r > 1.
///
/// Monotone decreasing on [0, 1] (h' = r/9·(−24r⁴ + 68r² − 44) < 0), continuous at both ends
/// (h(0) = 1, h(1) = 0). Evaluated in Horner form on r².
pub fn bell<S: Scalar>(r: S) -> S {
    if r < S::ZERO {
        return S::ONE;
    }
    if r > S::ONE {
        return S::ZERO;
    }
    let q = r * r;
    let poly =
        S::from_f32(-22.0 / 9.0) + q * (S::from_f32(17.0 / 9.0) + q * S::from_f32(-4.0 / 9.0));
    // Clamped: rounding must not leave [0, 1] near the ends.
    (S::ONE + q * poly).clamp_to(S::ZERO, S::ONE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    /// W-T2: h = 1 inside, h(0) = 1, h(1) = 0, 0 beyond, monotone decreasing on [0, 1],
    /// continuous at 0 and 1, and the fixed-point bell within 1e-4 of the f32 one.
    #[test]
    fn the_bell_of_eq_6() {
        assert_eq!(bell(-0.5f32), 1.0);
        assert_eq!(bell(0.0f32), 1.0);
        assert!(bell(1.0f32).abs() < 1e-6);
        assert_eq!(bell(1.5f32), 0.0);
        assert!((bell(1e-4f32) - 1.0).abs() < 1e-6);
        assert!(bell(1.0f32 - 1e-4).abs() < 1e-6);
        let mut last = 1.0f32;
        for i in 1..=1000 {
            let r = i as f32 / 1000.0;
            let h = bell(r);
            assert!(h <= last, "h({r}) = {h} > {last}");
            let exact = 1.0 - 4.0 / 9.0 * r.powi(6) + 17.0 / 9.0 * r.powi(4) - 22.0 / 9.0 * r * r;
            assert!((h - exact).abs() < 1e-6, "h({r}) = {h}, want {exact}");
            let fx = bell(Fx::from_f32(r)).to_f32();
            assert!((fx - h).abs() < 1e-4, "Fx h({r}) = {fx}, f32 {h}");
            last = h;
        }
        assert_eq!(bell(Fx::from_f32(-1.0)), Fx::ONE);
        assert_eq!(bell(Fx::from_f32(2.0)), Fx::ZERO);
    }
}
