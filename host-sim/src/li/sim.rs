//! The li2015 engine on the CPU: every insect goes through `swarm_core::li::step_checked` each
//! step (its waypoint, the preferred velocity, ORCA, the move) on the frame [`li_frame`]
//! builds from the world, in parallel and deterministically: a step reads only what every
//! insect broadcast at the previous one, so any thread count gives the same bits. The world
//! (the container, its obstacles, the sensed insects: the fly's [`FlyWorld`]) is the
//! backstop that keeps the new states physical, and counts each correction.

use rayon::prelude::*;
use swarm_core::li::{self, LiDecision, LiFrame, LiParams, LiState, WIRE_LI_NEIGHBOURS};
use swarm_core::li::{WIRE_LI_SURFACES, density::Density};
use swarm_core::{Checked, Fx, Scalar, StepCtx, Vec3};

use crate::by_scalar;
use crate::error::{Result, SimError};
use crate::fly::{FlyWorld, Kinematic, reach};
use crate::grid::permuted;
use crate::nearest::select;
use crate::par::for_each_agent;
use crate::scalar::{AgentGroup, ByScalar, SimScalar, v3};

/// Neighbour capacity of a li frame (the wire's).
pub const N: usize = WIRE_LI_NEIGHBOURS;
/// Surface capacity of a li frame (the wire's).
pub const O: usize = WIRE_LI_SURFACES;

/// The sensor frame of the simulator (and of the wire).
pub type LiSimFrame<S> = LiFrame<S, N, O>;

impl<S: SimScalar> Kinematic<S> for LiState<S> {
    fn kinematics(&self) -> (Vec3<S>, Vec3<S>) {
        (self.pos, self.vel)
    }
    fn kinematics_mut(&mut self) -> (&mut Vec3<S>, &mut Vec3<S>) {
        (&mut self.pos, &mut self.vel)
    }
}

/// The frame of the insect in slot `slot` with parameters `p`: its nearest [`N`] neighbours
/// strictly within the neighbour distance (nearest first, ties by id) with their broadcast
/// position and velocity, the surfaces within ORCA's reach; and whether more were in range.
pub fn li_frame<S: SimScalar>(w: &FlyWorld, slot: usize, p: &LiParams<S>) -> (LiSimFrame<S>, bool) {
    let me = v3::<S>(w.sensed.pos[slot]);
    let ids = &w.sensed.id;
    let pos = |j: u32, q: [f32; 3]| S::sensed3(q, || w.sensed.pos[j as usize]);
    let near = select::<S, N>(&w.grid, me, p.range.to_f32(), slot as u32, pos, |j| {
        ids[j as usize]
    });
    let mut frame = LiSimFrame::new();
    for j in near.slots() {
        // At most N selected: no push can fail.
        let _ = frame.neighbours.push(li::LiNeighbour {
            id: ids[j],
            pos: v3(w.sensed.pos[j]),
            vel: v3(w.sensed.vel[j]),
        });
    }
    frame.surfaces = w.surfaces(me, reach(p.orca_radius(), p.tau, p.speed));
    (frame, near.within > N)
}

/// What happened in one step, or since the start (one count per insect and step).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Insects that arrived and proposed waypoints.
    pub arrivals: u64,
    /// Waypoints proposed.
    pub proposals: u64,
    /// Arrivals whose every proposal was rejected (the insect held).
    pub held: u64,
    /// Insects whose ORCA program was infeasible (the fallback acted).
    pub infeasible: u64,
    /// Insects with more neighbours in range than the frame holds.
    pub truncated: u64,
    /// Insects the world put back out of an obstacle or inside the container.
    pub corrected: u64,
}

impl std::ops::AddAssign for Counts {
    fn add_assign(&mut self, o: Counts) {
        self.arrivals += o.arrivals;
        self.proposals += o.proposals;
        self.held += o.held;
        self.infeasible += o.infeasible;
        self.truncated += o.truncated;
        self.corrected += o.corrected;
    }
}

