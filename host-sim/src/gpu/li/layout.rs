//! The li2015 values as `u32` words for the GPU tick (`shaders/li_tick.wgsl` and
//! `shaders/li_step.wgsl` read them in the same layout): the states, the decisions, each
//! group's parameters with its learned data (the two tables, the density grid: 4 KiB at most),
//! and the status words of the controller's refusals. Every value is converted on the host
//! exactly as the CPU engine converts it (`nearest::squared` for the selection's limit), so the
//! GPU computes from the CPU's bits.

use swarm_core::li::density::MAX_CELLS;
use swarm_core::li::{BINS, LiDecision, LiParams, LiState, LiTable};
use swarm_core::{Error, Vec3};

use crate::error::Result;
use crate::gpu::status;
use crate::gpu::words::Word;
use crate::scalar::SimScalar;

/// Words of a state: position, velocity, waypoint, segment start, age (`LI_STATE_WORDS`).
pub const STATE_WORDS: usize = 13;
/// Words of a decision: the preferred velocity, the proposals, whether one was accepted,
/// whether ORCA was infeasible (`LI_DECISION_WORDS`).
pub const DECISION_WORDS: usize = 6;

/// Group words from 0: dt, speed, eps, radius, margin, tau, range in `S`; from
/// [`GROUP_PATIENCE`]: patience, orca_neighbours, proposals, sampling, fallback.
pub const GROUP_PATIENCE: usize = 7;
/// Group word: the range squared in `S` (the neighbour selection's limit, strict).
pub const GROUP_RANGE2: usize = 12;
/// Group words: the lengths' table ([`TABLE_WORDS`]: lo, hi in `S`, the number of bins, the
/// shares in `S`, zero past the last bin).
pub const GROUP_LENGTHS: usize = 16;
/// Group words: the turns' table.
pub const GROUP_TURNS: usize = GROUP_LENGTHS + TABLE_WORDS;
/// Words of a table.
pub const TABLE_WORDS: usize = 3 + BINS;
/// Group words: the density's origin and cell in `S`, its dims.
pub const GROUP_DENSITY: usize = GROUP_TURNS + TABLE_WORDS;
/// Group words: the density's weights, four bytes a word (the first the lowest).
pub const GROUP_WEIGHTS: usize = 160;
/// Words of a group (`LI_GROUP_WORDS`).
pub const GROUP_WORDS: usize = GROUP_WEIGHTS + MAX_CELLS / 4;

/// The WGSL constants of the layout and their values (checked against the shaders by a test).
pub const WGSL_CONSTANTS: &[(&str, u32)] = &[
    ("LI_STATE_WORDS", STATE_WORDS as u32),
    ("LI_DECISION_WORDS", DECISION_WORDS as u32),
    ("LI_GROUP_WORDS", GROUP_WORDS as u32),
    ("LI_GROUP_PATIENCE", GROUP_PATIENCE as u32),
    ("LI_GROUP_RANGE2", GROUP_RANGE2 as u32),
    ("LI_GROUP_LENGTHS", GROUP_LENGTHS as u32),
    ("LI_GROUP_TURNS", GROUP_TURNS as u32),
    ("LI_TABLE_WORDS", TABLE_WORDS as u32),
    ("LI_GROUP_DENSITY", GROUP_DENSITY as u32),
    ("LI_GROUP_WEIGHTS", GROUP_WEIGHTS as u32),
    ("LI_FLAG_TRUNCATED", crate::gpu::swarm3d::FLAG_TRUNCATED),
];

/// The fields the li controller names in its errors, by their code in a status word
/// (`LI_FIELD_*` in `shaders/li_step.wgsl`; 0 is no field). The frame's codes are the fly's
/// (`fly_frame_validate` checks a li frame); 8, the fly's stimulus, is none.
pub const FIELDS: [&str; 13] = [
    "",
    "state.pos",
    "state.vel",
    "state.waypoint",
    "frame.neighbours.pos",
    "frame.neighbours.vel",
    "frame.neighbours.id",
    "state.seg_start",
    "",
    "frame.surfaces.point",
    "frame.surfaces.normal",
    "pref",
    "next.pos",
];

