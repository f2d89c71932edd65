//! The word layout of the ant kernels' buffers: the values of [`swarm_core::ant`] as `u32`
//! words, packed and unpacked here and read and written by `shaders/ant_layout.wgsl` in the same
//! layout (the word counts are constants on both sides, checked against each other by a test).
//!
//! An `S` is one word ([`Word`]: the bits of an [`Fx`](swarm_core::Fx), or of an `f32`), an
//! enum its discriminant, a `u16`, `u8` or `bool` one word; an absent `Option` is a 0 flag followed by
//! zero words, and the entries of a frame past its length are zero words, so two equal values
//! always have equal words. Frames have the simulator's capacities ([`N`], [`O`], [`SURFACES`]).
//!
//! | value | words |
//! |---|---|
//! | [`AntState`] | pos, heading, label, nest, origin, arrival, goal (flag, x, y), follow (flag, turn, winding), motion, stop (flag, reason, remaining, place) |
//! | [`AntPlan`] | state, predicted |
//! | [`AntParams`] | speed, dt, theta, p_stop, casual_stop_ticks, collect_ticks, drop_ticks, contact_range, avoid_range, collision_range, w0, c, k |
//! | [`PlanFrame`](swarm_core::ant::PlanFrame) | bounds (min, max), neighbour count, [`N`] × (id, pos, label, nest, origin, arrival), object count, [`O`] × (kind, id, closest or center, normal, radius) |
//! | [`ResolveFrame`](swarm_core::ant::ResolveFrame) | bounds, neighbour count, [`N`] × prediction, obstacle count, [`SURFACES`] × (closest, normal) |
//! | [`StepCtx`] | seed, agent, step |
//! | a result | status ([`status_of`]), then the value (zero words for an error) |

use swarm_core::ant::{
    AntNeighbor, AntObject, AntParams, AntPlan, AntState, Follow, Label, MotionState, SURFACES,
    StopReason, StopTimer, Surface, Turn,
};
use swarm_core::{Error, Rect, StepCtx, Vec2};

use crate::ants::{AntPlanFrame, AntResolveFrame, N, O};
use crate::error::{Result, SimError};
use crate::gpu::status;
pub use crate::gpu::words::Word;
use crate::gpu::words::Words;

/// Words of an [`AntState`] (`ANT_STATE_WORDS`).
pub const STATE_WORDS: usize = 20;
/// Words of an [`AntPlan`] (`ANT_PLAN_WORDS`).
pub const PLAN_WORDS: usize = STATE_WORDS + 2;
/// Words of an [`AntParams`] (`ANT_PARAMS_WORDS`).
pub const PARAMS_WORDS: usize = 13;
/// Words of an [`AntNeighbor`] (`ANT_NEIGHBOR_WORDS`).
pub const NEIGHBOUR_WORDS: usize = 8;
/// Words of an [`AntObject`] (`ANT_OBJECT_WORDS`).
pub const OBJECT_WORDS: usize = 7;
/// Words of a [`Surface`] (`ANT_SURFACE_WORDS`).
pub const SURFACE_WORDS: usize = 4;
/// Words of a [`PlanFrame`](swarm_core::ant::PlanFrame) of the simulator (`ANT_PLAN_FRAME_WORDS`).
pub const PLAN_FRAME_WORDS: usize = 4 + 1 + N * NEIGHBOUR_WORDS + 1 + O * OBJECT_WORDS;
/// Words of a [`ResolveFrame`](swarm_core::ant::ResolveFrame) of the simulator (`ANT_RESOLVE_FRAME_WORDS`).
pub const RESOLVE_FRAME_WORDS: usize = 4 + 1 + 2 * N + 1 + SURFACES * SURFACE_WORDS;
/// Words of a [`StepCtx`] (`ANT_CTX_WORDS`).
pub const CTX_WORDS: usize = 3;

