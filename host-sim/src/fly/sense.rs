//! The sensor frame of a ren2016 insect, built from the world as a drone would sense it (spec
//! §1.5 step 1): the nearest neighbours within r_att with their broadcast position and
//! velocity (nearest first, ties by id, at most [`N`]: the wire's capacity, so every run can be
//! mirrored on a device), the stimulus in range (a predator before a target), and the obstacle
//! surfaces within ORCA's reach. The HIL harness feeds devices with this same function.

use swarm_core::Vec3;
use swarm_core::fly::{
    FlyFrame, FlyParams, Neighbour, STIMULUS_PREDATOR, STIMULUS_TARGET, Stimulus,
    WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES,
};

use super::world::{FlyWorld, reach};
use crate::nearest::select;
use crate::scalar::{SimScalar, v3};
use crate::space::at;

/// Neighbour capacity of a fly frame (the wire's).
pub const N: usize = WIRE_FLY_NEIGHBOURS;
/// Surface capacity of a fly frame (the wire's).
pub const O: usize = WIRE_FLY_SURFACES;

/// The sensor frame of the simulator (and of the wire).
pub type FlySimFrame<S> = FlyFrame<S, N, O>;

/// The stimulus sources a group responds to (object ids).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stimuli {
    /// The target it pursues (its `goal`).
    pub goal: Option<u16>,
    /// The predator it escapes (its `threat`).
    pub threat: Option<u16>,
}

/// The frame of the insect in slot `slot` with parameters `p` responding to `stimuli`, and
/// whether more than [`N`] insects were within r_att (the frame was truncated: spec §2.1).
pub fn fly_frame<S: SimScalar>(
    w: &FlyWorld,
    slot: usize,
    p: &FlyParams<S>,
    stimuli: Stimuli,
) -> (FlySimFrame<S>, bool) {
    let me = v3::<S>(w.sensed.pos[slot]);
    let ids = &w.sensed.id;
    let pos = |j: u32, q: [f32; 3]| S::sensed3(q, || w.sensed.pos[j as usize]);
    let near = select::<S, N>(&w.grid, me, p.r_att.to_f32(), slot as u32, pos, |j| {
        ids[j as usize]
    });
    let mut frame = FlySimFrame::new();
    for j in near.slots() {
        // At most N selected: no push can fail.
        let _ = frame.neighbours.push(Neighbour {
            id: ids[j],
            pos: v3(w.sensed.pos[j]),
            vel: v3(w.sensed.vel[j]),
        });
    }
    frame.stimulus = stimulus(w, me, p.r_res, stimuli);
    frame.surfaces = w.surfaces(me, reach(p.orca_radius(), p.tau, p.max_speed));
    (frame, near.within > N)
}

/// The stimulus of an insect at `me` with visual range `r_res` (spec §2.3, R12): the threat
/// if it is active and within r_res (H(0) = 1), else the goal if it is.
fn stimulus<S: SimScalar>(
    w: &FlyWorld,
    me: Vec3<S>,
    r_res: S,
    stimuli: Stimuli,
) -> Option<Stimulus<S>> {
    let r2 = r_res * r_res;
    let sensed = |id: Option<u16>, kind| {
        let c = at::<S>(w.source(id?)?);
        ((c - me).length_sq() <= r2).then_some(Stimulus { pos: c, kind })
    };
    sensed(stimuli.threat, STIMULUS_PREDATOR).or_else(|| sensed(stimuli.goal, STIMULUS_TARGET))
}
