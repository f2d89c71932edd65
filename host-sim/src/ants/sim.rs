//! The ant engine: every ant goes through `swarm_core::ant::plan` then `resolve` each tick,
//! in parallel (rayon) and deterministically: a tick reads only the previous tick's sensed
//! world, so any thread count gives the same bits.

use rayon::prelude::*;
use swarm_core::ant::{
    self, AntParams, AntPlan, AntState, Label, PlanFrame, ResolveFrame, StopReason,
};
use swarm_core::rand;
use swarm_core::{Checked, Fx, Rect, StepCtx, Vec2};

use super::sense::{
    Around, bounds, fill_plan_frame_noting, fill_resolve_frame, fill_resolve_frame_from,
};
use super::world::{AntObjectDef, AntObjectKind, AntWorld};
use crate::by_scalar;
use crate::error::{Result, SimError};
use crate::grid::permuted;
use crate::par::for_each_agent_by;
use crate::scalar::{AgentGroup, ByScalar, SimScalar, a2};

/// A group of ants sharing parameters and a scalar type. The group owns the world slots
/// `first..first + len`; slots are reordered now and then so that ants near each other in the
/// world are near each other in memory, and `ids` keeps each ant's stable id (the id its random
/// numbers, its neighbours and every output use).
#[derive(Clone, Debug)]
pub struct AntGroup<S> {
    /// Group name.
    pub name: String,
    /// First world slot of the group.
    pub first: usize,
    /// Controller parameters (validated).
    pub params: Checked<AntParams<S>>,
    /// Current states, by slot.
    pub states: Vec<AntState<S>>,
    /// Stable agent id of each slot.
    pub ids: Vec<u32>,
    plans: Vec<AntPlan<S>>,
    next: Vec<AntState<S>>,
    /// Per slot, the ants noted by this tick's plan query for the resolve frame.
    around: Vec<Around>,
}

impl<S: SimScalar> AntGroup<S> {
    /// A group of ants starting in `states`, occupying slots (and ids) from `first` on.
    pub fn new(
        name: String,
        first: usize,
        params: Checked<AntParams<S>>,
        states: Vec<AntState<S>>,
    ) -> Self {
        let plans = states
            .iter()
            .map(|s| AntPlan {
                state: *s,
                predicted: s.pos,
            })
            .collect();
        AntGroup {
            name,
            first,
            params,
            ids: (first as u32..(first + states.len()) as u32).collect(),
            next: states.clone(),
            around: vec![Around::default(); states.len()],
            states,
            plans,
        }
    }

    /// Every ant plans; each also notes the ants within `reach` for its resolve frame.
    fn plan(&mut self, w: &AntWorld, seed: u32, step: u32, reach: f32) -> Result<()> {
        let (first, params) = (self.first, &self.params);
        let idle = PlanFrame::new(bounds::<S>(w));
        let ids = &self.ids;
        for_each_agent_by(
            self.plans
                .par_iter_mut()
                .zip(self.around.par_iter_mut())
                .zip(self.states.par_iter().zip(ids.par_iter())),
            |k| u64::from(ids[k]),
            || idle.clone(),
            |frame, k, ((out, around), (s, &id))| {
                let ctx = StepCtx {
                    seed,
                    agent: id,
                    step,
                };
                // An ant that stays stopped this tick reads nothing of its frame
                // (xiang2018 §4.1): an empty one changes no result and saves the queries.
                let stays = s.stop.is_some_and(|t| t.remaining > 1);
                let frame = if stays {
                    &idle
                } else {
                    fill_plan_frame_noting(w, first + k, frame, Some((around, reach)));
                    &*frame
                };
                *out = ant::plan_checked(s, frame, params, ctx)
                    .map_err(|e| SimError::controller("ant plan", step, id, e))?;
                Ok(())
            },
        )
    }

    /// Publishes the plans' predictions p*(t+1); returns the largest distance between a
    /// prediction and its ant's sensed position.
    fn write_predictions(&self, w: &mut AntWorld) -> f32 {
        let r = self.first..self.first + self.plans.len();
        w.predicted[r.clone()]
            .par_iter_mut()
            .zip(&w.sensed.pos[r])
            .zip(&self.plans)
            .map(|((out, pos), p)| {
                *out = a2(p.predicted);
                let d = [out[0] - pos[0], out[1] - pos[1]];
                (d[0] * d[0] + d[1] * d[1]).sqrt() as f32
            })
            .reduce(|| 0.0, f32::max)
    }

