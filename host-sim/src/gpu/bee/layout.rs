//! The word layout of the bee kernels' buffers: the values of [`swarm_core::bee`] as `u32`
//! words, packed and unpacked here and read and written by `shaders/bee_layout.wgsl` in the same
//! layout (the word counts are constants on both sides, checked against each other by a test).
//!
//! An `S` is one word ([`Word`]: the bits of an [`Fx`](swarm_core::Fx), or of an `f32`), a
//! `bool` one word; an absent `Option` is a 0 flag followed by zero words, and the entries of a
//! frame past its length are zero words, so two equal values always have equal words. Frames
//! have the simulator's capacities ([`N`] neighbours, [`P`] target particles).
//!
//! | value | words |
//! |---|---|
//! | [`BeeState`] | pos, vel, forward, density, avoiding, u0, roll, pitch |
//! | [`BeeDecision`] | accel, velocity, roll, pitch, avoiding, density |
//! | [`BeeParams`] | h, grid_edge, kappa1, kappa2, kappa3, epsilon, mass, gravity, air_density, wing_area, radius, d0, dt, stiffness, rest_density, max_speed, damping |
//! | [`BeeFrame`](swarm_core::bee::BeeFrame) | t, neighbour count, [`N`] × (pos, vel, density), target count, [`P`] × point, goal (flag, point), obstacle (flag, point, normal) |
//! | a step's result | status ([`status_of`]), decision, next state (zero words for an error) |

use swarm_core::bee::{BeeDecision, BeeNeighbor, BeeParams, BeeState, ObstacleSense};
use swarm_core::{Error, Vec3};

pub use crate::gpu::words::Word;

use crate::bees::{BeeSimFrame, N, P};
use crate::error::Result;
use crate::gpu::status;
use crate::gpu::words::Words;

/// Words of a [`BeeState`] (`BEE_STATE_WORDS`).
pub const STATE_WORDS: usize = 16;
/// Words of a [`BeeDecision`] (`BEE_DECISION_WORDS`).
pub const DECISION_WORDS: usize = 10;
/// Words of a [`BeeParams`] (`BEE_PARAMS_WORDS`).
pub const PARAMS_WORDS: usize = 17;
/// Words of a [`BeeNeighbor`] (`BEE_NEIGHBOR_WORDS`).
pub const NEIGHBOUR_WORDS: usize = 7;
/// Where the neighbours of a frame start (`BEE_FRAME_NEIGHBOURS`): after t and their count.
const FRAME_NEIGHBOURS: usize = 2;
/// Where the target particles of a frame start (`BEE_FRAME_TARGETS`): after their count.
const FRAME_TARGETS: usize = FRAME_NEIGHBOURS + N * NEIGHBOUR_WORDS + 1;
/// Where the goal of a frame starts (`BEE_FRAME_GOAL`): its flag.
const FRAME_GOAL: usize = FRAME_TARGETS + 3 * P;
/// Where the obstacle of a frame starts (`BEE_FRAME_OBSTACLE`): its flag.
const FRAME_OBSTACLE: usize = FRAME_GOAL + 4;
/// Words of a [`BeeFrame`](swarm_core::bee::BeeFrame) of the simulator (`BEE_FRAME_WORDS`).
pub const FRAME_WORDS: usize = FRAME_OBSTACLE + 7;

/// Words of one element of the step kernel's input: state, frame, parameters.
pub const STEP_INPUT_WORDS: usize = STATE_WORDS + FRAME_WORDS + PARAMS_WORDS;
/// Words of one element of the step kernel's output: status, decision, next state.
pub const STEP_OUTPUT_WORDS: usize = 1 + DECISION_WORDS + STATE_WORDS;

/// The WGSL constants of the layout and their values (checked against `bee_layout.wgsl` and
/// `bee_frame.wgsl` by a test).
pub const WGSL_CONSTANTS: &[(&str, usize)] = &[
    ("BEE_STATE_WORDS", STATE_WORDS),
    ("BEE_DECISION_WORDS", DECISION_WORDS),
    ("BEE_PARAMS_WORDS", PARAMS_WORDS),
    ("BEE_NEIGHBOR_WORDS", NEIGHBOUR_WORDS),
    ("BEE_FRAME_WORDS", FRAME_WORDS),
    ("BEE_FRAME_NEIGHBOURS", FRAME_NEIGHBOURS),
    ("BEE_FRAME_TARGETS", FRAME_TARGETS),
    ("BEE_FRAME_GOAL", FRAME_GOAL),
    ("BEE_FRAME_OBSTACLE", FRAME_OBSTACLE),
    ("BEE_NEIGHBOURS", N),
    ("BEE_TARGETS", P),
];

// ---- packing ----

