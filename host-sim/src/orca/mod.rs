//! Crowds of agents avoiding each other with 3D ORCA ([`swarm_core::orca3d`]), stepped on the
//! host in parallel: RVO2-3D's `doStep` (van den Berg, Guy, Lin and Manocha, *Reciprocal
//! n-body collision avoidance*, ISRR 2009) with a uniform grid instead of its kd-tree.
//!
//! One [`OrcaCrowd::step`] is, for every agent, in parallel:
//!
//! 1. its `max_neighbors` nearest agents strictly within `neighbor_dist` (nearest first, ties by
//!    agent id, so the planes' order does not depend on memory layout or threads);
//! 2. [`orca3d::solve`] toward the caller's preferred velocity;
//!
//! and then every agent moves, `v ← v_new`, `p ← p + v·Δt` (Jacobi, like RVO2-3D: every
//! decision reads the previous step's positions and velocities only). The result is the same
//! bits on any number of threads (tested).
//!
//! Speed (issue 16: 5-6× RVO2-3D's agent-steps per second on two threads,
//! `docs/benchmarks.md`): the agents' memory slots follow the grid's cells, so the agents of a
//! cell share one copy of their candidate neighbours, whose distances are computed in
//! vectorised loops; the search for the `k` nearest starts from last step's `k`-th distance
//! (a hint that never changes the result). Nothing is allocated per agent.
//!
//! [`cube`] builds the benchmark scenario of issue 16 (`scripts/bench-orca.sh`, against
//! RVO2-3D); [`overlaps`] counts the pairs closer than two radii.

pub mod cube;
mod search;

use search::{Block, Search};

#[cfg(test)]
mod tests;

use rayon::prelude::*;
use swarm_core::orca3d::{self, Body, OrcaParams};
use swarm_core::{Error, Vec3};

use crate::error::{Result, SimError};
use crate::grid::{Grid, permuted};
use crate::par::for_each_agent_by;

pub use cube::{CUBE_RADIUS, Cube, random_cube, toward};

/// The most neighbours an agent takes into account (the capacity of the plane buffer).
pub const MAX_NEIGHBORS: usize = 16;

/// How a crowd is set up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrowdParams {
    /// Every agent's radius (≥ 0).
    pub radius: f32,
    /// Agents farther than this are not neighbours (> 0; RVO2-3D's `neighborDist`).
    pub neighbor_dist: f32,
    /// ORCA's parameters (`max_neighbors` at most [`MAX_NEIGHBORS`]).
    pub orca: OrcaParams<f32>,
    /// A safety margin (≥ 0) added to every agent's radius in ORCA's planes, never in
    /// [`OrcaCrowd::overlaps`]. ORCA steers agents onto each other's boundary, where `f32`
    /// rounding leaves pairs a few ulps inside two radii, and where its planes cannot all be
    /// met (LP4) or two agents are not among each other's nearest it lets them in deeper; a
    /// margin keeps them apart (0.01 for radius 1.5: `docs/benchmarks.md`, issue 16).
    pub margin: f32,
}

impl CrowdParams {
    /// The parameters of issue 16's benchmark (RVO2-3D's `Sphere` example): radius 1.5,
    /// neighbour distance 15, 10 neighbours, time horizon 10, time step 0.125, speed 2,
    /// RVO2-3D's `linearProgram4` fallback, no margin.
    pub fn rvo2_cube() -> CrowdParams {
        CrowdParams {
            radius: CUBE_RADIUS,
            neighbor_dist: 15.0,
            orca: OrcaParams {
                time_horizon: 10.0,
                dt: 0.125,
                max_speed: 2.0,
                max_neighbors: 10,
                fallback: orca3d::Fallback::Lp4,
            },
            margin: 0.0,
        }
    }

    /// `Err(GroupParams)` naming the parameter that is out of range.
    pub fn validate(&self) -> Result<()> {
        let bad = |field| SimError::GroupParams {
            group: "orca crowd".into(),
            source: Error::BadParam { field },
        };
        self.orca
            .validate()
            .map_err(|source| SimError::GroupParams {
                group: "orca crowd".into(),
                source,
            })?;
        if !(self.radius.is_finite() && self.radius >= 0.0) {
            return Err(bad("radius"));
        }
        if !(self.margin.is_finite() && self.margin >= 0.0) {
            return Err(bad("margin"));
        }
        if !(self.neighbor_dist.is_finite() && self.neighbor_dist > 0.0) {
            return Err(bad("neighbor_dist"));
        }
        if usize::from(self.orca.max_neighbors) > MAX_NEIGHBORS {
            return Err(bad("max_neighbors"));
        }
        Ok(())
    }
}

