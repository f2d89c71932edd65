//! A tiny brute-force ant world for the example and the integration tests of `swarm-core`:
//! one nest, one food source, one round obstacle, O(n²) neighbour search. (The real
//! simulator, with grids, scenarios and outputs, is `swarm-sim`.)

#![allow(dead_code)]

use swarm_core::ant::{
    self, AntNeighbor, AntObject, AntParams, AntPlan, AntState, Label, PlanFrame, ResolveFrame,
    StopReason, Surface,
};
use swarm_core::rand::rand;
use swarm_core::{Rect, Scalar, StepCtx, Vec2};

/// Neighbour capacity of the frames.
pub const N: usize = 8;
/// Object capacity of the frames.
pub const O: usize = 4;
/// Radius within which an ant senses objects.
pub const SENSE: f32 = 8.0;

/// A round obstacle.
#[derive(Clone, Copy, Debug)]
pub struct Rock<S> {
    pub center: Vec2<S>,
    pub radius: S,
}

pub struct World<S: Scalar> {
    pub ants: Vec<AntState<S>>,
    pub bounds: Rect<S>,
    pub nest: (Vec2<S>, S),
    pub food: (Vec2<S>, S),
    pub rocks: Vec<Rock<S>>,
    pub params: AntParams<S>,
    pub seed: u32,
    pub step: u32,
    /// Food dropped at the nest so far.
    pub deliveries: u32,
}

impl<S: Scalar> World<S> {
    /// `n` ants leaving the nest at (20, 50) in random directions; food at (80, 50); a rock
    /// between them, off the straight line.
    pub fn demo(n: usize, seed: u32) -> Self {
        let v = Vec2::<S>::from_f32;
        let nest = (v(20.0, 50.0), S::from_f32(3.0));
        let ants = (0..n as u32)
            .map(|i| {
                let a = rand(seed, i, u32::MAX, 0) as f32 / u32::MAX as f32 * std::f32::consts::TAU;
                AntState::at_nest(0, nest.0, v(a.cos(), a.sin()))
            })
            .collect();
        World {
            ants,
            bounds: Rect::new(v(0.0, 0.0), v(100.0, 100.0)),
            nest,
            food: (v(80.0, 50.0), S::from_f32(4.0)),
            rocks: vec![Rock {
                center: v(50.0, 40.0),
                radius: S::from_f32(6.0),
            }],
            params: AntParams::default(),
            seed,
            step: 0,
            deliveries: 0,
        }
    }

    pub fn ctx(&self, i: usize) -> StepCtx {
        StepCtx {
            seed: self.seed,
            agent: i as u32,
            step: self.step,
        }
    }

    /// The plan-phase sensor frame of ant `i`: its nearest neighbours in contact range
    /// (by distance, then id) and the objects in sensing range.
    pub fn plan_frame(&self, i: usize) -> PlanFrame<S, N, O> {
        let me = &self.ants[i];
        let mut f = PlanFrame::new(self.bounds);
        let mut near: Vec<(S, usize)> = self
            .ants
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(j, a)| ((a.pos - me.pos).length_sq(), j))
            .filter(|&(d2, _)| d2 <= self.params.contact_range * self.params.contact_range)
            .collect();
        near.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap().then(a.1.cmp(&b.1)));
        for &(_, j) in near.iter().take(N) {
            let a = &self.ants[j];
            let _ = f.neighbours.push(AntNeighbor {
                id: j as u32,
                pos: a.pos,
                label: a.label,
                nest: a.nest,
                origin: a.origin,
                arrival: a.arrival,
            });
        }
        let sense = S::from_f32(SENSE);
        for r in &self.rocks {
            let d = me.pos - r.center;
            if let Some(u) = d.normalized() {
                let closest = r.center + u * r.radius;
                if (closest - me.pos).length() <= sense
                    && let Some(surface) = Surface::seen_from(me.pos, closest)
                {
                    let _ = f.objects.push(AntObject::Obstacle(surface));
                }
            }
        }
        if (self.food.0 - me.pos).length() <= sense + self.food.1 {
            let _ = f.objects.push(AntObject::Food {
                id: 1,
                center: self.food.0,
                radius: self.food.1,
            });
        }
        if (self.nest.0 - me.pos).length() <= sense + self.nest.1 {
            let _ = f.objects.push(AntObject::Nest {
                id: 0,
                center: self.nest.0,
                radius: self.nest.1,
            });
        }
        f
    }

    /// The resolve-phase frame of ant `i`: the predictions of the ants predicted nearby.
    pub fn resolve_frame(&self, plans: &[AntPlan<S>], i: usize) -> ResolveFrame<S, N> {
        let me = plans[i].predicted;
        let mut near: Vec<(S, usize)> = plans
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(j, p)| ((p.predicted - me).length_sq(), j))
            .filter(|&(d2, _)| d2 < self.params.collision_range * self.params.collision_range)
            .collect();
        near.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap().then(a.1.cmp(&b.1)));
        let mut f = ResolveFrame::new(self.bounds);
        for &(_, j) in near.iter().take(N) {
            let _ = f.neighbours.push(plans[j].predicted);
        }
        f
    }

    /// One tick: every ant plans, then every ant resolves with its neighbours' plans.
    pub fn step(&mut self) -> Vec<AntPlan<S>> {
        let plans: Vec<AntPlan<S>> = (0..self.ants.len())
            .map(|i| {
                ant::plan(
                    &self.ants[i],
                    &self.plan_frame(i),
                    &self.params,
                    self.ctx(i),
                )
                .expect("valid world input")
            })
            .collect();
        for i in 0..self.ants.len() {
            let next = ant::resolve(&plans[i], &self.resolve_frame(&plans, i), &self.params)
                .expect("valid world input");
            let was_dropping = self.ants[i]
                .stop
                .is_some_and(|t| t.reason == StopReason::DroppingFood);
            if was_dropping && next.label == Label::Nest && self.ants[i].label == Label::Food {
                self.deliveries += 1;
            }
            self.ants[i] = next;
        }
        self.step += 1;
        plans
    }

    /// How many ants carry each label (Nothing, Food, Nest).
    pub fn label_counts(&self) -> [usize; 3] {
        let mut c = [0; 3];
        for a in &self.ants {
            c[a.label as usize] += 1;
        }
        c
    }

    /// An order-sensitive FNV-1a hash of every ant's position and heading bits.
    pub fn hash(&self) -> u64 {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        for a in &self.ants {
            for x in [a.pos.x, a.pos.y, a.heading.x, a.heading.y] {
                for b in x.to_f32().to_bits().to_le_bytes() {
                    h = (h ^ b as u64).wrapping_mul(0x100_0000_01b3);
                }
            }
        }
        h
    }
}