fn v3<S: Word>(out: &mut Vec<u32>, v: Vec3<S>) {
    out.extend([v.x.to_word(), v.y.to_word(), v.z.to_word()]);
}

/// Appends the words of `s`.
pub fn write_state<S: Word>(out: &mut Vec<u32>, s: &BeeState<S>) {
    v3(out, s.pos);
    v3(out, s.vel);
    v3(out, s.forward);
    out.extend([s.density.to_word(), u32::from(s.avoiding)]);
    v3(out, s.u0);
    out.extend([s.roll.to_word(), s.pitch.to_word()]);
}

/// Appends the words of `d`.
pub fn write_decision<S: Word>(out: &mut Vec<u32>, d: &BeeDecision<S>) {
    v3(out, d.accel);
    v3(out, d.velocity);
    out.extend([
        d.roll.to_word(),
        d.pitch.to_word(),
        u32::from(d.avoiding),
        d.density.to_word(),
    ]);
}

/// Appends the words of `p`.
pub fn write_params<S: Word>(out: &mut Vec<u32>, p: &BeeParams<S>) {
    out.extend(
        [
            p.h,
            p.grid_edge,
            p.kappa1,
            p.kappa2,
            p.kappa3,
            p.epsilon,
            p.mass,
            p.gravity,
            p.air_density,
            p.wing_area,
            p.radius,
            p.d0,
            p.dt,
            p.stiffness,
            p.rest_density,
            p.max_speed,
            p.damping,
        ]
        .map(Word::to_word),
    );
}

/// Appends the words of `f`.
pub fn write_frame<S: Word>(out: &mut Vec<u32>, f: &BeeSimFrame<S>) {
    out.extend([f.t.to_word(), f.neighbours.len() as u32]);
    for n in &f.neighbours {
        v3(out, n.pos);
        v3(out, n.vel);
        out.push(n.density.to_word());
    }
    out.extend(std::iter::repeat_n(
        0,
        (N - f.neighbours.len()) * NEIGHBOUR_WORDS,
    ));
    out.push(f.targets.len() as u32);
    for &p in &f.targets {
        v3(out, p);
    }
    out.extend(std::iter::repeat_n(0, (P - f.targets.len()) * 3));
    match f.goal {
        Some(g) => {
            out.push(1);
            v3(out, g);
        }
        None => out.extend([0; 4]),
    }
    match f.obstacle {
        Some(o) => {
            out.push(1);
            v3(out, o.point);
            v3(out, o.normal);
        }
        None => out.extend([0; 7]),
    }
}

/// Appends one element of the step kernel's input ([`STEP_INPUT_WORDS`]).
pub fn write_step_input<S: Word>(
    out: &mut Vec<u32>,
    state: &BeeState<S>,
    frame: &BeeSimFrame<S>,
    params: &BeeParams<S>,
) {
    write_state(out, state);
    write_frame(out, frame);
    write_params(out, params);
}

/// What `swarm_core::bee::step_checked` returns.
pub type StepResult<S> = std::result::Result<(BeeDecision<S>, BeeState<S>), Error>;

/// Appends what the step kernel writes for `r` ([`STEP_OUTPUT_WORDS`]): the status, then the
/// decision and the next state (zero words for an error).
pub fn write_step_result<S: Word>(out: &mut Vec<u32>, r: &StepResult<S>) {
    match r {
        Ok((d, s)) => {
            out.push(0);
            write_decision(out, d);
            write_state(out, s);
        }
        Err(e) => {
            out.push(status_of(e));
            out.extend([0; DECISION_WORDS + STATE_WORDS]);
        }
    }
}

// ---- unpacking ----

/// The [`BeeState`] of the first [`STATE_WORDS`] of `w` (missing words read as zero).
///
/// # Errors
///
/// [`SimError::GpuWords`](crate::error::SimError::GpuWords) for a flag that is neither 0 nor 1.
pub fn read_state<S: Word>(w: &[u32]) -> Result<BeeState<S>> {
    let mut r = Words(w);
    let pos = r.v3();
    let vel = r.v3();
    let forward = r.v3();
    let density = r.s();
    let avoiding = r.flag()?;
    let u0 = r.v3();
    let roll = r.s();
    Ok(BeeState {
        pos,
        vel,
        forward,
        density,
        avoiding,
        u0,
        roll,
        pitch: r.s(),
    })
}

/// The [`BeeDecision`] of the first [`DECISION_WORDS`] of `w`.
///
/// # Errors
///
/// As [`read_state`].
pub fn read_decision<S: Word>(w: &[u32]) -> Result<BeeDecision<S>> {
    let mut r = Words(w);
    let accel = r.v3();
    let velocity = r.v3();
    let roll = r.s();
    let pitch = r.s();
    let avoiding = r.flag()?;
    Ok(BeeDecision {
        accel,
        velocity,
        roll,
        pitch,
        avoiding,
        density: r.s(),
    })
}