/// Words of one element of the plan kernel's input: state, frame, parameters, step context.
pub const PLAN_INPUT_WORDS: usize = STATE_WORDS + PLAN_FRAME_WORDS + PARAMS_WORDS + CTX_WORDS;
/// Words of one element of the plan kernel's output: status, plan.
pub const PLAN_OUTPUT_WORDS: usize = 1 + PLAN_WORDS;
/// Words of one element of the resolve kernel's input: plan, frame, parameters.
pub const RESOLVE_INPUT_WORDS: usize = PLAN_WORDS + RESOLVE_FRAME_WORDS + PARAMS_WORDS;
/// Words of one element of the resolve kernel's output: status, state.
pub const RESOLVE_OUTPUT_WORDS: usize = 1 + STATE_WORDS;

/// The WGSL constants of the layout and their values (checked against `ant_layout.wgsl` and
/// `ant_frame.wgsl` by a test).
pub const WGSL_CONSTANTS: &[(&str, usize)] = &[
    ("ANT_STATE_WORDS", STATE_WORDS),
    ("ANT_PLAN_WORDS", PLAN_WORDS),
    ("ANT_PARAMS_WORDS", PARAMS_WORDS),
    ("ANT_NEIGHBOR_WORDS", NEIGHBOUR_WORDS),
    ("ANT_OBJECT_WORDS", OBJECT_WORDS),
    ("ANT_SURFACE_WORDS", SURFACE_WORDS),
    ("ANT_PLAN_FRAME_WORDS", PLAN_FRAME_WORDS),
    ("ANT_RESOLVE_FRAME_WORDS", RESOLVE_FRAME_WORDS),
    ("ANT_CTX_WORDS", CTX_WORDS),
    ("ANT_PLAN_FRAME_NEIGHBOURS", 5),
    ("ANT_PLAN_FRAME_OBJECTS", 6 + N * NEIGHBOUR_WORDS),
    ("ANT_RESOLVE_FRAME_NEIGHBOURS", 5),
    ("ANT_RESOLVE_FRAME_OBSTACLES", 6 + 2 * N),
    ("ANT_NEIGHBOURS", N),
    ("ANT_OBJECTS", O),
    ("ANT_SURFACES", SURFACES),
];

// ---- packing ----

fn v2<S: Word>(out: &mut Vec<u32>, v: Vec2<S>) {
    out.extend([v.x.to_word(), v.y.to_word()]);
}

/// Appends the words of `s`.
pub fn write_state<S: Word>(out: &mut Vec<u32>, s: &AntState<S>) {
    v2(out, s.pos);
    v2(out, s.heading);
    out.extend([s.label as u32, s.nest.into(), s.origin.into()]);
    v2(out, s.arrival);
    match s.goal {
        Some(g) => {
            out.push(1);
            v2(out, g);
        }
        None => out.extend([0; 3]),
    }
    match s.follow {
        Some(f) => out.extend([1, f.turn as u32, f.winding.to_word()]),
        None => out.extend([0; 3]),
    }
    out.push(s.motion as u32);
    match s.stop {
        Some(t) => out.extend([1, t.reason as u32, t.remaining.into(), t.place.into()]),
        None => out.extend([0; 4]),
    }
}

/// Appends the words of `p`.
pub fn write_plan<S: Word>(out: &mut Vec<u32>, p: &AntPlan<S>) {
    write_state(out, &p.state);
    v2(out, p.predicted);
}

/// Appends the words of `p`.
pub fn write_params<S: Word>(out: &mut Vec<u32>, p: &AntParams<S>) {
    out.extend([
        p.speed.to_word(),
        p.dt.to_word(),
        p.theta.to_word(),
        p.p_stop.to_word(),
        p.casual_stop_ticks.into(),
        p.collect_ticks.into(),
        p.drop_ticks.into(),
        p.contact_range.to_word(),
        p.avoid_range.to_word(),
        p.collision_range.to_word(),
        p.w0.to_word(),
        p.c.to_word(),
        p.k.into(),
    ]);
}

/// Appends the words of `c`.
pub fn write_ctx(out: &mut Vec<u32>, c: StepCtx) {
    out.extend([c.seed, c.agent, c.step]);
}

fn rect<S: Word>(out: &mut Vec<u32>, r: Rect<S>) {
    v2(out, r.min);
    v2(out, r.max);
}