/// A group of insects sharing parameters (their data included) and a scalar type. It owns
/// the world slots `first..first + len`; `ids` keeps each insect's stable id while slots are
/// reordered.
#[derive(Clone, Debug)]
pub struct LiGroup<S> {
    /// Group name.
    pub name: String,
    /// First world slot of the group.
    pub first: usize,
    /// Controller parameters (validated).
    pub params: Checked<LiParams<S>>,
    /// Current states, by slot.
    pub states: Vec<LiState<S>>,
    /// Stable agent id of each slot.
    pub ids: Vec<u32>,
    /// The last step's decisions, by slot.
    pub decisions: Vec<LiDecision<S>>,
    /// Whether each insect's last frame was truncated.
    pub truncated: Vec<bool>,
    /// What the world corrected at the last step, by slot (bit 0 an obstacle, bit 1 a wall).
    pub corrected: Vec<u8>,
    /// Visits of each cell of the group's density grid since the start (every insect, every
    /// measured step): the accumulated density of Fig. 4.
    pub visits: Vec<u64>,
    pub(crate) next: Vec<LiState<S>>,
}

impl<S: SimScalar> LiGroup<S> {
    /// A group of insects starting in `states`, occupying slots (and ids) from `first` on.
    pub fn new(
        name: String,
        first: usize,
        params: Checked<LiParams<S>>,
        states: Vec<LiState<S>>,
    ) -> Self {
        let n = states.len();
        LiGroup {
            name,
            first,
            visits: vec![0; params.density.weights.len()],
            params,
            ids: (first as u32..(first + n) as u32).collect(),
            decisions: vec![LiDecision::default(); n],
            truncated: vec![false; n],
            corrected: vec![0; n],
            next: states.clone(),
            states,
        }
    }

    /// The random-number context of group slot `k` at step `step`.
    pub(crate) fn ctx(&self, seed: u32, step: u32, k: usize) -> StepCtx {
        StepCtx {
            seed,
            agent: self.ids[k],
            step,
        }
    }

    /// Runs every insect's step on its frame: the decisions and the next states as the
    /// controller gave them (not yet kept physical).
    fn decide(&mut self, w: &FlyWorld, seed: u32, step: u32) -> Result<()> {
        let (mut next, mut decisions, mut truncated) = (
            std::mem::take(&mut self.next),
            std::mem::take(&mut self.decisions),
            std::mem::take(&mut self.truncated),
        );
        let this = &*self;
        let result = for_each_agent(
            next.par_iter_mut()
                .zip(decisions.par_iter_mut())
                .zip(truncated.par_iter_mut()),
            || (),
            |(), k, ((out, dec), cut)| {
                let (frame, more) = li_frame(w, this.first + k, &this.params);
                let ctx = this.ctx(seed, step, k);
                let (s, d) = li::step_checked(&this.states[k], &frame, &this.params, ctx)
                    .map_err(|e| SimError::controller("li step", step, ctx.agent, e))?;
                (*out, *dec, *cut) = (s, d, more);
                Ok(())
            },
        );
        self.next = next;
        self.decisions = decisions;
        self.truncated = truncated;
        result
    }

    /// Keeps the next states physical, makes them current and writes the sensed world;
    /// returns this step's counts.
    fn commit(&mut self, w: &mut FlyWorld) -> Counts {
        let world = &*w;
        self.next
            .par_iter_mut()
            .zip(self.corrected.par_iter_mut())
            .with_min_len(1024)
            .for_each(|(s, fix)| *fix = world.confine(s));
        w.sensed.write(self.first, &self.ids, &self.next);
        std::mem::swap(&mut self.states, &mut self.next);
        self.counts()
    }

    /// What happened to this group at the last step.
    pub fn counts(&self) -> Counts {
        let mut c = Counts::default();
        for ((d, &t), &fix) in self
            .decisions
            .iter()
            .zip(&self.truncated)
            .zip(&self.corrected)
        {
            let arrived = d.proposals > 0;
            c.arrivals += u64::from(arrived);
            c.proposals += u64::from(d.proposals);
            c.held += u64::from(arrived && !d.accepted);
            c.infeasible += u64::from(d.infeasible);
            c.truncated += u64::from(t);
            c.corrected += u64::from(fix != 0);
        }
        c
    }

