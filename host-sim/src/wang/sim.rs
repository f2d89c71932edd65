//! The wang2014 engine: a tick is two phases, like the controller's.
//!
//! 1. **advect** (eq. 9): every insect reads the fields at its position (the navigation
//!    direction of its goal's cost field, the nearest boundary of eq. 2, the lamp) and moves
//!    to its tentative position x* = x + V·Δt; the world then puts any x* inside an obstacle
//!    back on its surface (spec §1.6 step 2, counted) and broadcasts the x*.
//! 2. **separate** (MDE, §6): every insect is pushed apart from the neighbours whose x* came
//!    closer than d_min (Jacobi: from the broadcast x* only), and the world confines the
//!    result again.
//!
//! Both phases read only what the previous one published, so they run in parallel and give
//! the same bits on any thread count.

use rayon::prelude::*;
use swarm_core::wang::{
    self, AdvectFrame, Close, SeparateFrame, WIRE_WANG_NEIGHBOURS, WangParams, WangState,
};
use swarm_core::{Checked, Fx, StepCtx, Vec3};

use super::world::WangWorld;
use crate::by_scalar;
use crate::error::{Result, SimError};
use crate::grid::permuted;
use crate::nearest::select;
use crate::par::for_each_agent_by;
use crate::scalar::{AgentGroup, ByScalar, SimScalar, a3, a3f, v3};
use crate::space::confine;

/// Insects whose field cells [`WangGroup::warm`] loads at once, ahead of their steps.
const WARM_BLOCK: usize = 64;

/// The MDE neighbours of a separate frame (the wire's capacity).
pub const K: usize = WIRE_WANG_NEIGHBOURS;

/// The separate-phase frame of the simulator (and of the wire).
pub type WangSeparateFrame<S> = SeparateFrame<S, K>;

/// What the world corrected and MDE did in one step, or since the start.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Insects put back on an obstacle's surface.
    pub obstacle: u64,
    /// Insects clamped into the bounds.
    pub bounds: u64,
    /// Insects MDE displaced (one per insect and step, however many neighbours pushed it).
    pub pushed: u64,
}

impl std::ops::AddAssign for Counts {
    fn add_assign(&mut self, o: Counts) {
        self.obstacle += o.obstacle;
        self.bounds += o.bounds;
        self.pushed += o.pushed;
    }
}

/// A group of insects sharing parameters, a goal and a scalar type. The group owns the world
/// slots `first..first + len`; `ids` keeps each insect's stable id while slots are reordered.
#[derive(Clone, Debug)]
pub struct WangGroup<S> {
    /// Group name.
    pub name: String,
    /// First world slot of the group.
    pub first: usize,
    /// Controller parameters (validated).
    pub params: Checked<WangParams<S>>,
    /// Object id of the group's goal.
    pub goal: u16,
    /// Current states, by slot.
    pub states: Vec<WangState<S>>,
    /// Stable agent id of each slot.
    pub ids: Vec<u32>,
    /// The advect phase's replies (x*, V), as the controller gave them.
    pub moved: Vec<WangState<S>>,
    /// x* after the world's corrections: what the separate phase starts from.
    pub placed: Vec<WangState<S>>,
    /// The separate phase's replies (x_{k+1}), as the controller gave them.
    pub next: Vec<WangState<S>>,
    /// How many neighbours pushed each insect at the last step.
    pub pushes: Vec<u8>,
    /// What the world corrected at the last step, by slot: bit 0 an obstacle, bit 1 the bounds.
    pub corrected: Vec<u8>,
}

impl<S: SimScalar> WangGroup<S> {
    /// A group of insects starting in `states`, occupying slots (and ids) from `first` on.
    pub fn new(
        name: String,
        first: usize,
        params: Checked<WangParams<S>>,
        goal: u16,
        states: Vec<WangState<S>>,
    ) -> Self {
        let n = states.len();
        WangGroup {
            name,
            first,
            params,
            goal,
            ids: (first as u32..(first + n) as u32).collect(),
            moved: states.clone(),
            placed: states.clone(),
            next: states.clone(),
            pushes: vec![0; n],
            corrected: vec![0; n],
            states,
        }
    }

    /// The advect frame of the insect in group slot `k` at state `s` (the navigation
    /// direction of the group's goal field, the nearest boundary within d0, the lamp when the
    /// group has phototaxis).
    pub fn advect_frame(&self, w: &WangWorld, s: &WangState<S>) -> AdvectFrame<S> {
        AdvectFrame {
            guide: w
                .field(self.goal)
                .map_or(Vec3::zero(), |f| f.guide_at(s.pos)),
            boundary: w.boundary(s.pos, self.params.d0),
            lamp: self.lamp(w),
        }
    }

