//! Algorithm 1 of li2015 (§4.2, waypoint computation) with the Metropolis-Hastings screening
//! of §4.3, for one insect at one step.

use super::density::Density;
use super::sampler::Table;
use crate::check::{check_nonneg, check_vec};
use crate::rand::{self, stream};
use crate::scalar::pi;
use crate::{Error, Result, Scalar, StepCtx, Vec3};

/// [`Screening::sampling`]: Algorithm 1 screened by Metropolis-Hastings (meso + macro: the
/// paper's model, §4.2-4.3).
pub const SAMPLING_MH: u8 = 0;
/// [`Screening::sampling`]: Algorithm 1 alone (the mesoscopic level of Fig. 4): a proposal is
/// accepted when it is inside the grid, whatever its density (ours: the grid is the domain).
pub const SAMPLING_MESO: u8 = 1;
/// [`Screening::sampling`]: a waypoint uniform in the grid's box, length and turn ignored
/// (Fig. 4's "random sampling", spec L12).
pub const SAMPLING_RANDOM: u8 = 2;

wire_type! {
    /// The parameters of the waypoint level (spec §1.6, §2.3; ours where the paper is silent).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Screening<S> {
        /// ε of Algorithm 1: the insect has arrived when ‖x − g‖ ≤ ε (ours: one step of
        /// travel, v0·Δt).
        pub eps: S,
        /// K: proposals per arrival (≥ 1). The paper resamples a rejected waypoint ("another
        /// waypoint would be sampled", spec L9; ours K = 32); 1 is standard
        /// Metropolis-Hastings, one proposal. When all K are rejected the insect holds (its
        /// waypoint is its position) and proposes again at the next step, from the heading
        /// the rejections left ([`next_waypoint`]).
        pub proposals: u8,
        /// How waypoints are drawn: [`SAMPLING_MH`], [`SAMPLING_MESO`] or
        /// [`SAMPLING_RANDOM`].
        pub sampling: u8,
    }

    /// An insect's waypoint state: its current waypoint g and the start s of its current
    /// segment (x − s is the direction it came from).
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Waypoint<S> {
        /// g: where the insect flies.
        pub waypoint: Vec3<S>,
        /// s: where the current segment began.
        pub seg_start: Vec3<S>,
    }

    /// What [`next_waypoint`] decided.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Next<S> {
        /// The waypoint state after this step.
        pub waypoint: Waypoint<S>,
        /// How many proposals were drawn (0: not arrived yet).
        pub proposals: u8,
        /// Whether a proposal was accepted (false when not arrived, or held).
        pub accepted: bool,
    }
}

impl<S: Scalar> Default for Screening<S> {
    /// ε = 0.148 m/s × 0.01 s (spec §1.3 in metres, §1.6), K = 32, Metropolis-Hastings.
    fn default() -> Self {
        Screening {
            eps: S::from_f32(0.00148),
            proposals: 32,
            sampling: SAMPLING_MH,
        }
    }
}

impl<S: Scalar> Screening<S> {
    /// `Err(BadParam)` unless ε is finite and non-negative, K ≥ 1 and the sampling known.
    pub fn validate(&self) -> Result<()> {
        check_nonneg(self.eps, "eps").map_err(|_| Error::BadParam { field: "eps" })?;
        if self.proposals == 0 {
            return Err(Error::BadParam { field: "proposals" });
        }
        if self.sampling > SAMPLING_RANDOM {
            return Err(Error::BadParam { field: "sampling" });
        }
        Ok(())
    }
}

/// `direction(d, θ)` of Algorithm 1 in 3D (spec §2.2, ours): the unit vector at angle |θ| from
/// d̂, at azimuth `phi` about it (measured from the axis d̂ × a, a the world axis least aligned
/// with d̂). When `d` cannot be normalised (the first waypoint, or an insect that did not
/// move), the uniform direction on the sphere of height `z` ∈ (−1, 1) and azimuth `phi`.
pub fn direction<S: Scalar>(d: Vec3<S>, theta: S, phi: S, z: S) -> Vec3<S> {
    let (s_phi, c_phi) = phi.sin_cos();
    let Some(n) = d.normalized() else {
        let r = (S::ONE - z * z).max(S::ZERO).sqrt();
        return Vec3::new(r * c_phi, z, r * s_phi);
    };
    let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
    let a = if ax <= ay && ax <= az {
        Vec3::new(S::ONE, S::ZERO, S::ZERO)
    } else if ay <= az {
        Vec3::new(S::ZERO, S::ONE, S::ZERO)
    } else {
        Vec3::new(S::ZERO, S::ZERO, S::ONE)
    };
    // n is a unit vector and a the axis least aligned with it: |n × a|² ≥ 2/3.
    let e1 = n.cross(a).normalized().unwrap_or(a);
    let e2 = n.cross(e1);
    let (s_t, c_t) = theta.abs().sin_cos();
    n * c_t + (e1 * c_phi + e2 * s_phi) * s_t
}