    /// The longest step an ant of this group can predict: v·Δt·|O*| with |O*| < 1.01 (the
    /// state check), and some for the rounding.
    fn step_bound(&self) -> f32 {
        (self.params.speed * self.params.dt).to_f32().abs() * 1.02 + 1e-3
    }

    /// Every ant resolves; with `noted`, from the ants its plan query noted.
    fn resolve(&mut self, w: &AntWorld, step: u32, noted: bool) -> Result<()> {
        let (first, params) = (self.first, &self.params);
        let idle = ResolveFrame::new(bounds::<S>(w));
        let ids = &self.ids;
        for_each_agent_by(
            self.next
                .par_iter_mut()
                .zip(self.plans.par_iter().zip(ids.par_iter()))
                .zip(self.around.par_iter()),
            |k| u64::from(ids[k]),
            || idle.clone(),
            |frame, k, ((out, (p, &id)), around)| {
                // A stopped ant does not move: its resolve frame is never read.
                let frame = if p.state.is_stopped() {
                    &idle
                } else if noted {
                    fill_resolve_frame_from(w, first + k, around, frame);
                    &*frame
                } else {
                    fill_resolve_frame(w, first + k, frame);
                    &*frame
                };
                *out = ant::resolve_checked(p, frame, params)
                    .map_err(|e| SimError::controller("ant resolve", step, id, e))?;
                Ok(())
            },
        )
    }

    /// Makes the resolved states current and writes the sensed world; returns what happened,
    /// in slot order. An ant that finished collecting at its leg's way point moves on to the
    /// next leg with probability [`ROUTE_ADVANCE`] (see [`AntWorld::target_of`]).
    fn commit(&mut self, w: &mut AntWorld, seed: u32, step: u32) -> Vec<AntEvent> {
        let route = &w.route;
        let events = (
            self.states.par_iter(),
            self.next.par_iter_mut(),
            self.ids.par_iter(),
        )
            .into_par_iter()
            .filter_map(|(old, new, &agent)| {
                let e = event(agent, old, new)?;
                if let AntEvent::Collected { food, .. } = e
                    && route.contains(&food)
                    && rand::chance(StepCtx { seed, agent, step }, ROUTE_STREAM, ROUTE_ADVANCE)
                {
                    advance(new, food);
                }
                Some(e)
            })
            .collect();
        w.sensed.write(self.first, &self.ids, &self.next);
        std::mem::swap(&mut self.states, &mut self.next);
        events
    }

    /// Sorts the group's slots by their cell in the world's grid (then by slot): a permutation
    /// of the slots that changes no result, only memory locality. Rewrites the group's part of
    /// the sensed world.
    fn reorder(&mut self, w: &mut AntWorld) {
        let perm = w
            .grid
            .order_of(&self.states, |s| [s.pos.x.to_f32(), s.pos.y.to_f32(), 0.0]);
        self.states = permuted(&self.states, &perm);
        self.ids = permuted(&self.ids, &perm);
        w.sensed.write(self.first, &self.ids, &self.states);
    }

    /// Moves the group's ants that are inside an active obstacle of `objects` out (see
    /// [`AntSim::move_out_of_obstacles`]); returns how many.
    fn move_out(&mut self, objects: &[AntObjectDef], min: [f32; 2], max: [f32; 2]) -> usize {
        let arena = Rect::new(
            Vec2::new(S::from_f32(min[0]), S::from_f32(min[1])),
            Vec2::new(S::from_f32(max[0]), S::from_f32(max[1])),
        );
        let obstacles: Vec<&AntObjectDef> = objects
            .iter()
            .filter(|o| o.active && o.kind == AntObjectKind::Obstacle)
            .collect();
        let mut moved = 0;
        for s in &mut self.states {
            if let Some(p) = way_out(&obstacles, arena, s.pos) {
                s.pos = p;
                s.follow = None;
                moved += 1;
            }
        }
        moved
    }

    /// This tick's plans, by slot (after the plan phase).
    pub(super) fn plans(&self) -> &[AntPlan<S>] {
        &self.plans
    }