/// The kinds of error the li kernels write: `NonFinite`, `OutOfRange`, `Inconsistent`.
const KINDS: u32 = 3;

/// The status word of a controller error, as the li kernels write it.
pub fn status_of(e: &Error) -> u32 {
    status::status_of(&FIELDS, KINDS, e)
}

/// The controller's answer of a status word: `Ok(())` for 0, else the [`Error`] it stands for.
///
/// # Errors
///
/// [`SimError::GpuWords`](crate::error::SimError::GpuWords) for a word no li kernel writes.
pub fn status_error(word: u32) -> Result<std::result::Result<(), Error>> {
    status::status_error(&FIELDS, KINDS, "li status word", word)
}

fn push_v3<S: Word>(out: &mut Vec<u32>, v: Vec3<S>) {
    out.extend([v.x.to_word(), v.y.to_word(), v.z.to_word()]);
}

fn v3<S: Word>(w: &[u32]) -> Vec3<S> {
    Vec3::new(S::from_word(w[0]), S::from_word(w[1]), S::from_word(w[2]))
}

/// Appends the [`STATE_WORDS`] words of `s`.
pub fn write_state<S: Word>(out: &mut Vec<u32>, s: &LiState<S>) {
    for v in [s.pos, s.vel, s.waypoint, s.seg_start] {
        push_v3(out, v);
    }
    out.push(u32::from(s.age));
}

/// The state of [`STATE_WORDS`] words.
pub fn read_state<S: Word>(w: &[u32]) -> LiState<S> {
    LiState {
        pos: v3(&w[0..3]),
        vel: v3(&w[3..6]),
        waypoint: v3(&w[6..9]),
        seg_start: v3(&w[9..12]),
        age: w[12] as u16,
    }
}

/// The decision of [`DECISION_WORDS`] words.
pub fn read_decision<S: Word>(w: &[u32]) -> LiDecision<S> {
    LiDecision {
        pref: v3(&w[0..3]),
        proposals: w[3] as u8,
        accepted: w[4] != 0,
        infeasible: w[5] != 0,
    }
}

/// Appends the [`TABLE_WORDS`] words of `t`.
fn write_table<S: Word>(out: &mut Vec<u32>, t: &LiTable<S>) {
    out.extend([t.lo.to_word(), t.hi.to_word(), t.cdf.len() as u32]);
    out.extend(t.cdf.iter().map(|c| c.to_word()));
    out.extend(std::iter::repeat_n(0, BINS - t.cdf.len()));
}

/// Appends the [`GROUP_WORDS`] words of a group with parameters `p` (checked: at most
/// [`BINS`] bins a table and [`MAX_CELLS`] cells).
pub fn write_group<S: Word + SimScalar>(out: &mut Vec<u32>, p: &LiParams<S>) {
    let start = out.len();
    out.extend([p.dt, p.speed, p.eps, p.radius, p.margin, p.tau, p.range].map(Word::to_word));
    out.push(u32::from(p.patience));
    out.extend([p.orca_neighbours, p.proposals, p.sampling, p.fallback].map(u32::from));
    out.push(crate::nearest::squared::<S>(p.range.to_f32()).to_word());
    out.resize(start + GROUP_LENGTHS, 0);
    write_table(out, &p.lengths);
    write_table(out, &p.turns);
    let d = &p.density;
    push_v3(out, d.origin);
    out.push(d.cell.to_word());
    out.extend(d.dims.map(u32::from));
    out.resize(start + GROUP_WEIGHTS, 0);
    out.extend(d.weights.chunks(4).map(|c| {
        c.iter()
            .enumerate()
            .fold(0u32, |w, (k, &b)| w | u32::from(b) << (8 * k))
    }));
    out.resize(start + GROUP_WORDS, 0);
}
