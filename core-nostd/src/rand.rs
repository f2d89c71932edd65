//! Counter-based randomness: a random number is a pure function of
//! `(seed, agent, step, stream)`, so every decision depends only on its inputs, whatever the
//! thread count, machine or backend. The hash is 32-bit integer only (wrapping multiplies,
//! xor-shifts), so the same function is written in WGSL.

use crate::{Scalar, StepCtx};

/// Named streams, so two draws of one agent in one step never share bits.
pub mod stream {
    /// Ant: casual stop (xiang2018 §4.1).
    pub const ANT_STOP: u32 = 1;
    /// Ant: basic-movement turn (xiang2018 §4.1).
    pub const ANT_TURN: u32 = 2;
    /// Ant: direction after a degenerate geometry (e.g. exactly on a disturbance centre).
    pub const ANT_FALLBACK: u32 = 3;
    /// Ant: its preferred way round an obstacle met head-on (drawn at step 0, once per ant).
    pub const ANT_SIDE: u32 = 4;
    /// Bee: the bee's own clock offset, drawn once (step 0) per bee: which period of eq. 4
    /// within the wrap (hence its phase of eq. 3), see `bee::oscillation::clock_offset`.
    pub const BEE_PHASE: u32 = 0x20;
    /// Bee: the swarm's base roll phase, drawn once per seed (agent 0, step 0), see
    /// `bee::oscillation::clock_offset`.
    pub const BEE_PHASE_BASE: u32 = 0x21;
    /// Wang: whether the phototaxis bias toward the lamp applies this step (wang2014 §7).
    pub const WANG_PHOTO: u32 = 0x30;
    /// Wang: x component of the random-noise baseline (wang2014 §7.1).
    pub const WANG_NOISE_X: u32 = 0x31;
    /// Wang: y component of the random-noise baseline.
    pub const WANG_NOISE_Y: u32 = 0x32;
    /// Wang: z component of the random-noise baseline.
    pub const WANG_NOISE_Z: u32 = 0x33;
    /// Wang: the height (cosine of the polar angle) of the direction that separates a
    /// coincident MDE pair (wang2014 §6), drawn with the pair's lower id as the agent.
    pub const WANG_MDE: u32 = 0x34;
    /// Wang: the azimuth of that direction.
    pub const WANG_MDE_AZIMUTH: u32 = 0x35;
    /// ren2016: the escape angle θ of an episode.
    pub const FLY_ESCAPE: u32 = 0x40;
    /// ren2016: the white and Gaussian noise, x (the Gaussian's four draws add `k << 8`).
    pub const FLY_NOISE_X: u32 = 0x41;
    /// ren2016: the white and Gaussian noise, y.
    pub const FLY_NOISE_Y: u32 = 0x42;
    /// ren2016: the white and Gaussian noise, z.
    pub const FLY_NOISE_Z: u32 = 0x43;
    /// li2015: a proposed segment's length (Algorithm 1; proposal a adds `a << 8`).
    pub const LI_LENGTH: u32 = 0x50;
    /// li2015: a proposed segment's turning angle.
    pub const LI_TURN: u32 = 0x51;
    /// li2015: the azimuth of that turn about the previous direction.
    pub const LI_AZIMUTH: u32 = 0x52;
    /// li2015: the height of a uniform direction (the first waypoint).
    pub const LI_HEIGHT: u32 = 0x53;
    /// li2015: the Metropolis-Hastings acceptance of a proposal (§4.3).
    pub const LI_ACCEPT: u32 = 0x54;
}

/// Wellons' `lowbias32` finaliser: a bijective 32-bit mixer with low avalanche bias.
#[inline]
pub const fn mix32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// The random 32-bit word for `(seed, agent, step, stream)`.
///
/// `h = mix(mix(mix(mix(seed ^ 0x9e3779b9) ^ agent) ^ step) ^ stream)`.
#[inline]
pub const fn rand(seed: u32, agent: u32, step: u32, stream: u32) -> u32 {
    let h = mix32(seed ^ 0x9e37_79b9);
    let h = mix32(h ^ agent);
    let h = mix32(h ^ step);
    mix32(h ^ stream)
}

/// A uniform number in the open interval (0, 1) for this step and stream.
#[inline]
pub fn unit<S: Scalar>(ctx: StepCtx, stream: u32) -> S {
    S::unit_open(rand(ctx.seed, ctx.agent, ctx.step, stream))
}

/// A uniform angle in the open interval (−θ, θ) for this step and stream.
#[inline]
pub fn angle<S: Scalar>(ctx: StepCtx, stream: u32, theta: S) -> S {
    let u: S = unit(ctx, stream);
    (u + u - S::ONE) * theta
}

/// A Bernoulli draw: true with probability `p` (`p` ≤ 0 never, ≥ 1 always).
#[inline]
pub fn chance<S: Scalar>(ctx: StepCtx, stream: u32, p: S) -> bool {
    unit::<S>(ctx, stream) < p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pinned_values() {
        // Pinned so the WGSL port and the firmware can be checked against these exact words.
        assert_eq!(rand(0, 0, 0, 0), 0x41f3_9e5e); // from an independent Python port
        assert_eq!(rand(42, 7, 1000, 2), 0xe8f3_d26d);
    }

    #[test]
    fn streams_and_counters_decorrelate() {
        let a = rand(1, 2, 3, 4);
        assert_ne!(a, rand(1, 2, 3, 5));
        assert_ne!(a, rand(1, 2, 4, 4));
        assert_ne!(a, rand(1, 3, 3, 4));
        assert_ne!(a, rand(2, 2, 3, 4));
        // Bit balance over many draws.
        let mut ones = [0u32; 32];
        for i in 0..20_000 {
            let r = rand(9, i, 0, 0);
            for (b, o) in ones.iter_mut().enumerate() {
                *o += (r >> b) & 1;
            }
        }
        for o in ones {
            assert!((9_600..10_400).contains(&o), "biased bit: {o}/20000");
        }
    }
}