    /// This tick's resolved states, by slot (after the resolve phase, before they are
    /// published).
    pub(super) fn resolved(&self) -> &[AntState<S>] {
        &self.next
    }

    /// The states in id order.
    pub fn states_by_id(&self) -> Vec<(u32, AntState<S>)> {
        let mut v: Vec<(u32, AntState<S>)> = self
            .ids
            .iter()
            .copied()
            .zip(self.states.iter().copied())
            .collect();
        v.sort_unstable_by_key(|&(id, _)| id);
        v
    }
}

/// Where an ant at `p` inside one of `obstacles` goes: just beyond the boundary point nearest
/// to it (twice [`ant::SURFACE_MARGIN`] out) of an obstacle it is in, if that point is clear
/// of every obstacle (the nearest such point); else, where obstacles overlap, the first clear
/// point on rings around `p` (radius growing by a quarter unit, 8 points per quarter unit of
/// radius, in angle order: deterministic). Clamped to the arena. `None` if `p` is free; `p`
/// itself stays if nothing within 64 units is clear.
fn way_out<S: SimScalar>(
    obstacles: &[&AntObjectDef],
    arena: Rect<S>,
    p: Vec2<S>,
) -> Option<Vec2<S>> {
    let margin = S::from_f32(ant::SURFACE_MARGIN);
    let beyond = margin + margin;
    let clear = |q: Vec2<S>| {
        obstacles.iter().all(|o| {
            let (b, _, inside) = o.surface(q);
            !inside && (q - b).length() >= margin
        })
    };
    if !obstacles.iter().any(|o| o.closest(p).1) {
        return None;
    }
    let nearest = obstacles
        .iter()
        .map(|o| o.surface(p))
        .filter(|&(_, _, inside)| inside)
        .map(|(b, n, _)| arena.clamp(b + n * beyond))
        .filter(|&q| clear(q))
        .min_by(|a, b| {
            let (da, db) = ((*a - p).length(), (*b - p).length());
            da.partial_cmp(&db).unwrap_or(core::cmp::Ordering::Equal)
        });
    if nearest.is_some() {
        return nearest;
    }
    let quarter = S::from_f32(0.25);
    let turn = swarm_core::scalar::pi::<S>() * S::from_i32(2);
    for ring in 1..=256 {
        let r = quarter * S::from_i32(ring);
        let count = 8 * ring;
        for k in 0..count {
            let a = turn * S::from_i32(k) / S::from_i32(count);
            let q = arena.clamp(p + Vec2::from_angle(a) * r);
            if clear(q) {
                return Some(q);
            }
        }
    }
    Some(p)
}

/// A group of either scalar type.
pub type AnyAntGroup = ByScalar<AntGroup<f32>, AntGroup<Fx>>;

crate::scalar::agent_group!(AntGroup);

/// The event, if any, of ant `agent` going from `old` to `new`: the end of a collecting or
/// dropping stop that changed its label.
fn event<S>(agent: u32, old: &AntState<S>, new: &AntState<S>) -> Option<AntEvent> {
    let t = old.stop?;
    let finished = new.stop.is_none();
    match t.reason {
        StopReason::CollectingFood if finished && new.label == Label::Food => {
            Some(AntEvent::Collected {
                agent,
                food: t.place,
            })
        }
        StopReason::DroppingFood if finished && new.label == Label::Nest => {
            Some(AntEvent::Delivered {
                agent,
                nest: t.place,
            })
        }
        _ => None,
    }
}

/// The probability that an ant which reached its leg's way point goes on to the next leg
/// instead of returning (ours: the paper gives no rule; half the ants move on at each way point,
/// so every leg stays foraged while the colony stretches along the route).
pub const ROUTE_ADVANCE: f32 = 0.5;

/// The random stream of the route decisions (the controllers use streams below 16).
const ROUTE_STREAM: u32 = 0x5200;

/// Ant `s` has just reached way point `wp` and takes the next leg: `wp` becomes its nest,
/// it knows where it is (S_nest, arrived here) and keeps going forward instead of turning back.
fn advance<S: SimScalar>(s: &mut AntState<S>, wp: u16) {
    s.nest = wp;
    s.origin = wp;
    s.label = Label::Nest;
    s.arrival = s.pos;
    s.heading = -s.heading;
}

