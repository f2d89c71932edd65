//! The wang2014 values as `u32` words for the GPU tick (`shaders/wang_tick.wgsl` reads them in
//! the same layout): the states, each group's parameters and what its frames take besides the
//! world (its goal's field, its lamp, d_min squared), the cost fields, and the status words of
//! the controller's refusals. Every value is converted on the host exactly as the CPU engine
//! converts it (`S::from_f32`, `squared`), or sent as `f32` bits that the kernel converts as
//! [`CostField::guide_at`] does, so the GPU computes from the CPU's bits.

use swarm_core::Error;
use swarm_core::wang::{WangParams, WangState};

use crate::error::Result;
use crate::fields::{CostField, GUIDE_SCALE};
use crate::gpu::status;
use crate::gpu::words::Word;
use crate::scalar::SimScalar;

/// Words of a state: position, velocity (`WANG_STATE_WORDS`).
pub const STATE_WORDS: usize = 6;

/// Words of a group (`WANG_GROUP_WORDS`): the parameters in `S` (scale, gain, s0, dt, d0,
/// d_min, p_photo, u_photo), then the words below.
pub const GROUP_WORDS: usize = 16;
/// Group word: the noise source ([`WangParams::noise`]).
pub const GROUP_NOISE: usize = 8;
/// Group word: where the field of the group's goal starts in the fields' words ([`NO_FIELD`]:
/// its goal is absent).
pub const GROUP_FIELD: usize = 9;
/// Group word: whether its frames have a lamp (phototaxis and a goal present).
pub const GROUP_HAS_LAMP: usize = 10;
/// Group words: the lamp (x, y, z in `S`).
pub const GROUP_LAMP: usize = 11;
/// Group word: d_min squared in `S` (the MDE selection's limit, strict).
pub const GROUP_RANGE2: usize = 14;
/// [`GROUP_FIELD`] of a group whose goal has no field.
pub const NO_FIELD: u32 = u32::MAX;

/// Words of a field's header: cells along x, y, z; the lower corner and the cell (`f32`
/// bits); where its cell records start; the guides' scale (`f32` bits).
pub const FIELD_HEADER_WORDS: usize = 9;
/// Field words: the cells along x, y and z (`WANG_FIELD_DIMS`).
pub const FIELD_DIMS: usize = 0;
/// Field words: the grid's lower corner, as `f32` bits.
pub const FIELD_MIN: usize = 3;
/// Field word: the cell's edge, as `f32` bits.
pub const FIELD_CELL: usize = 6;
/// Field word: where the cell records start (one [`GuideCell`](crate::fields::GuideCell) word a cell, in
/// [`CellGrid::index`] order: the guide quantised to 8 bits a component, the goal flag).
///
/// [`CellGrid::index`]: crate::fields::CellGrid::index
pub const FIELD_CELLS: usize = 7;
/// Field word: [`GUIDE_SCALE`] as `f32` bits (a stored component `q` is `f32(q) · scale`).
pub const FIELD_SCALE: usize = 8;

/// The WGSL constants of the layout and their values (checked against `wang_tick.wgsl` by a
/// test).
pub const WGSL_CONSTANTS: &[(&str, u32)] = &[
    ("WANG_STATE_WORDS", STATE_WORDS as u32),
    ("WANG_GROUP_WORDS", GROUP_WORDS as u32),
    ("WANG_GROUP_NOISE", GROUP_NOISE as u32),
    ("WANG_GROUP_FIELD", GROUP_FIELD as u32),
    ("WANG_GROUP_HAS_LAMP", GROUP_HAS_LAMP as u32),
    ("WANG_GROUP_LAMP", GROUP_LAMP as u32),
    ("WANG_GROUP_RANGE2", GROUP_RANGE2 as u32),
    ("WANG_NO_FIELD", NO_FIELD),
    ("WANG_FIELD_DIMS", FIELD_DIMS as u32),
    ("WANG_FIELD_MIN", FIELD_MIN as u32),
    ("WANG_FIELD_CELL", FIELD_CELL as u32),
    ("WANG_FIELD_CELLS", FIELD_CELLS as u32),
    ("WANG_FIELD_SCALE", FIELD_SCALE as u32),
];