/// Appends the words of `f`.
pub fn write_plan_frame<S: Word>(out: &mut Vec<u32>, f: &AntPlanFrame<S>) {
    rect(out, f.bounds);
    out.push(f.neighbours.len() as u32);
    for n in &f.neighbours {
        out.push(n.id);
        v2(out, n.pos);
        out.extend([n.label as u32, n.nest.into(), n.origin.into()]);
        v2(out, n.arrival);
    }
    out.extend(std::iter::repeat_n(
        0,
        (N - f.neighbours.len()) * NEIGHBOUR_WORDS,
    ));
    out.push(f.objects.len() as u32);
    for o in &f.objects {
        let z = S::ZERO;
        let (kind, id, a, b, radius) = match *o {
            AntObject::Obstacle(s) => (0, 0, s.closest, s.normal, z),
            AntObject::Disturbance { center, radius } => (1, 0, center, Vec2::zero(), radius),
            AntObject::Food { id, center, radius } => (2, id, center, Vec2::zero(), radius),
            AntObject::Nest { id, center, radius } => (3, id, center, Vec2::zero(), radius),
        };
        out.extend([kind, u32::from(id)]);
        v2(out, a);
        v2(out, b);
        out.push(radius.to_word());
    }
    out.extend(std::iter::repeat_n(0, (O - f.objects.len()) * OBJECT_WORDS));
}

/// Appends the words of `f`.
pub fn write_resolve_frame<S: Word>(out: &mut Vec<u32>, f: &AntResolveFrame<S>) {
    rect(out, f.bounds);
    out.push(f.neighbours.len() as u32);
    for &p in &f.neighbours {
        v2(out, p);
    }
    out.extend(std::iter::repeat_n(0, (N - f.neighbours.len()) * 2));
    out.push(f.obstacles.len() as u32);
    for s in &f.obstacles {
        v2(out, s.closest);
        v2(out, s.normal);
    }
    out.extend(std::iter::repeat_n(
        0,
        (SURFACES - f.obstacles.len()) * SURFACE_WORDS,
    ));
}

/// Appends one element of the plan kernel's input ([`PLAN_INPUT_WORDS`]).
pub fn write_plan_input<S: Word>(
    out: &mut Vec<u32>,
    state: &AntState<S>,
    frame: &AntPlanFrame<S>,
    params: &AntParams<S>,
    ctx: StepCtx,
) {
    write_state(out, state);
    write_plan_frame(out, frame);
    write_params(out, params);
    write_ctx(out, ctx);
}

/// Appends one element of the resolve kernel's input ([`RESOLVE_INPUT_WORDS`]).
pub fn write_resolve_input<S: Word>(
    out: &mut Vec<u32>,
    plan: &AntPlan<S>,
    frame: &AntResolveFrame<S>,
    params: &AntParams<S>,
) {
    write_plan(out, plan);
    write_resolve_frame(out, frame);
    write_params(out, params);
}

/// Appends what the plan kernel writes for `r` ([`PLAN_OUTPUT_WORDS`]): the status, then the
/// plan (zero words for an error).
pub fn write_plan_result<S: Word>(out: &mut Vec<u32>, r: &std::result::Result<AntPlan<S>, Error>) {
    match r {
        Ok(p) => {
            out.push(0);
            write_plan(out, p);
        }
        Err(e) => {
            out.push(status_of(e));
            out.extend([0; PLAN_WORDS]);
        }
    }
}

/// Appends what the resolve kernel writes for `r` ([`RESOLVE_OUTPUT_WORDS`]): the status, then
/// the state (zero words for an error).
pub fn write_resolve_result<S: Word>(
    out: &mut Vec<u32>,
    r: &std::result::Result<AntState<S>, Error>,
) {
    match r {
        Ok(s) => {
            out.push(0);
            write_state(out, s);
        }
        Err(e) => {
            out.push(status_of(e));
            out.extend([0; STATE_WORDS]);
        }
    }
}

// ---- unpacking ----