/// Something an ant did this tick that the world keeps count of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AntEvent {
    /// Ant `agent` finished collecting food at food source `food`.
    Collected {
        /// Ant id.
        agent: u32,
        /// Food source id.
        food: u16,
    },
    /// Ant `agent` finished dropping food at nest `nest`.
    Delivered {
        /// Ant id.
        agent: u32,
        /// Nest id.
        nest: u16,
    },
}

/// A whole ant colony (or several) in its world.
#[derive(Clone, Debug)]
pub struct AntSim {
    /// The world and the sensed state of every ant.
    pub world: AntWorld,
    /// The groups, in agent-index order.
    pub groups: Vec<AnyAntGroup>,
    /// The run's seed.
    pub seed: u32,
    /// The next tick to run.
    pub step: u32,
    /// Re-sort the slots by grid cell every this many ticks (0: never). Changes no result.
    pub reorder_every: u32,
    /// Ants moved out of obstacles so far ([`AntSim::move_out_of_obstacles`]).
    pub moved_out: u64,
    /// What happened in the last tick, in agent order.
    pub events: Vec<AntEvent>,
    /// Food deliveries so far.
    pub delivered: u64,
    /// Whether this tick's predictions stayed within the step bound the plan queries assumed
    /// (then the resolve frames come from the noted ants).
    noted: bool,
}

impl AntSim {
    /// A simulation of `groups` (contiguous agent indices, in order) in `world`.
    pub fn new(mut world: AntWorld, groups: Vec<AnyAntGroup>, seed: u32) -> Self {
        let n = groups.iter().map(AnyAntGroup::len).sum();
        world.sensed.resize(n);
        world.size_grids(n);
        world.predicted.resize(n, [0.0; 2]);
        world.step_reach = groups
            .iter()
            .map(|g| by_scalar!(g, g => g.step_bound()))
            .fold(0.0, f32::max)
            + world.rounding_margin();
        for g in &groups {
            by_scalar!(g, g => world.sensed.write(g.first, &g.ids, &g.states));
        }
        let mut sim = AntSim {
            world,
            groups,
            seed,
            step: 0,
            reorder_every: 16,
            moved_out: 0,
            events: Vec::new(),
            delivered: 0,
            noted: false,
        };
        sim.move_out_of_obstacles();
        sim.reorder();
        sim
    }

    /// Moves every ant that is inside an active obstacle (it spawned there, or an event put
    /// the obstacle on top of it) out, just beyond the nearest point of the obstacle's
    /// boundary, and counts it in [`AntSim::moved_out`]. Returns how many moved.
    pub fn move_out_of_obstacles(&mut self) -> usize {
        let w = &mut self.world;
        let mut moved = 0;
        for g in &mut self.groups {
            by_scalar!(g, g => {
                let n = g.move_out(&w.objects, w.min, w.max);
                if n > 0 {
                    w.sensed.write(g.first, &g.ids, &g.states);
                }
                moved += n;
            });
        }
        self.moved_out += moved as u64;
        moved
    }

    /// Sorts every group's slots by grid cell (memory locality for the neighbour queries).
    pub fn reorder(&mut self) {
        for g in &mut self.groups {
            by_scalar!(g, g => g.reorder(&mut self.world));
        }
    }

    /// Number of ants.
    pub fn agents(&self) -> usize {
        self.world.len()
    }

    /// One tick (xiang2018 Algorithm 1): every ant plans (steps 1-3, eq. 1), the predictions
    /// are shared, every ant resolves (eq. 2-5); then food taken and delivered is accounted.
    /// Returns what happened, in agent order. The same as [`AntSim::plan_phase`] then
    /// [`AntSim::resolve_phase`].
    pub fn step(&mut self) -> Result<Vec<AntEvent>> {
        self.plan_phase()?;
        self.resolve_phase()
    }

    /// The first half of a tick: every ant plans from the sensed world ([`AntSim::plan_all`]),
    /// and the predictions p*(t+1) are published in [`AntWorld::predicted`]
    /// ([`AntSim::publish_plans`]). Between the halves the world holds both frames of every
    /// ant ([`plan_frame`](super::plan_frame) and [`resolve_frame`](super::resolve_frame)):
    /// what the HIL harness sends to a device.
    pub fn plan_phase(&mut self) -> Result<()> {
        self.plan_all()?;
        self.publish_plans();
        Ok(())
    }