/// A step's decision and next state from the words after its status.
///
/// # Errors
///
/// As [`read_state`].
pub fn read_step<S: Word>(w: &[u32]) -> Result<(BeeDecision<S>, BeeState<S>)> {
    let d = read_decision(w)?;
    Ok((d, read_state(w.get(DECISION_WORDS..).unwrap_or(&[]))?))
}

/// The [`BeeParams`] of the first [`PARAMS_WORDS`] of `w`.
pub fn read_params<S: Word>(w: &[u32]) -> BeeParams<S> {
    let mut r = Words(w);
    BeeParams {
        h: r.s(),
        grid_edge: r.s(),
        kappa1: r.s(),
        kappa2: r.s(),
        kappa3: r.s(),
        epsilon: r.s(),
        mass: r.s(),
        gravity: r.s(),
        air_density: r.s(),
        wing_area: r.s(),
        radius: r.s(),
        d0: r.s(),
        dt: r.s(),
        stiffness: r.s(),
        rest_density: r.s(),
        max_speed: r.s(),
        damping: r.s(),
    }
}

/// The bee frame of the first [`FRAME_WORDS`] of `w`.
///
/// # Errors
///
/// [`SimError::GpuWords`](crate::error::SimError::GpuWords) for a list longer than its capacity
/// or a bad flag.
pub fn read_frame<S: Word>(w: &[u32]) -> Result<BeeSimFrame<S>> {
    let mut r = Words(w);
    let mut f = BeeSimFrame::new(r.s());
    let n = r.len(N)?;
    for _ in 0..n {
        let pos = r.v3();
        let vel = r.v3();
        let density = r.s();
        let _ = f.neighbours.push(BeeNeighbor { pos, vel, density });
    }
    r.skip((N - n) * NEIGHBOUR_WORDS);
    let n = r.len(P)?;
    for _ in 0..n {
        let _ = f.targets.push(r.v3());
    }
    r.skip((P - n) * 3);
    f.goal = if r.flag()? {
        Some(r.v3())
    } else {
        r.skip(3);
        None
    };
    f.obstacle = if r.flag()? {
        let point = r.v3();
        Some(ObstacleSense {
            point,
            normal: r.v3(),
        })
    } else {
        None
    };
    Ok(f)
}

// ---- status words ----

/// The fields the bee controller names in its errors, by their code in a status word
/// (`BEE_FIELD_*` in `shaders/bee_frame.wgsl`; 0 is no field).
pub const FIELDS: [&str; 20] = [
    "",
    "state.pos",
    "state.vel",
    "state.forward",
    "state.density",
    "state.u0",
    "state.roll",
    "state.pitch",
    "frame.t",
    "frame.neighbours.pos",
    "frame.neighbours.vel",
    "frame.neighbours.density",
    "frame.targets",
    "frame.goal",
    "frame.obstacle.point",
    "frame.obstacle.normal",
    "decision.accel",
    "decision.velocity",
    "decision.pos",
    "decision.density",
];

/// The kinds of error the bee kernels write: [`Error::NonFinite`] and [`Error::OutOfRange`].
const KINDS: u32 = 2;

/// The status word of a controller error, as the bee kernels write it: `kind | field << 8 |
/// (index + 1) << 16`, the kind 1 for [`Error::NonFinite`], 2 for [`Error::OutOfRange`];
/// `u32::MAX` for an error the bee step never returns.
pub fn status_of(e: &Error) -> u32 {
    status::status_of(&FIELDS, KINDS, e)
}

/// The controller's answer of a status word: `Ok(())` for 0, else the [`Error`] it stands for.
///
/// # Errors
///
/// [`SimError::GpuWords`](crate::error::SimError::GpuWords) for a word no bee kernel writes.
pub fn status_error(word: u32) -> Result<std::result::Result<(), Error>> {
    status::status_error(&FIELDS, KINDS, "bee status word", word)
}

/// The result of one step from the kernel's output words ([`STEP_OUTPUT_WORDS`]): the error
/// of its status word, or the decision and next state.
///
/// # Errors
///
/// [`SimError::GpuWords`](crate::error::SimError::GpuWords) for words no bee kernel writes.
pub fn read_step_result<S: Word>(w: &[u32]) -> Result<StepResult<S>> {
    let status = w.first().copied().unwrap_or(0);
    Ok(match status_error(status)? {
        Ok(()) => Ok(read_step(w.get(1..).unwrap_or(&[]))?),
        Err(e) => Err(e),
    })
}