/// The fields the wang2014 controller names in its errors, by their code in a status word
/// (`WANG_FIELD_*` in `shaders/wang_step.wgsl`; 0 is no field).
pub const FIELDS: [&str; 13] = [
    "",
    "state.pos",
    "state.vel",
    "frame.guide",
    "frame.boundary.point",
    "frame.boundary.normal",
    "frame.boundary.curvature",
    "frame.boundary.axis",
    "frame.lamp",
    "moved.pos",
    "moved.vel",
    "frame.neighbours.pos",
    "frame.neighbours.id",
];

/// The kinds of error the wang kernels write: `NonFinite`, `OutOfRange`, `Inconsistent`.
const KINDS: u32 = 3;

/// The status word of a controller error, as the wang kernels write it (see
/// [`status::status_of`]).
pub fn status_of(e: &Error) -> u32 {
    status::status_of(&FIELDS, KINDS, e)
}

/// The controller's answer of a status word: `Ok(())` for 0, else the [`Error`] it stands for.
///
/// # Errors
///
/// [`SimError::GpuWords`](crate::error::SimError::GpuWords) for a word no wang kernel writes.
pub fn status_error(word: u32) -> Result<std::result::Result<(), Error>> {
    status::status_error(&FIELDS, KINDS, "wang status word", word)
}

/// Appends the words of `s`.
pub fn write_state<S: Word>(out: &mut Vec<u32>, s: &WangState<S>) {
    for v in [s.pos, s.vel] {
        out.extend([v.x.to_word(), v.y.to_word(), v.z.to_word()]);
    }
}

/// The state of [`STATE_WORDS`] words.
pub fn read_state<S: Word>(w: &[u32]) -> WangState<S> {
    let v = |k: usize| {
        swarm_core::Vec3::new(
            S::from_word(w[k]),
            S::from_word(w[k + 1]),
            S::from_word(w[k + 2]),
        )
    };
    WangState {
        pos: v(0),
        vel: v(3),
    }
}

/// What a group's frames take besides the world: the word where its goal's field starts
/// ([`NO_FIELD`] for none) and its lamp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroupInputs<S> {
    /// Where the field of its goal starts in the fields' words.
    pub field: u32,
    /// The lamp of its advect frames.
    pub lamp: Option<swarm_core::Vec3<S>>,
}

/// Appends the [`GROUP_WORDS`] words of a group with parameters `p`.
pub fn write_group<S: Word + SimScalar>(
    out: &mut Vec<u32>,
    p: &WangParams<S>,
    inputs: GroupInputs<S>,
) {
    let start = out.len();
    out.extend(
        [
            p.scale, p.gain, p.s0, p.dt, p.d0, p.d_min, p.p_photo, p.u_photo,
        ]
        .map(Word::to_word),
    );
    out.push(u32::from(p.noise));
    out.push(inputs.field);
    let lamp = inputs.lamp.unwrap_or(swarm_core::Vec3::zero());
    out.push(u32::from(inputs.lamp.is_some()));
    out.extend([lamp.x, lamp.y, lamp.z].map(Word::to_word));
    out.push(crate::nearest::squared::<S>(p.d_min.to_f32()).to_word());
    out.resize(start + GROUP_WORDS, 0);
}

/// The fields' words: each field's header ([`FIELD_HEADER_WORDS`]) and cell records, one
/// after the other; and where each starts, by goal id.
pub fn field_words(fields: &[(u16, CostField)]) -> (Vec<u32>, Vec<(u16, u32)>) {
    let mut out = Vec::new();
    let mut at = Vec::with_capacity(fields.len());
    for (goal, f) in fields {
        let start = out.len();
        at.push((*goal, start as u32));
        let g = &f.grid;
        out.extend(g.dims);
        out.extend(g.min.map(f32::to_bits));
        out.push(g.cell.to_bits());
        out.push((start + FIELD_HEADER_WORDS) as u32);
        out.push(GUIDE_SCALE.to_bits());
        out.extend((0..g.len()).map(|i| f.cell(i).0));
    }
    (out, at)
}