    /// The longest step an ant can predict, over every group.
    fn step_bound(&self) -> f32 {
        self.groups
            .iter()
            .map(|g| by_scalar!(g, g => g.step_bound()))
            .fold(0.0, f32::max)
    }

    /// Every ant plans from the sensed world (the decisions of the plan phase; nothing is
    /// published).
    pub fn plan_all(&mut self) -> Result<()> {
        let (seed, step) = (self.seed, self.step);
        self.world.index_positions();
        // Two ants' predictions within the collision range of each other are sensed within
        // the collision range plus both steps: each plan query notes those ants.
        let reach =
            self.world.collision_range + 2.0 * self.step_bound() + self.world.rounding_margin();
        for g in &mut self.groups {
            by_scalar!(g, g => g.plan(&self.world, seed, step, reach))?;
        }
        Ok(())
    }

    /// Publishes the plans' predictions p*(t+1) in [`AntWorld::predicted`].
    pub fn publish_plans(&mut self) {
        let mut shift = 0.0f32;
        for g in &self.groups {
            shift = shift.max(by_scalar!(g, g => g.write_predictions(&mut self.world)));
        }
        self.world.max_shift = shift;
        self.noted = shift <= self.step_bound();
    }

    /// The second half of a tick (after [`AntSim::plan_phase`]): every ant resolves, the
    /// states advance, the tick counter moves on. Returns what happened (also kept in
    /// [`AntSim::events`]).
    pub fn resolve_phase(&mut self) -> Result<Vec<AntEvent>> {
        self.resolve_all()?;
        self.publish_states();
        Ok(self.events.clone())
    }

    /// Every ant resolves its plan against the published predictions (the decisions of the
    /// resolve phase; nothing is published).
    pub fn resolve_all(&mut self) -> Result<()> {
        let (step, noted) = (self.step, self.noted);
        for g in &mut self.groups {
            by_scalar!(g, g => g.resolve(&self.world, step, noted))?;
        }
        Ok(())
    }

    /// Makes the resolved states current (what happened goes to [`AntSim::events`]), accounts
    /// the food, and moves the tick counter on.
    pub fn publish_states(&mut self) {
        let (seed, step) = (self.seed, self.step);
        self.events.clear();
        for g in &mut self.groups {
            let events = by_scalar!(g, g => g.commit(&mut self.world, seed, step));
            self.events.extend(events);
        }
        if self.reorder_every > 0 && (step + 1) % self.reorder_every == 0 {
            self.reorder();
        }
        let events = std::mem::take(&mut self.events);
        self.consume_food(&events);
        self.delivered += events
            .iter()
            .filter(|e| matches!(e, AntEvent::Delivered { .. }))
            .count() as u64;
        self.events = events;
        self.noted = false;
        self.step += 1;
    }