/// The acceptance of §4.3 for a proposal with density `w_g` from a position with density
/// `w_x`, given a uniform `u` ∈ (0, 1): never into a zero cell; from a zero cell any `w_g` > 0
/// (spec L8, ours); else with probability min(1, w_g/w_x) (`u·w_x < w_g`).
pub fn accept<S: Scalar>(w_x: u8, w_g: u8, u: S) -> bool {
    w_g > 0 && (w_x <= w_g || u * S::from_i32(i32::from(w_x)) < S::from_i32(i32::from(w_g)))
}

/// One step of Algorithm 1 with the screening of §4.3, for the insect at `pos` with waypoint
/// state `current`:
///
/// * not arrived (‖x − g‖ > ε): unchanged;
/// * arrived: up to K proposals, each `g = x + l·o` with `l` drawn from `lengths`, `o =
///   direction(x − s, θ)` and θ drawn from `turns` (radians; its magnitude is the cone
///   angle), screened by [`accept`] against `density`; the first accepted one becomes the
///   waypoint and `s = x`; if none is, the insect holds (`g = x`, the heading reversed once per
///   rejection, see below).
///
/// Ours (spec L9, docs/models.md): a rejection reverses the heading the next proposal turns
/// from (proposal a turns from `came` = x − s when a is even, from −`came` when a is odd), and
/// a hold keeps the heading as K rejections left it (s = x − `came` for K even, x + `came` for
/// K odd, or s = x when that point is out of range). This is the lifted ("guided walk")
/// Metropolis-Hastings of Gustafson (1998) on the chain of (position, heading): the proposal
/// turns the heading by the data's angle at a uniform azimuth, which is symmetric under
/// reversal (from −o the angle back to −d is the same), so the density stays the chain's
/// stationary law while the insects keep the data's persistence. Redrawing in the same cone
/// kept insects circling at the edge of the density; a uniform redraw left them spread flatter
/// than the density (docs/models.md gives the measurements).
///
/// [`SAMPLING_MESO`] accepts any proposal inside the grid; [`SAMPLING_RANDOM`] proposes a
/// point uniform in the grid's box instead of `x + l·o`, accepted when inside.
///
/// Randomness: proposal a (0-based) draws from streams
/// [`LI_LENGTH`](stream::LI_LENGTH), [`LI_TURN`](stream::LI_TURN),
/// [`LI_AZIMUTH`](stream::LI_AZIMUTH), [`LI_HEIGHT`](stream::LI_HEIGHT) and
/// [`LI_ACCEPT`](stream::LI_ACCEPT), each plus `a << 8` (a random waypoint's x, y and z are
/// the first three).
///
/// # Errors
///
/// `BadParam` for an invalid [`Screening`]; `NonFinite`/`OutOfRange` naming `pos`,
/// `current.waypoint` or `current.seg_start`.
#[allow(clippy::too_many_arguments)]
pub fn next_waypoint<S: Scalar, const L: usize, const T: usize>(
    pos: Vec3<S>,
    current: &Waypoint<S>,
    lengths: &Table<S, L>,
    turns: &Table<S, T>,
    density: &Density<'_, S>,
    params: &Screening<S>,
    ctx: StepCtx,
) -> Result<Next<S>> {
    params.validate()?;
    check_vec(pos, "pos")?;
    check_vec(current.waypoint, "current.waypoint")?;
    check_vec(current.seg_start, "current.seg_start")?;
    if (pos - current.waypoint).length_sq() > params.eps * params.eps {
        return Ok(Next {
            waypoint: *current,
            proposals: 0,
            accepted: false,
        });
    }
    let w_x = density.at(pos);
    let came = pos - current.seg_start;
    for a in 0..params.proposals {
        let draw = |s: u32| rand::unit::<S>(ctx, s + (u32::from(a) << 8));
        let (u1, u2, u3) = (
            draw(stream::LI_LENGTH),
            draw(stream::LI_TURN),
            draw(stream::LI_AZIMUTH),
        );
        let g = if params.sampling == SAMPLING_RANDOM {
            let (lo, hi) = density.bounds();
            lo + Vec3::new((hi.x - lo.x) * u1, (hi.y - lo.y) * u2, (hi.z - lo.z) * u3)
        } else {
            let (l, theta) = (lengths.sample(u1), turns.sample(u2));
            let phi = (u3 * S::from_i32(2) - S::ONE) * pi::<S>();
            let z = draw(stream::LI_HEIGHT) * S::from_i32(2) - S::ONE;
            let heading = if a.is_multiple_of(2) { came } else { -came };
            pos + direction(heading, theta, phi, z) * l
        };
        let accepted = if params.sampling == SAMPLING_MH {
            accept(w_x, density.at(g), draw(stream::LI_ACCEPT))
        } else {
            density.cell_of(g).is_some()
        };
        if accepted {
            return Ok(Next {
                waypoint: Waypoint {
                    waypoint: g,
                    seg_start: pos,
                },
                proposals: a + 1,
                accepted: true,
            });
        }
    }
    // Held: the heading as the K rejections reversed it.
    let seg_start = if params.proposals.is_multiple_of(2) {
        current.seg_start
    } else {
        let s = pos + came;
        if check_vec(s, "seg_start").is_ok() {
            s
        } else {
            pos
        }
    };
    Ok(Next {
        waypoint: Waypoint {
            waypoint: pos,
            seg_start,
        },
        proposals: params.proposals,
        accepted: false,
    })
}