/// The [`AntState`] next in `r`.
fn state<S: Word>(r: &mut Words<'_>) -> Result<AntState<S>> {
    let pos = r.v2();
    let heading = r.v2();
    let label = label(r.next())?;
    let nest = r.u16("nest id")?;
    let origin = r.u16("origin id")?;
    let arrival = r.v2();
    let goal = if r.flag()? {
        Some(r.v2())
    } else {
        r.skip(2);
        None
    };
    let follow = if r.flag()? {
        let turn = match r.next() {
            0 => Turn::Ccw,
            1 => Turn::Cw,
            word => return Err(SimError::GpuWords { what: "Turn", word }),
        };
        Some(Follow {
            turn,
            winding: r.s(),
        })
    } else {
        r.skip(2);
        None
    };
    let motion = match r.next() {
        0 => MotionState::Stop,
        1 => MotionState::BasicMovement,
        2 => MotionState::InteractNeighbors,
        3 => MotionState::InteractEnvironment,
        word => {
            return Err(SimError::GpuWords {
                what: "MotionState",
                word,
            });
        }
    };
    let stop = if r.flag()? {
        let reason = match r.next() {
            0 => StopReason::Casual,
            1 => StopReason::CollectingFood,
            2 => StopReason::DroppingFood,
            word => {
                return Err(SimError::GpuWords {
                    what: "StopReason",
                    word,
                });
            }
        };
        Some(StopTimer {
            reason,
            remaining: r.u16("stop.remaining")?,
            place: r.u16("stop.place")?,
        })
    } else {
        r.skip(3);
        None
    };
    Ok(AntState {
        pos,
        heading,
        label,
        nest,
        origin,
        arrival,
        goal,
        follow,
        motion,
        stop,
    })
}

fn label(word: u32) -> Result<Label> {
    match word {
        0 => Ok(Label::Nothing),
        1 => Ok(Label::Food),
        2 => Ok(Label::Nest),
        word => Err(SimError::GpuWords {
            what: "Label",
            word,
        }),
    }
}

/// The [`AntState`] of the first [`STATE_WORDS`] of `w` (missing words read as zero).
///
/// # Errors
///
/// [`SimError::GpuWords`] for a word no state has (an enum discriminant, a flag, a `u16`).
pub fn read_state<S: Word>(w: &[u32]) -> Result<AntState<S>> {
    state(&mut Words(w))
}

/// The [`AntPlan`] of the first [`PLAN_WORDS`] of `w`.
///
/// # Errors
///
/// As [`read_state`].
pub fn read_plan<S: Word>(w: &[u32]) -> Result<AntPlan<S>> {
    let mut r = Words(w);
    let state = state(&mut r)?;
    Ok(AntPlan {
        state,
        predicted: r.v2(),
    })
}

/// The [`AntParams`] of the first [`PARAMS_WORDS`] of `w`.
///
/// # Errors
///
/// [`SimError::GpuWords`] for a count too large for its field.
pub fn read_params<S: Word>(w: &[u32]) -> Result<AntParams<S>> {
    let mut r = Words(w);
    Ok(AntParams {
        speed: r.s(),
        dt: r.s(),
        theta: r.s(),
        p_stop: r.s(),
        casual_stop_ticks: r.u16("casual_stop_ticks")?,
        collect_ticks: r.u16("collect_ticks")?,
        drop_ticks: r.u16("drop_ticks")?,
        contact_range: r.s(),
        avoid_range: r.s(),
        collision_range: r.s(),
        w0: r.s(),
        c: r.s(),
        k: {
            let word = r.next();
            u8::try_from(word).map_err(|_| SimError::GpuWords { what: "k", word })?
        },
    })
}

/// The [`StepCtx`] of the first [`CTX_WORDS`] of `w`.
pub fn read_ctx(w: &[u32]) -> StepCtx {
    let mut r = Words(w);
    StepCtx {
        seed: r.next(),
        agent: r.next(),
        step: r.next(),
    }
}