    /// The lamp of the group's advect frames: its goal's centre while the goal is present,
    /// when the group has phototaxis (p_photo > 0).
    pub fn lamp(&self, w: &WangWorld) -> Option<Vec3<S>> {
        (self.params.p_photo > S::ZERO)
            .then(|| w.goal_center(self.goal))
            .flatten()
            .map(|c| Vec3::from_f32(c[0], c[1], c[2]))
    }

    /// The separate frame of the insect in world slot `slot`: the `K` nearest broadcast x*
    /// strictly within d_min, nearest first, ties by id.
    pub fn separate_frame(&self, w: &WangWorld, slot: usize) -> WangSeparateFrame<S> {
        let me = v3::<S>(w.moved[slot]);
        let ids = &w.id;
        let at = |j: u32, q: [f32; 3]| S::sensed3(q, || w.moved[j as usize]);
        let d_min = self.params.d_min.to_f32();
        let mut frame = SeparateFrame::new();
        if d_min <= 0.0 {
            return frame;
        }
        let near = select::<S, K>(&w.mde_grid, me, d_min, slot as u32, at, |j| ids[j as usize]);
        for j in near.slots() {
            let _ = frame.neighbours.push(Close {
                id: ids[j],
                pos: v3(w.moved[j]),
            });
        }
        frame
    }

    /// The random-number context of group slot `k`.
    fn ctx(&self, seed: u32, step: u32, k: usize) -> StepCtx {
        StepCtx {
            seed,
            agent: self.ids[k],
            step,
        }
    }

    /// Touches the goal field's cells that the insects in slots `k..k + WARM_BLOCK` will
    /// sample ([`CostField::warm`](crate::fields::CostField::warm)): their cache misses then
    /// overlap instead of stalling one insect after another. Changes no result.
    fn warm(&self, w: &WangWorld, k: usize) {
        let Some(field) = w.field(self.goal) else {
            return;
        };
        let end = (k + WARM_BLOCK).min(self.states.len());
        let mut acc = 0;
        for s in &self.states[k..end] {
            acc ^= field.warm(a3f(s.pos));
        }
        std::hint::black_box(acc);
    }

    /// Phase 1: every insect's tentative move (eq. 9).
    fn advect(&mut self, w: &WangWorld, seed: u32, step: u32) -> Result<()> {
        let mut moved = std::mem::take(&mut self.moved);
        let this = &*self;
        let result = for_each_agent_by(
            moved.par_iter_mut(),
            |k| u64::from(this.ids[k]),
            || (),
            |(), k, out| {
                if k % WARM_BLOCK == 0 {
                    this.warm(w, k);
                }
                let s = &this.states[k];
                let frame = this.advect_frame(w, s);
                let ctx = this.ctx(seed, step, k);
                *out = wang::advect_checked(s, &frame, &this.params, ctx)
                    .map_err(|e| SimError::controller("wang advect", step, ctx.agent, e))?;
                Ok(())
            },
        );
        self.moved = moved;
        result
    }

    /// Keeps x* physical and broadcasts it (one parallel pass: copy, confine, broadcast).
    fn place(&mut self, w: &mut WangWorld) -> (u64, u64) {
        let (lo, hi) = (w.min, w.max);
        let r = self.first..self.first + self.states.len();
        let (obstacles, near) = (&w.obstacles, &w.near);
        let (moved, id) = (&mut w.moved[r.clone()], &mut w.id[r]);
        self.placed
            .par_iter_mut()
            .zip(self.moved.par_iter())
            .zip(self.corrected.par_iter_mut())
            .zip(moved.par_iter_mut().zip(id.par_iter_mut()))
            .zip(self.ids.par_iter())
            .with_min_len(1024)
            .for_each(|((((s, m), fix), (out, id)), &i)| {
                *s = *m;
                *fix = confine(obstacles, near, lo, hi, &mut s.pos, &mut s.vel);
                *out = a3(s.pos);
                *id = i;
            });
        tally(&self.corrected)
    }

    /// Phase 2: minimum distance enforcement.
    fn separate(&mut self, w: &WangWorld, seed: u32, step: u32) -> Result<()> {
        let first = self.first;
        let (mut next, mut pushes) = (
            std::mem::take(&mut self.next),
            std::mem::take(&mut self.pushes),
        );
        let this = &*self;
        let result = for_each_agent_by(
            next.par_iter_mut().zip(pushes.par_iter_mut()),
            |k| u64::from(this.ids[k]),
            || (),
            |(), k, (out, pushed)| {
                let frame = this.separate_frame(w, first + k);
                let ctx = this.ctx(seed, step, k);
                let (s, n) = wang::separate_checked(&this.placed[k], &frame, &this.params, ctx)
                    .map_err(|e| SimError::controller("wang separate", step, ctx.agent, e))?;
                *out = s;
                *pushed = n;
                Ok(())
            },
        );
        self.next = next;
        self.pushes = pushes;
        result
    }

