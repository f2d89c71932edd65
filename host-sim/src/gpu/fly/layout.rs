//! The ren2016 values as `u32` words for the GPU tick (`shaders/fly_tick.wgsl` reads them in the
//! same layout): the states, the decisions, each group's parameters and what its frames take
//! besides the world (its goal and threat, r_att, r_rep and r_ali squared), each slot's flags, and the status
//! words of the controller's refusals. Every value is converted on the host exactly as the CPU
//! engine converts it (`nearest::squared` for the selection's limit), so the GPU computes from
//! the CPU's bits.

use swarm_core::fly::{FlyDecision, FlyParams, FlyState};
use swarm_core::{Error, Vec3};

use crate::error::Result;
use crate::fly::Stimuli;
use crate::gpu::status;
use crate::gpu::words::Word;
use crate::scalar::SimScalar;
use crate::swarm3d::Source;

/// Words of a state: position, velocity, escape θ, escaping (`FLY_STATE_WORDS`).
pub const STATE_WORDS: usize = 8;
/// Words of a decision: the preferred velocity, whether ORCA was infeasible
/// (`FLY_DECISION_WORDS`).
pub const DECISION_WORDS: usize = 4;

/// Words of a group (`FLY_GROUP_WORDS`): the sixteen parameters in `S` in [`FlyParams`]' order
/// (γ … max_speed), then the words below.
pub const GROUP_WORDS: usize = 40;
/// Group words: `orca_neighbours`, `noise`, `fallback`, `escape_sides`.
pub const GROUP_ORCA_NEIGHBOURS: usize = 16;
/// Group word: the object id of the goal it pursues ([`NO_SOURCE`]: none).
pub const GROUP_GOAL: usize = 20;
/// Group word: the object id of the threat it escapes ([`NO_SOURCE`]: none).
pub const GROUP_THREAT: usize = 21;
/// Group word: r_att squared in `S` (the neighbour selection's limit, strict).
pub const GROUP_RANGE2: usize = 22;
/// Group word: r_rep squared in `S` (the repulsion zone's band of the selection, strict).
pub const GROUP_REP2: usize = 23;
/// Group word: r_ali squared in `S` (the alignment zone's band of the selection, strict).
pub const GROUP_ALI2: usize = 24;
/// Group words: the goal's region, then the threat's ([`REGION_WORDS`] each): [`REGION_BOX`] or
/// [`REGION_CAVE`] (0 for a source with a centre only), then its lower and upper corners in `S`
/// (all zero for a source with a centre only).
pub const GROUP_REGIONS: usize = 26;
/// Words of a source's region in a group ([`GROUP_REGIONS`]).
pub const REGION_WORDS: usize = 7;
/// A region's first word: a `region` (a goal's nearest point is pursued, a threat's walls
/// ahead echo).
pub const REGION_BOX: u32 = 1;
/// A region's first word: a `cave` (a goal's echo ahead is pursued: `ahead_point`).
pub const REGION_CAVE: u32 = 2;
/// [`GROUP_GOAL`] or [`GROUP_THREAT`] of a group without one.
pub const NO_SOURCE: u32 = u32::MAX;

pub use crate::gpu::swarm3d::FLAG_TRUNCATED;

/// The WGSL constants of the layout and their values (checked against `fly_tick.wgsl` by a
/// test).
pub const WGSL_CONSTANTS: &[(&str, u32)] = &[
    ("FLY_STATE_WORDS", STATE_WORDS as u32),
    ("FLY_DECISION_WORDS", DECISION_WORDS as u32),
    ("FLY_GROUP_WORDS", GROUP_WORDS as u32),
    ("FLY_GROUP_ORCA_NEIGHBOURS", GROUP_ORCA_NEIGHBOURS as u32),
    ("FLY_GROUP_GOAL", GROUP_GOAL as u32),
    ("FLY_GROUP_THREAT", GROUP_THREAT as u32),
    ("FLY_GROUP_RANGE2", GROUP_RANGE2 as u32),
    ("FLY_GROUP_REP2", GROUP_REP2 as u32),
    ("FLY_GROUP_ALI2", GROUP_ALI2 as u32),
    ("FLY_GROUP_REGIONS", GROUP_REGIONS as u32),
    ("FLY_REGION_WORDS", REGION_WORDS as u32),
    ("FLY_REGION_BOX", REGION_BOX),
    ("FLY_REGION_CAVE", REGION_CAVE),
    ("FLY_ZONE_QUOTA", crate::fly::ZONE_QUOTA as u32),
    ("FLY_NO_SOURCE", NO_SOURCE),
    ("FLY_FLAG_TRUNCATED", FLAG_TRUNCATED),
];