    /// Counts every insect's cell of the density grid into [`LiGroup::visits`].
    fn measure(&mut self) {
        let d = &self.params.density;
        let Ok(grid) = Density::new(d.origin, d.cell, d.dims, &d.weights) else {
            return;
        };
        for s in &self.states {
            if let Some(i) = cell_index(&grid, d.dims, s.pos) {
                self.visits[i] += 1;
            }
        }
    }

    /// Sorts the group's slots by their cell in the world's grid: changes no result, only
    /// memory locality. Rewrites the group's part of the sensed world.
    fn reorder(&mut self, w: &mut FlyWorld) {
        let perm = w.grid.order_of(&self.states, |s| {
            let p = s.pos.to_f32();
            [p.x, p.y, p.z]
        });
        self.states = permuted(&self.states, &perm);
        self.decisions = permuted(&self.decisions, &perm);
        self.truncated = permuted(&self.truncated, &perm);
        self.corrected = permuted(&self.corrected, &perm);
        self.ids = permuted(&self.ids, &perm);
        self.next.clone_from(&self.states);
        w.sensed.write(self.first, &self.ids, &self.states);
    }

    /// This step's next states as the controller gave them, by slot (after
    /// [`LiSim::decide_all`], before [`LiSim::publish`]).
    pub(crate) fn decided(&self) -> &[LiState<S>] {
        &self.next
    }

    /// The total variation between the accumulated density ([`LiGroup::visits`]) and the
    /// group's target grid w_c, both normalised (L-T7); `None` before any visit.
    pub fn density_tv(&self) -> Option<f64> {
        total_variation(&self.visits, &self.params.density.weights)
    }
}

/// The flat index (x fastest) of the cell of `grid` holding `p`.
fn cell_index<S: Scalar>(grid: &Density<'_, S>, dims: [u16; 3], p: Vec3<S>) -> Option<usize> {
    let [x, y, z] = grid.cell_of(p)?.map(usize::from);
    let [nx, ny, _] = dims.map(usize::from);
    Some(x + nx * (y + ny * z))
}

/// ½ Σ |a_c/Σa − b_c/Σb|: the total variation between two histograms on the same cells;
/// `None` when either is empty.
pub fn total_variation(a: &[u64], b: &[u8]) -> Option<f64> {
    let sa: u64 = a.iter().sum();
    let sb: u64 = b.iter().map(|&w| u64::from(w)).sum();
    if sa == 0 || sb == 0 || a.len() != b.len() {
        return None;
    }
    let tv = a
        .iter()
        .zip(b)
        .map(|(&x, &w)| (x as f64 / sa as f64 - f64::from(w) / sb as f64).abs())
        .sum::<f64>();
    Some(0.5 * tv)
}

/// A group of either scalar type.
pub type AnyLiGroup = ByScalar<LiGroup<f32>, LiGroup<Fx>>;

crate::scalar::agent_group!(LiGroup);

/// A li2015 swarm (or several groups) in its world.
#[derive(Clone, Debug)]
pub struct LiSim {
    /// The container, its obstacles and the sensed state of every insect.
    pub world: FlyWorld,
    /// The groups, in slot order.
    pub groups: Vec<AnyLiGroup>,
    /// The run's seed (waypoint proposals, spawn).
    pub seed: u32,
    /// The next step to run.
    pub step: u32,
    /// Re-sort the slots by grid cell every this many steps (0: never). Changes no result.
    pub reorder_every: u32,
    /// What happened at the last step.
    pub last: Counts,
    /// What happened since the start.
    pub total: Counts,
    /// Σ of the polarisation (Eq. 8) after each measured step.
    pub polarisation: f64,
    /// Σ of the mean distance to the swarm's centroid after each measured step.
    pub centroid_distance: f64,
    /// The steps measured.
    pub measured: u64,
    /// Insects closer than this count as a collision: 2·radius (the groups' largest).
    pub collision_distance: f32,
}