    /// Confines x_{k+1}, makes it current; returns the corrections and the insects pushed.
    fn commit(&mut self, w: &WangWorld) -> Counts {
        let (lo, hi) = (w.min, w.max);
        let (obstacles, near) = (&w.obstacles, &w.near);
        // The decided states become current (`next` keeps the old ones until the next step).
        std::mem::swap(&mut self.states, &mut self.next);
        let (obstacle, bounds, pushed) = self
            .states
            .par_iter_mut()
            .zip(self.corrected.par_iter_mut())
            .zip(self.pushes.par_iter())
            .with_min_len(1024)
            .map(|((s, c), &n)| {
                // Not pushed, the state is x* as placed; if placing corrected nothing, x* was
                // physical and confining it again would change nothing: skipped, same bits.
                let fix = if n == 0 && *c == 0 {
                    0
                } else {
                    confine(obstacles, near, lo, hi, &mut s.pos, &mut s.vel)
                };
                *c |= fix;
                (
                    u64::from(fix & 1),
                    u64::from(fix >> 1 & 1),
                    u64::from(n > 0),
                )
            })
            .reduce(|| (0, 0, 0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
        Counts {
            obstacle,
            bounds,
            pushed,
        }
    }

    /// Sorts the group's slots by their cell in the MDE grid: changes no result, only memory
    /// locality.
    fn reorder(&mut self, w: &WangWorld) {
        let perm = w.mde_grid.order_of(&self.states, |s| {
            let p = s.pos.to_f32();
            [p.x, p.y, p.z]
        });
        self.states = permuted(&self.states, &perm);
        self.ids = permuted(&self.ids, &perm);
        self.pushes = permuted(&self.pushes, &perm);
        self.corrected = permuted(&self.corrected, &perm);
        self.moved.clone_from(&self.states);
        self.placed.clone_from(&self.states);
        self.next.clone_from(&self.states);
    }

    /// What the world corrected and MDE did to this group at the last step.
    pub fn counts(&self) -> Counts {
        let (obstacle, bounds) = tally(&self.corrected);
        Counts {
            obstacle,
            bounds,
            pushed: self.pushes.iter().filter(|&&n| n > 0).count() as u64,
        }
    }

    /// The states in id order.
    pub fn by_id(&self) -> Vec<(u32, WangState<S>)> {
        let mut v: Vec<_> = self
            .ids
            .iter()
            .copied()
            .zip(self.states.iter().copied())
            .collect();
        v.sort_unstable_by_key(|e| e.0);
        v
    }
}

/// (obstacle, bounds) corrections among `flags`.
fn tally(flags: &[u8]) -> (u64, u64) {
    flags.iter().fold((0, 0), |(o, b), &f| {
        (o + u64::from(f & 1), b + u64::from(f >> 1 & 1))
    })
}

/// A group of either scalar type.
pub type AnyWangGroup = ByScalar<WangGroup<f32>, WangGroup<Fx>>;

crate::scalar::agent_group!(WangGroup);

/// A wang2014 swarm (or several) in its world.
#[derive(Clone, Debug)]
pub struct WangSim {
    /// The world, its fields and the broadcast x*.
    pub world: WangWorld,
    /// The groups, in slot order.
    pub groups: Vec<AnyWangGroup>,
    /// The run's seed (phototaxis draws, random noise, coincident MDE pairs, spawn).
    pub seed: u32,
    /// The next step to run.
    pub step: u32,
    /// Re-sort the slots by grid cell every this many steps (0: never). Changes no result.
    pub reorder_every: u32,
    /// What happened at the last step.
    pub last: Counts,
    /// What happened since the start.
    pub total: Counts,
    /// The paper's measures over all insects, counted by
    /// [`Engine::after_tick`](crate::engine::Engine).
    pub metrics: super::Metrics,
    /// The same measures group by group.
    pub group_metrics: Vec<super::Metrics>,
}

impl WangSim {
    /// A simulation of `groups` (contiguous slots, in order) in `world`; solves the fields.
    ///
    /// # Errors
    ///
    /// What solving the fields refuses ([`WangWorld::solve_if_dirty`]).
    pub fn new(mut world: WangWorld, groups: Vec<AnyWangGroup>, seed: u32) -> Result<Self> {
        let n = groups.iter().map(AnyWangGroup::len).sum();
        world.resize(n);
        world.solve_if_dirty()?;
        let mut sim = WangSim {
            world,
            groups,
            seed,
            step: 0,
            reorder_every: 32,
            last: Counts::default(),
            total: Counts::default(),
            metrics: super::Metrics::default(),
            group_metrics: Vec::new(),
        };
        sim.reorder();
        sim.metrics = super::Metrics::new(sim.positions_by_id());
        sim.group_metrics = sim
            .groups
            .iter()
            .map(|g| by_scalar!(g, g => super::Metrics::new(g.by_id().iter().map(|(_, s)| a3(s.pos)).collect())))
            .collect();
        Ok(sim)
    }

    /// Number of insects.
    pub fn agents(&self) -> usize {
        self.world.moved.len()
    }

    /// Sorts every group's slots by grid cell.
    pub fn reorder(&mut self) {
        for g in &mut self.groups {
            by_scalar!(g, g => g.reorder(&self.world));
        }
        for g in &self.groups {
            by_scalar!(g, g => {
                for (k, s) in g.states.iter().enumerate() {
                    self.world.moved[g.first + k] = a3(s.pos);
                    self.world.id[g.first + k] = g.ids[k];
                }
            });
        }
    }

    /// Runs phase `phase` (0 advect, 1 separate) for every insect; publishes nothing.
    ///
    /// # Errors
    ///
    /// [`SimError::Controller`] for a refused frame; a field that cannot be solved.
    pub fn decide(&mut self, phase: usize) -> Result<()> {
        let (seed, step) = (self.seed, self.step);
        if phase == 0 {
            self.world.solve_if_dirty()?;
        }
        for g in &mut self.groups {
            by_scalar!(g, g => match phase {
                0 => g.advect(&self.world, seed, step),
                _ => g.separate(&self.world, seed, step),
            })?;
        }
        Ok(())
    }

    /// Publishes phase `phase`: after advect the corrected x* are broadcast (and indexed for
    /// MDE); after separate the new states are confined and made current, and the step ends.
    pub fn publish(&mut self, phase: usize) {
        if phase == 0 {
            let mut c = Counts::default();
            for g in &mut self.groups {
                let (o, b) = by_scalar!(g, g => g.place(&mut self.world));
                c.obstacle += o;
                c.bounds += b;
            }
            let w = &mut self.world;
            w.mde_grid
                .rebuild(&w.moved, |p| [p[0] as f32, p[1] as f32, p[2] as f32]);
            self.last = c;
            return;
        }
        let mut c = self.last;
        for g in &mut self.groups {
            c += by_scalar!(g, g => g.commit(&self.world));
        }
        self.last = c;
        self.total += c;
        self.step += 1;
        if self.reorder_every > 0 && self.step.is_multiple_of(self.reorder_every) {
            self.reorder();
        }
    }

    /// One whole tick.
    ///
    /// # Errors
    ///
    /// As [`WangSim::decide`].
    pub fn tick(&mut self) -> Result<Counts> {
        for phase in 0..2 {
            self.decide(phase)?;
            self.publish(phase);
        }
        Ok(self.last)
    }

    /// Every insect's position, in id order.
    pub fn positions_by_id(&self) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; self.agents()];
        for g in &self.groups {
            by_scalar!(g, g => for (s, &id) in g.states.iter().zip(&g.ids) {
                out[id as usize] = a3(s.pos);
            });
        }
        out
    }

    /// Counts the last step into the measures (overall and by group).
    pub fn measure(&mut self) {
        let mut all = Counts::default();
        for (g, m) in self.groups.iter().zip(&mut self.group_metrics) {
            by_scalar!(g, g => {
                let c = g.counts();
                let states = g.by_id();
                let pos: Vec<_> = states.iter().map(|(_, s)| a3(s.pos)).collect();
                let vel: Vec<_> = states.iter().map(|(_, s)| a3(s.vel)).collect();
                m.tick(c, &pos, &vel);
                all += c;
            });
        }
        let (pos, vel) = (self.positions_by_id(), self.velocities_by_id());
        self.metrics.tick(all, &pos, &vel);
    }

    /// Every insect's velocity V of its last step, in id order.
    pub fn velocities_by_id(&self) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; self.agents()];
        for g in &self.groups {
            by_scalar!(g, g => for (s, &id) in g.states.iter().zip(&g.ids) {
                out[id as usize] = a3(s.vel);
            });
        }
        out
    }
}