    /// Food sources with an amount lose one unit per collection and disappear when empty.
    fn consume_food(&mut self, events: &[AntEvent]) {
        for e in events {
            let AntEvent::Collected { food, .. } = *e else {
                continue;
            };
            for o in self.world.objects.iter_mut().filter(|o| o.id == food) {
                if let AntObjectKind::Food { amount: Some(a) } = &mut o.kind {
                    *a = a.saturating_sub(1);
                    o.active &= *a > 0;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ants::{AntObjectDef, Shape2};
    use swarm_core::Vec2;

    /// 400 ants at a nest, food 60 units away: a small hand-built world.
    fn world_sim<S: SimScalar>(n: usize) -> AntSim
    where
        AnyAntGroup: From<AntGroup<S>>,
    {
        let params = AntParams::<S>::default();
        let mut w = AntWorld::new(
            [0.0, 0.0],
            [120.0, 80.0],
            params.contact_range.to_f32(),
            params.collision_range.to_f32(),
        );
        let circle = |center, radius| Shape2::Circle { center, radius };
        w.objects = vec![
            AntObjectDef {
                id: 0,
                name: "nest".into(),
                kind: AntObjectKind::Nest,
                shape: circle([20.0, 40.0], 3.0),
                active: true,
            },
            AntObjectDef {
                id: 1,
                name: "food".into(),
                kind: AntObjectKind::Food { amount: None },
                shape: circle([80.0, 40.0], 4.0),
                active: true,
            },
            AntObjectDef {
                id: 2,
                name: "rock".into(),
                kind: AntObjectKind::Obstacle,
                shape: circle([50.0, 30.0], 5.0),
                active: true,
            },
        ];
        let states = (0..n)
            .map(|i| {
                let a = S::from_f32(i as f32 * 0.618 * core::f32::consts::TAU);
                AntState::at_nest(0, Vec2::from_f32(20.0, 40.0), Vec2::from_angle(a))
            })
            .collect();
        let group = AntGroup::new("colony".into(), 0, params.checked().unwrap(), states);
        AntSim::new(w, vec![group.into()], 42)
    }

    /// Hash of every ant's position, in id order.
    fn hash(sim: &AntSim) -> u64 {
        let mut by_id: Vec<(u32, [f64; 2])> = sim
            .world
            .sensed
            .id
            .iter()
            .copied()
            .zip(sim.world.sensed.pos.iter().copied())
            .collect();
        by_id.sort_by_key(|e| e.0);
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        for (_, p) in by_id {
            for x in p {
                h = (h ^ x.to_bits()).wrapping_mul(0x100_0000_01b3);
            }
        }
        h
    }

    #[test]
    fn reordering_slots_changes_no_result() {
        let run = |every| {
            let mut sim = world_sim::<f32>(300);
            sim.reorder_every = every;
            for _ in 0..200 {
                sim.step().unwrap();
            }
            hash(&sim)
        };
        assert_eq!(run(0), run(1));
        assert_eq!(run(0), run(16));
    }

    fn run_with_threads(threads: usize, steps: u32) -> (u64, u64) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut sim = world_sim::<f32>(400);
            for _ in 0..steps {
                sim.step().unwrap();
            }
            (hash(&sim), sim.delivered)
        })
    }

    /// The engine's frames are the public functions': its plan frames (objects from the index)
    /// and the resolve frames built from the ants each plan query noted, for every moving ant,
    /// in a crowd at the nest (lists that overflow included) and spread out.
    fn noted_frames_are_the_grids<S: SimScalar>()
    where
        AnyAntGroup: From<AntGroup<S>>,
    {
        let mut sim = world_sim::<S>(400);
        let (mut listed, mut overflowed) = (0, 0);
        for _ in 0..300 {
            sim.plan_phase().unwrap();
            assert!(sim.noted);
            let g = by_scalar!(&sim.groups[0], g => g.around.clone());
            for (k, around) in g.iter().enumerate() {
                let stopped = by_scalar!(&sim.groups[0], g => g.plans[k].state.is_stopped());
                if stopped {
                    continue;
                }
                let mut engine_plan = PlanFrame::new(bounds::<S>(&sim.world));
                let mut scratch = Around::default();
                fill_plan_frame_noting(&sim.world, k, &mut engine_plan, Some((&mut scratch, 3.0)));
                assert_eq!(engine_plan, super::super::plan_frame::<S>(&sim.world, k));
                let mut from_list = ResolveFrame::new(bounds::<S>(&sim.world));
                fill_resolve_frame_from(&sim.world, k, around, &mut from_list);
                assert_eq!(from_list, super::super::resolve_frame::<S>(&sim.world, k));
                match around.slots() {
                    Some(_) => listed += 1,
                    None => overflowed += 1,
                }
            }
            sim.resolve_phase().unwrap();
        }
        assert!(
            listed > 10_000 && overflowed > 1_000,
            "{listed} {overflowed}"
        );
    }

    #[test]
    fn noted_resolve_frames_equal_the_grids() {
        noted_frames_are_the_grids::<f32>();
        noted_frames_are_the_grids::<Fx>();
    }

    #[test]
    fn bit_identical_for_any_thread_count() {
        assert_eq!(run_with_threads(1, 300), run_with_threads(2, 300));
    }

    #[test]
    fn a_colony_delivers_food_in_both_scalars() {
        for mut sim in [world_sim::<f32>(300), world_sim::<Fx>(300)] {
            let mut delivered = 0;
            for _ in 0..2500 {
                for e in sim.step().unwrap() {
                    if let AntEvent::Delivered { nest, .. } = e {
                        assert_eq!(nest, 0);
                        delivered += 1;
                    }
                }
            }
            assert!(delivered > 50, "{delivered} deliveries");
        }
    }
}