/// A crowd of ORCA agents: their bodies (position, velocity, radius) in memory slots that are
/// reordered by grid cell (for locality, every step by default), each with its stable id.
#[derive(Clone, Debug)]
pub struct OrcaCrowd {
    params: CrowdParams,
    /// The agents by slot.
    bodies: Vec<Body<f32>>,
    /// The id of the agent in each slot.
    ids: Vec<u32>,
    /// The next step's bodies (scratch).
    next: Vec<Body<f32>>,
    /// By slot: the distance within which the agent found its neighbours in the last step
    /// (infinity if it found fewer than `max_neighbors`), a hint for the next search.
    reach: Vec<f32>,
    next_reach: Vec<f32>,
    /// The neighbour grid and its search plan.
    search: Search,
    steps: u32,
    reorder_every: u32,
}

impl OrcaCrowd {
    /// A crowd at rest at `positions` (agent `i` at `positions[i]`).
    ///
    /// Errors: `GroupParams` for invalid `params` or a position that is not finite.
    pub fn new(positions: &[Vec3<f32>], params: CrowdParams) -> Result<OrcaCrowd> {
        params.validate()?;
        if positions
            .iter()
            .any(|p| !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()))
        {
            return Err(SimError::GroupParams {
                group: "orca crowd".into(),
                source: Error::NonFinite {
                    field: "positions",
                    index: None,
                },
            });
        }
        let bodies: Vec<Body<f32>> = positions
            .iter()
            .map(|&pos| Body {
                pos,
                vel: Vec3::zero(),
                radius: params.radius + params.margin,
            })
            .collect();
        Ok(OrcaCrowd {
            params,
            next: bodies.clone(),
            reach: vec![f32::INFINITY; bodies.len()],
            next_reach: vec![f32::INFINITY; bodies.len()],
            ids: (0..bodies.len() as u32).collect(),
            bodies,
            search: Search::default(),
            steps: 0,
            reorder_every: DEFAULT_REORDER_EVERY,
        })
    }

    /// The number of agents.
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// Whether the crowd has no agents.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// The steps taken so far.
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// The parameters.
    pub fn params(&self) -> &CrowdParams {
        &self.params
    }

    /// Reorders the memory slots by grid cell every `every` steps (0: never). Only the speed
    /// changes, never a result.
    pub fn set_reorder_every(&mut self, every: u32) {
        self.reorder_every = every;
    }

    /// Every agent's body, by id (its radius is [`CrowdParams::radius`] plus the margin).
    pub fn bodies(&self) -> Vec<Body<f32>> {
        let mut out = vec![Body::default(); self.bodies.len()];
        for (b, &id) in self.bodies.iter().zip(&self.ids) {
            out[id as usize] = *b;
        }
        out
    }

    /// Every agent's position, by id.
    pub fn positions(&self) -> Vec<Vec3<f32>> {
        self.bodies().into_iter().map(|b| b.pos).collect()
    }

    /// The pairs of agents closer than two radii (see [`overlaps`]).
    pub fn overlaps(&self) -> u64 {
        let pos: Vec<Vec3<f32>> = self.bodies.iter().map(|b| b.pos).collect();
        overlaps(&pos, self.params.radius)
    }

    /// One step: every agent's new velocity by ORCA toward `pref(id, position)` (its preferred
    /// velocity), then every agent moves. Runs on the current rayon pool.
    ///
    /// Errors: `Controller` (phase `orca`) when `orca3d::solve` refuses an agent's input (a
    /// preferred velocity that is not finite, ...); the crowd is then left as it was. Of
    /// several failing agents the one of the lowest id is reported.
    pub fn step<P>(&mut self, pref: P) -> Result<()>
    where
        P: Fn(u32, Vec3<f32>) -> Vec3<f32> + Sync,
    {
        self.index();
        if self.reorder_every > 0 && self.steps.is_multiple_of(self.reorder_every) {
            self.reorder();
        }
        let (mut next, mut reach) = (
            std::mem::take(&mut self.next),
            std::mem::take(&mut self.next_reach),
        );
        let this = &*self;
        let result = for_each_agent_by(
            next.par_iter_mut().zip(reach.par_iter_mut()),
            |k| u64::from(this.ids[k]),
            Block::default,
            |block, k, (out, reach)| {
                (*out, *reach) = this.advance(block, k, &pref)?;
                Ok(())
            },
        );
        (self.next, self.next_reach) = (next, reach);
        result?;
        std::mem::swap(&mut self.bodies, &mut self.next);
        std::mem::swap(&mut self.reach, &mut self.next_reach);
        self.steps += 1;
        Ok(())
    }

    /// Slot `k`'s body after this step, and the distance within which its neighbours were
    /// found.
    #[inline]
    fn advance<P>(&self, block: &mut Block, k: usize, pref: &P) -> Result<(Body<f32>, f32)>
    where
        P: Fn(u32, Vec3<f32>) -> Vec3<f32>,
    {
        let me = self.bodies[k];
        let id = self.ids[k];
        let mut near = [Body::default(); MAX_NEIGHBORS];
        let (n, reach) = self.neighbours(block, k, &mut near);
        let v = orca3d::solve::<f32, MAX_NEIGHBORS>(
            &me,
            &near[..n],
            &[],
            pref(id, me.pos),
            &self.params.orca,
        )
        .map_err(|e| SimError::controller("orca", self.steps, id, e))?
        .velocity;
        let next = Body {
            pos: me.pos + v * self.params.orca.dt,
            vel: v,
            radius: me.radius,
        };
        Ok((next, reach))
    }

    /// Fills `out` with slot `k`'s neighbours, nearest first; returns how many and the
    /// distance within which they were found ([`search::Found::reach`]).
    #[inline]
    fn neighbours(
        &self,
        block: &mut Block,
        k: usize,
        out: &mut [Body<f32>; MAX_NEIGHBORS],
    ) -> (usize, f32) {
        let o = &self.params.orca;
        // The last step's neighbours are still within this (up to rounding, which only costs
        // a second search).
        let hint = self.reach[k] * (1.0 + 1e-4) + 2.0 * o.max_speed * o.dt + 1e-3;
        let found = self.search.nearest(
            block,
            self.bodies[k].pos,
            usize::from(o.max_neighbors),
            hint,
            k as u32,
            &self.ids,
        );
        for (o, s) in out.iter_mut().zip(found.slots()) {
            *o = self.bodies[s];
        }
        (found.len(), found.reach())
    }

    /// Rebuilds the grid over the current positions (a new grid when they left its box).
    fn index(&mut self) {
        let (lo, hi) = bounds(&self.bodies, |b| [b.pos.x, b.pos.y, b.pos.z]);
        if !self.search.covers(lo, hi) {
            let range = self.params.neighbor_dist;
            let margin = 2.0 * range;
            let (lo, hi) = (lo.map(|x| x - margin), hi.map(|x| x + margin));
            let budget = (8 * self.bodies.len()).max(1 << 16);
            self.search = Search::new(lo, hi, range, budget);
        }
        self.search
            .rebuild(&self.bodies, |b| [b.pos.x, b.pos.y, b.pos.z]);
    }

    /// Puts the slots in the order of the grid's cells (neighbours close in memory, and the
    /// agents of a cell one after the other).
    fn reorder(&mut self) {
        let order = self.search.order();
        self.bodies = permuted(&self.bodies, order);
        self.ids = permuted(&self.ids, order);
        self.reach = permuted(&self.reach, order);
        self.search.renumber_in_order();
    }
}