impl LiSim {
    /// A simulation of `groups` (contiguous slots, in order) in `world`.
    pub fn new(mut world: FlyWorld, groups: Vec<AnyLiGroup>, seed: u32) -> Self {
        let n = groups.iter().map(AnyLiGroup::len).sum();
        world.resize(n);
        for g in &groups {
            by_scalar!(g, g => world.sensed.write(g.first, &g.ids, &g.states));
        }
        let radius = groups
            .iter()
            .map(|g| by_scalar!(g, g => g.params.radius.to_f32()))
            .fold(0.0, f32::max);
        let mut sim = LiSim {
            world,
            groups,
            seed,
            step: 0,
            reorder_every: 16,
            last: Counts::default(),
            total: Counts::default(),
            polarisation: 0.0,
            centroid_distance: 0.0,
            measured: 0,
            collision_distance: 2.0 * radius,
        };
        sim.reorder();
        sim
    }

    /// Number of insects.
    pub fn agents(&self) -> usize {
        self.world.len()
    }

    /// Sorts every group's slots by grid cell (memory locality for the neighbour queries).
    pub fn reorder(&mut self) {
        self.world.index_positions();
        for g in &mut self.groups {
            by_scalar!(g, g => g.reorder(&mut self.world));
        }
    }

    /// Every insect decides from the previous step's sensed world (nothing is published).
    ///
    /// # Errors
    ///
    /// [`SimError::Controller`] for a frame or state the controller refused.
    pub fn decide_all(&mut self) -> Result<()> {
        let (seed, step) = (self.seed, self.step);
        self.world.index_positions();
        for g in &mut self.groups {
            by_scalar!(g, g => g.decide(&self.world, seed, step))?;
        }
        Ok(())
    }

    /// Confines the decided states, makes them current (broadcast) and moves the step on;
    /// returns this step's counts.
    pub fn publish(&mut self) -> Counts {
        let mut c = Counts::default();
        for g in &mut self.groups {
            c += by_scalar!(g, g => g.commit(&mut self.world));
        }
        self.last = c;
        self.total += c;
        self.step += 1;
        if self.reorder_every > 0 && self.step.is_multiple_of(self.reorder_every) {
            self.reorder();
        }
        c
    }

    /// One whole step ([`LiSim::decide_all`] then [`LiSim::publish`]).
    ///
    /// # Errors
    ///
    /// As [`LiSim::decide_all`].
    pub fn step(&mut self) -> Result<Counts> {
        self.decide_all()?;
        Ok(self.publish())
    }

    /// Every insect's position, in id order.
    pub fn positions_by_id(&self) -> Vec<[f64; 3]> {
        by_id(&self.world.sensed.id, &self.world.sensed.pos)
    }

    /// Every insect's actual velocity, in id order.
    pub fn velocities_by_id(&self) -> Vec<[f64; 3]> {
        by_id(&self.world.sensed.id, &self.world.sensed.vel)
    }

    /// Adds this step to the accumulated density, the polarisation and the distance to the
    /// centroid.
    pub fn measure(&mut self) {
        for g in &mut self.groups {
            by_scalar!(g, g => g.measure());
        }
        let pos = &self.world.sensed.pos;
        self.polarisation += crate::eval::frame_polarisation(&self.world.sensed.vel);
        self.centroid_distance += mean_centroid_distance(pos);
        self.measured += 1;
    }

    /// The accumulated-density total variation to the target (L-T7), the groups' weighted by
    /// their insects; `None` before any measured step.
    pub fn density_tv(&self) -> Option<f64> {
        let mut sum = 0.0;
        let mut n = 0usize;
        for g in &self.groups {
            let (tv, len) = by_scalar!(g, g => (g.density_tv(), g.states.len()));
            sum += tv? * len as f64;
            n += len;
        }
        (n > 0).then(|| sum / n as f64)
    }
}

/// `values` (by slot) in id order.
fn by_id(ids: &[u32], values: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut out = vec![[0.0; 3]; ids.len()];
    for (v, &id) in values.iter().zip(ids) {
        out[id as usize] = *v;
    }
    out
}

/// The mean distance of `points` to their centroid (0 for none).
pub fn mean_centroid_distance(points: &[[f64; 3]]) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    let n = points.len() as f64;
    let c = [0, 1, 2].map(|k| points.iter().map(|p| p[k]).sum::<f64>() / n);
    points
        .iter()
        .map(|p| (0..3).map(|k| (p[k] - c[k]).powi(2)).sum::<f64>().sqrt())
        .sum::<f64>()
        / n
}