/// The [`AntPlanFrame`] of the first [`PLAN_FRAME_WORDS`] of `w`.
///
/// # Errors
///
/// [`SimError::GpuWords`] for a list longer than its capacity or a word no entry has.
pub fn read_plan_frame<S: Word>(w: &[u32]) -> Result<AntPlanFrame<S>> {
    let mut r = Words(w);
    let mut f = AntPlanFrame::new(r.rect());
    let n = r.len(N)?;
    for _ in 0..n {
        let id = r.next();
        let pos = r.v2();
        let label = label(r.next())?;
        let nest = r.u16("neighbour nest")?;
        let origin = r.u16("neighbour origin")?;
        let arrival = r.v2();
        let _ = f.neighbours.push(AntNeighbor {
            id,
            pos,
            label,
            nest,
            origin,
            arrival,
        });
    }
    r.skip((N - n) * NEIGHBOUR_WORDS);
    let n = r.len(O)?;
    for _ in 0..n {
        let kind = r.next();
        let id = r.u16("object id")?;
        let a = r.v2();
        let b = r.v2();
        let radius = r.s();
        let o = match kind {
            0 => AntObject::Obstacle(Surface {
                closest: a,
                normal: b,
            }),
            1 => AntObject::Disturbance { center: a, radius },
            2 => AntObject::Food {
                id,
                center: a,
                radius,
            },
            3 => AntObject::Nest {
                id,
                center: a,
                radius,
            },
            word => {
                return Err(SimError::GpuWords {
                    what: "AntObject kind",
                    word,
                });
            }
        };
        let _ = f.objects.push(o);
    }
    Ok(f)
}

/// The [`AntResolveFrame`] of the first [`RESOLVE_FRAME_WORDS`] of `w`.
///
/// # Errors
///
/// [`SimError::GpuWords`] for a list longer than its capacity.
pub fn read_resolve_frame<S: Word>(w: &[u32]) -> Result<AntResolveFrame<S>> {
    let mut r = Words(w);
    let mut f = AntResolveFrame::new(r.rect());
    let n = r.len(N)?;
    for _ in 0..n {
        let _ = f.neighbours.push(r.v2());
    }
    r.skip((N - n) * 2);
    let n = r.len(SURFACES)?;
    for _ in 0..n {
        let closest = r.v2();
        let _ = f.obstacles.push(Surface {
            closest,
            normal: r.v2(),
        });
    }
    Ok(f)
}

// ---- status words ----

/// The fields the ant controller names in its errors, by their code in a status word
/// (`ANT_FIELD_*` in `shaders/ant_state.wgsl`; 0 is no field).
pub const FIELDS: [&str; 24] = [
    "",
    "state.pos",
    "state.arrival",
    "state.heading",
    "state.origin",
    "state.goal",
    "state.follow",
    "state.follow.winding",
    "state.stop.remaining",
    "state.stop.reason",
    "state.stop",
    "bounds",
    "neighbours.pos",
    "neighbours.arrival",
    "neighbours.id",
    "neighbours.origin",
    "objects.closest",
    "objects.normal",
    "objects.center",
    "objects.radius",
    "neighbours",
    "obstacles.closest",
    "obstacles.normal",
    "plan.predicted",
];

/// The kinds of error the ant kernels write: [`Error::NonFinite`], [`Error::OutOfRange`] and
/// [`Error::Inconsistent`].
const KINDS: u32 = 3;

/// The status word of a controller error, as the ant kernels write it: `kind | field << 8 |
/// (index + 1) << 16`, the kind 1 for [`Error::NonFinite`], 2 for [`Error::OutOfRange`], 3 for
/// [`Error::Inconsistent`]; `u32::MAX` for an error the ant controller never returns.
pub fn status_of(e: &Error) -> u32 {
    status::status_of(&FIELDS, KINDS, e)
}

/// The controller's answer of a status word: `Ok(())` for 0, else the [`Error`] it stands for.
///
/// # Errors
///
/// [`SimError::GpuWords`] for a word no ant kernel writes.
pub fn status_error(word: u32) -> Result<std::result::Result<(), Error>> {
    status::status_error(&FIELDS, KINDS, "ant status word", word)
}