/// The fields the fly controller names in its errors, by their code in a status word
/// (`FLY_FIELD_*` in `shaders/fly_step.wgsl`; 0 is no field).
pub const FIELDS: [&str; 13] = [
    "",
    "state.pos",
    "state.vel",
    "state.escape_theta",
    "frame.neighbours.pos",
    "frame.neighbours.vel",
    "frame.neighbours.id",
    "frame.stimulus.pos",
    "frame.stimulus.kind",
    "frame.surfaces.point",
    "frame.surfaces.normal",
    "pref",
    "next.pos",
];

/// The kinds of error the fly kernels write: `NonFinite`, `OutOfRange`, `Inconsistent`.
const KINDS: u32 = 3;

/// The status word of a controller error, as the fly kernels write it (see
/// [`status::status_of`]).
pub fn status_of(e: &Error) -> u32 {
    status::status_of(&FIELDS, KINDS, e)
}

/// The controller's answer of a status word: `Ok(())` for 0, else the [`Error`] it stands for.
///
/// # Errors
///
/// [`SimError::GpuWords`](crate::error::SimError::GpuWords) for a word no fly kernel writes.
pub fn status_error(word: u32) -> Result<std::result::Result<(), Error>> {
    status::status_error(&FIELDS, KINDS, "fly status word", word)
}

/// Appends the [`STATE_WORDS`] words of `s`.
pub fn write_state<S: Word>(out: &mut Vec<u32>, s: &FlyState<S>) {
    for v in [s.pos, s.vel] {
        out.extend([v.x.to_word(), v.y.to_word(), v.z.to_word()]);
    }
    out.extend([s.escape_theta.to_word(), u32::from(s.escaping)]);
}

fn v3<S: Word>(w: &[u32]) -> Vec3<S> {
    Vec3::new(S::from_word(w[0]), S::from_word(w[1]), S::from_word(w[2]))
}

/// The state of [`STATE_WORDS`] words.
pub fn read_state<S: Word>(w: &[u32]) -> FlyState<S> {
    FlyState {
        pos: v3(&w[0..3]),
        vel: v3(&w[3..6]),
        escape_theta: S::from_word(w[6]),
        escaping: w[7] != 0,
    }
}

/// The decision of [`DECISION_WORDS`] words.
pub fn read_decision<S: Word>(w: &[u32]) -> FlyDecision<S> {
    FlyDecision {
        pref: v3(&w[0..3]),
        infeasible: w[3] != 0,
    }
}

/// Appends the [`GROUP_WORDS`] words of a group with parameters `p` responding to `stimuli`,
/// whose goal and threat are the sources `sources` (`None`: none, or not in the world).
pub fn write_group<S: Word + SimScalar>(
    out: &mut Vec<u32>,
    p: &FlyParams<S>,
    stimuli: Stimuli,
    sources: [Option<&Source>; 2],
) {
    let start = out.len();
    out.extend(
        [
            p.gamma,
            p.scale,
            p.gain,
            p.chi_rep,
            p.r_rep,
            p.chi_ali,
            p.r_ali,
            p.chi_att,
            p.r_att,
            p.chi_res,
            p.r_res,
            p.dt,
            p.radius,
            p.margin,
            p.tau,
            p.max_speed,
        ]
        .map(Word::to_word),
    );
    out.extend([p.orca_neighbours, p.noise, p.fallback, p.escape_sides].map(u32::from));
    let source = |id: Option<u16>| id.map_or(NO_SOURCE, u32::from);
    out.extend([source(stimuli.goal), source(stimuli.threat)]);
    for r in [p.r_att, p.r_rep, p.r_ali] {
        out.push(crate::nearest::squared::<S>(r.to_f32()).to_word());
    }
    out.push(0);
    for source in sources {
        match source.and_then(|s| Some((s.region?, s.cave))) {
            Some(([lo, hi], cave)) => {
                out.push(if cave { REGION_CAVE } else { REGION_BOX });
                out.extend(lo.iter().chain(&hi).map(|&c| S::from_f32(c).to_word()));
            }
            None => out.extend([0; REGION_WORDS]),
        }
    }
    debug_assert_eq!(out.len(), start + GROUP_WORDS);
}