/// Slots are reordered every this many steps by default (measured: `docs/benchmarks.md`).
const DEFAULT_REORDER_EVERY: u32 = 1;

/// The box around the points `pos(item)` (no items: the unit box at the origin).
fn bounds<T: Sync>(items: &[T], pos: impl Fn(&T) -> [f32; 3] + Sync) -> ([f32; 3], [f32; 3]) {
    let init = || ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    let (lo, hi) = items
        .par_iter()
        .with_min_len(4096)
        .fold(init, |(lo, hi), t| {
            let p = pos(t);
            (
                std::array::from_fn(|k| lo[k].min(p[k])),
                std::array::from_fn(|k| hi[k].max(p[k])),
            )
        })
        .reduce(init, |(a, b), (c, d)| {
            (
                std::array::from_fn(|k| a[k].min(c[k])),
                std::array::from_fn(|k| b[k].max(d[k])),
            )
        });
    if lo[0] > hi[0] {
        ([0.0; 3], [1.0; 3])
    } else {
        (lo, hi)
    }
}

/// The pairs of points closer than two radii (`|p_i − p_j|² < (2r)²`, in `f32`, as
/// `scripts/rvo2/random_cube.cc` counts them), found with a grid of cells of edge 2r.
pub fn overlaps(positions: &[Vec3<f32>], radius: f32) -> u64 {
    let cell = 2.0 * radius;
    if positions.len() < 2 || cell.is_nan() || cell <= 0.0 {
        return 0;
    }
    let pts: Vec<[f32; 3]> = positions.iter().map(|p| [p.x, p.y, p.z]).collect();
    let (lo, hi) = bounds(&pts, |p| *p);
    let mut grid = Grid::new(lo, hi, search::fitted_cell(lo, hi, cell, 4 * pts.len()));
    grid.rebuild(&pts, |p| *p);
    let limit = cell * cell;
    pts.par_iter()
        .enumerate()
        .map(|(i, &p)| {
            let mut n = 0u64;
            grid.for_each_candidate(p, cell, |j, q| {
                let d = Vec3::new(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
                n += u64::from(j as usize > i && d.length_sq() < limit);
            });
            n
        })
        .sum()
}
