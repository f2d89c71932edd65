//! ren2016's temperature extension (Eq. 1): how many insects per unit volume a swarm holds at
//! the environment temperature T, after the model of Grüebler et al. that the paper cites
//! (°C; the paper prints no unit, spec §1.2, a reading):
//!
//! N(T) = −0.1073·T² + 4.7643·T − 33.4556,
//!
//! positive between [`ROOTS`] (8.74 and 35.66 °C) with its peak 19.43 at 22.20 °C. The paper
//! takes N as the reference density a simulated swarm is adjusted to; how to adjust it is ours
//! (spec §2.8) and lives on the host.

/// The coefficients of Eq. 1: N(T) = `A`·T² + `B`·T + `C`.
pub const A: f64 = -0.1073;
/// See [`A`].
pub const B: f64 = 4.7643;
/// See [`A`].
pub const C: f64 = -33.4556;

/// The temperatures (°C) between which Eq. 1 gives a positive density (its roots).
pub const ROOTS: (f64, f64) = (8.744_157_354_920_791, 35.657_520_184_687_78);

/// Eq. 1: insects per unit volume at `celsius`; 0 outside [`ROOTS`] (where the printed
/// polynomial is negative: no swarm).
pub fn density(celsius: f64) -> f64 {
    ((A * celsius + B) * celsius + C).max(0.0)
}

/// The temperature of the densest swarm and its density: the vertex of Eq. 1,
/// (−B / 2A, N(−B / 2A)).
pub fn peak() -> (f64, f64) {
    let t = -B / (2.0 * A);
    (t, density(t))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// R-T24: N(T) at 10-35 °C, the roots and the peak, ±1e-4.
    #[test]
    fn eq_1_matches_the_spec() {
        let want = [
            (10.0, 3.4574),
            (15.0, 13.8664),
            (20.0, 18.9104),
            (25.0, 18.5894),
            (30.0, 12.9034),
            (35.0, 1.8524),
        ];
        for (t, n) in want {
            assert!((density(t) - n).abs() < 1e-4, "N({t}) = {}", density(t));
        }
        let (lo, hi) = ROOTS;
        assert!((lo - 8.7442).abs() < 1e-4 && (hi - 35.6575).abs() < 1e-4);
        let exact = |t: f64| (A * t + B) * t + C;
        assert!(exact(lo).abs() < 1e-5 && exact(hi).abs() < 1e-5);
        let (t, n) = peak();
        assert!(
            (t - 22.2008).abs() < 1e-4 && (n - 19.4301).abs() < 1e-4,
            "{t} {n}"
        );
        assert_eq!((density(0.0), density(40.0)), (0.0, 0.0));
    }
}
