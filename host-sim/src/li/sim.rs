//! The li2015 engine on the CPU: a [`Swarm3d`] of insects each going through
//! `swarm_core::li::step_checked` every step (its waypoint, the preferred velocity, ORCA, the
//! move) on the frame [`li_frame`] builds from the world; the world (the container, its
//! obstacles, the sensed insects) is the backstop that keeps the new states physical, and
//! counts each correction. The run measures the metrics of the paper: the accumulated density
//! and its total variation to the target, the distance to the swarm's centroid, the
//! polarisation of Eq. 8.

use swarm_core::li::{self, LiDecision, LiFrame, LiParams, LiState, WIRE_LI_NEIGHBOURS};
use swarm_core::li::{LiDevice, LiStep, LiStepReply, LiStepRequest};
use swarm_core::li::{WIRE_LI_SURFACES, density::Density};
use swarm_core::wire::Endpoint;
use swarm_core::{Checked, Scalar, StepCtx, Vec3};

use super::scenario::Route;
use crate::by_scalar;
use crate::engine::{Exchange, StateNames, soft_name};
use crate::error::{Result, SimError};
use crate::nearest::select;
use crate::output::Summary;
use crate::scalar::{SimScalar, v3};
use crate::swarm3d::{AnyGroup3d, Group3d, Kinematic, Model3d, Step3d, Swarm3d, World3d, reach};

/// Neighbour capacity of a li frame (the wire's).
pub const N: usize = WIRE_LI_NEIGHBOURS;
/// Surface capacity of a li frame (the wire's).
pub const O: usize = WIRE_LI_SURFACES;

/// The sensor frame of the simulator (and of the wire).
pub type LiSimFrame<S> = LiFrame<S, N, O>;

/// The li2015 model over both scalar types (the [`Model3d`] of [`LiSim`]).
#[derive(Clone, Copy, Debug)]
pub enum Li {}

/// A li2015 swarm (or several groups) in its world.
pub type LiSim = Swarm3d<Li>;
/// A group of li2015 insects sharing parameters (their data included) and a scalar type.
pub type LiGroup<S> = Group3d<Li, S>;
/// A group of either scalar type.
pub type AnyLiGroup = AnyGroup3d<Li>;

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
pub fn li_frame<S: SimScalar>(w: &World3d, slot: usize, p: &LiParams<S>) -> (LiSimFrame<S>, bool) {
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

impl<S: SimScalar> Step3d<S> for LiParams<S> {
    type Decision = LiDecision<S>;
    type Frame = LiSimFrame<S>;
    type Inputs = ();
    type Counts = Counts;
    const STEP: &'static str = "li step";

    fn frame(&self, w: &World3d, slot: usize, (): ()) -> (LiSimFrame<S>, bool) {
        li_frame(w, slot, self)
    }
    fn step(
        params: &Checked<Self>,
        state: &LiState<S>,
        frame: &LiSimFrame<S>,
        ctx: StepCtx,
    ) -> swarm_core::Result<(LiState<S>, LiDecision<S>)> {
        li::step_checked(state, frame, params, ctx)
    }
    fn exchange(
        agent: u32,
        (state, frame, ctx): (LiState<S>, LiSimFrame<S>, StepCtx),
        (decision, next): (LiDecision<S>, LiState<S>),
    ) -> Result<Exchange> {
        let request = LiStepRequest { state, frame, ctx };
        let reply = LiStepReply {
            decision,
            state: next,
        };
        Exchange::of::<LiParams<S>, LiStep>(agent, &request, &reply)
    }
    fn count(d: &LiDecision<S>, truncated: bool, fix: u8) -> Counts {
        let arrived = d.proposals > 0;
        Counts {
            arrivals: u64::from(arrived),
            proposals: u64::from(d.proposals),
            held: u64::from(arrived && !d.accepted),
            infeasible: u64::from(d.infeasible),
            truncated: u64::from(truncated),
            corrected: u64::from(fix != 0),
        }
    }
    const STATE_NAMES: StateNames = StateNames {
        labels: &["travelling", "proposing"],
        motions: &["feasible", "infeasible"],
    };
    /// `label` 1 on a step it arrived and proposed, `motion` 1 when its ORCA program was
    /// infeasible.
    fn marks(_: &LiState<S>, d: &LiDecision<S>) -> (u8, u8) {
        (u8::from(d.proposals > 0), u8::from(d.infeasible))
    }
    /// At rest, arrived at its start (its first step proposes a waypoint).
    fn at(pos: Vec3<S>) -> LiState<S> {
        LiState::at(pos)
    }
    fn radius(&self) -> f32 {
        self.radius.to_f32()
    }
    fn orca_radius(&self) -> f32 {
        self.orca_radius().to_f32()
    }
    fn range(&self) -> f32 {
        self.range.to_f32()
    }
    fn reach(&self) -> f32 {
        reach(self.orca_radius(), self.tau, self.speed).to_f32()
    }
    /// The li node's endpoint (its buffer sizes).
    fn soft(params: &Checked<Self>) -> Result<Box<dyn Endpoint + Send>> {
        let p: &LiParams<S> = params;
        let device = LiDevice::<S>::new(p.clone(), &soft_name::<LiParams<S>>());
        Ok(Box::new(device.map_err(SimError::Device)?))
    }
}

/// What a li2015 run accumulates after each measured step: the metrics of the paper.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LiMeasures {
    /// Σ of the polarisation (Eq. 8).
    pub polarisation: f64,
    /// Σ of the mean distance to the swarm's centroid.
    pub centroid_distance: f64,
    /// The steps measured.
    pub steps: u64,
    /// Visits of each cell of each group's density grid (every insect, every measured step):
    /// the accumulated density of Fig. 4, by group.
    pub visits: Vec<Vec<u64>>,
    /// The cells of the waypoints accepted (every arrival that accepted one, every measured
    /// step): the density the waypoint chain itself accumulates (the spec's prototype of
    /// L-T7 measured this one), by group.
    pub waypoints: Vec<Vec<u64>>,
    /// Each group's progress along its route of lights (Fig. 6), for the groups with one.
    pub routes: Vec<Option<RouteRun>>,
}

/// A group's progress along its route of lights (li2015 Fig. 6, spec §2.6).
#[derive(Clone, Debug, PartialEq)]
pub struct RouteRun {
    /// The route.
    pub route: Route,
    /// The density weights of each light (checked against the group's grid when built).
    pub weights: Vec<Vec<u8>>,
    /// The share of each light's density within `route.reach` of it (its cells' centres):
    /// the most of the swarm the density gathers there.
    pub held: Vec<f64>,
    /// The light the group is drawn to now.
    pub leg: usize,
    /// The step at which each light was reached so far, in order: the share of the group
    /// within `route.reach` of it at least `route.share` × [`RouteRun::held`].
    pub reached: Vec<u32>,
}

impl LiMeasures {
    /// The mean polarisation and distance to the centroid over the measured steps.
    pub fn means(&self) -> (f64, f64) {
        let n = self.steps.max(1) as f64;
        (self.polarisation / n, self.centroid_distance / n)
    }
}

impl<S: SimScalar> LiGroup<S> {
    /// How many of the group's insects are within `reach` of `light`.
    fn within(&self, light: [f64; 3], reach: f64) -> usize {
        let near = |s: &&LiState<S>| {
            let p = [s.pos.x, s.pos.y, s.pos.z].map(SimScalar::to_f64);
            (0..3).map(|k| (p[k] - light[k]).powi(2)).sum::<f64>() <= reach * reach
        };
        self.states.iter().filter(near).count()
    }

    /// Draws the group to another density over the same grid: a light's weights
    /// ([`light_weights`](super::data::light_weights) on the group's own grid: one per cell,
    /// its light's cell 255), which the parameters accept as they accepted the first light's.
    fn set_density(&mut self, weights: &[u8]) {
        let mut p: LiParams<S> = (*self.params).clone();
        p.density.weights =
            heapless::Vec::from_slice(weights).expect("a light's weights fill the group's grid");
        self.params = p
            .checked()
            .expect("a light's density is valid as the first light's");
    }

    /// Counts every insect's cell of the group's density grid into `visits`, and the cell of
    /// every waypoint accepted at the last step into `waypoints`.
    fn visit(&self, visits: &mut Vec<u64>, waypoints: &mut Vec<u64>) {
        let d = &self.params.density;
        visits.resize(d.weights.len(), 0);
        waypoints.resize(d.weights.len(), 0);
        let Ok(grid) = Density::new(d.origin, d.cell, d.dims, &d.weights) else {
            return;
        };
        for (s, decision) in self.states.iter().zip(&self.decisions) {
            if let Some(i) = cell_index(&grid, d.dims, s.pos) {
                visits[i] += 1;
            }
            if decision.accepted
                && let Some(i) = cell_index(&grid, d.dims, s.waypoint)
            {
                waypoints[i] += 1;
            }
        }
    }
}

impl LiSim {
    /// The accumulated-density total variation to the target (L-T7) of the insects'
    /// positions, the groups' weighted by their insects; `None` before any measured step (or
    /// for a group without insects).
    pub fn density_tv(&self) -> Option<f64> {
        self.tv_of(&self.measures.visits)
    }

    /// The same of the waypoints accepted ([`LiMeasures::waypoints`]); `None` until every
    /// group has accepted one.
    pub fn waypoint_tv(&self) -> Option<f64> {
        self.tv_of(&self.measures.waypoints)
    }

    fn tv_of(&self, counts: &[Vec<u64>]) -> Option<f64> {
        let mut sum = 0.0;
        let mut n = 0usize;
        for (k, g) in self.groups.iter().enumerate() {
            let visits = counts.get(k)?;
            let (tv, len) = by_scalar!(g, g => (
                total_variation(visits, &g.params.density.weights),
                g.states.len(),
            ));
            sum += tv? * len as f64;
            n += len;
        }
        (n > 0).then(|| sum / n as f64)
    }
}

impl Model3d for Li {
    type Params<S: SimScalar> = LiParams<S>;
    type Inputs = ();
    type Counts = Counts;
    type Measures = LiMeasures;

    fn cast<S: SimScalar>(p: &LiParams<f32>) -> LiParams<S> {
        p.cast()
    }
    /// Adds this step to the accumulated density, the polarisation and the distance to the
    /// centroid.
    fn measure(sim: &mut LiSim) {
        // In id order: the same sums whatever the slots (a GPU engine never reorders them).
        let polarisation = crate::eval::frame_polarisation(&sim.velocities_by_id());
        let centroid = mean_centroid_distance(&sim.positions_by_id());
        let m = &mut sim.measures;
        m.visits.resize(sim.groups.len(), Vec::new());
        m.waypoints.resize(sim.groups.len(), Vec::new());
        for ((g, visits), waypoints) in sim.groups.iter().zip(&mut m.visits).zip(&mut m.waypoints) {
            by_scalar!(g, g => g.visit(visits, waypoints));
        }
        m.polarisation += polarisation;
        m.centroid_distance += centroid;
        m.steps += 1;
    }
    /// A group whose share of insects has reached its current light moves on to the next one:
    /// its density becomes that light's.
    fn between_steps(sim: &mut LiSim) {
        let step = sim.step;
        for (g, run) in sim.groups.iter_mut().zip(&mut sim.measures.routes) {
            let Some(run) = run else { continue };
            if run.reached.len() > run.leg {
                continue; // the last light, reached: the swarm stays there
            }
            let light = run.route.lights[run.leg].map(f64::from);
            let reach = f64::from(run.route.reach);
            let (near, n) = by_scalar!(g, g => (g.within(light, reach), g.states.len()));
            let needed = f64::from(run.route.share) * run.held[run.leg];
            if n == 0 || (near as f64) < needed * n as f64 {
                continue;
            }
            run.reached.push(step);
            if run.leg + 1 < run.route.lights.len() {
                run.leg += 1;
                by_scalar!(g, g => g.set_density(&run.weights[run.leg]));
            }
        }
    }
    /// A route changes the density a device holds in the middle of the run: refused.
    fn device_ready(sim: &LiSim) -> Result<()> {
        for (g, run) in sim.groups.iter().zip(&sim.measures.routes) {
            if run.as_ref().is_some_and(|r| r.route.lights.len() > 1) {
                return Err(SimError::LiRouteDevice {
                    group: by_scalar!(g, g => g.name.clone()),
                });
            }
        }
        Ok(())
    }
    /// The metrics of the paper (the accumulated density's total variation to the target,
    /// the distance to the swarm's centroid, the polarisation) and what the waypoint level
    /// and ORCA did.
    fn closing(sim: &LiSim, summary: &mut Summary) -> String {
        let t = sim.total;
        let decisions = (sim.agents() as u64 * u64::from(sim.step)).max(1) as f64;
        let share = |n: u64| 100.0 * n as f64 / decisions;
        let (polarisation, centroid) = sim.measures.means();
        let tv = sim.density_tv();
        let proposals = t.proposals as f64 / t.arrivals.max(1) as f64;
        let held = 100.0 * t.held as f64 / t.arrivals.max(1) as f64;
        for (key, value) in [
            ("polarisation_mean", polarisation),
            ("centroid_distance_mean", centroid),
            ("proposals_per_arrival", proposals),
            ("arrivals_held_percent", held),
            ("orca_infeasible_percent", share(t.infeasible)),
            ("frames_truncated_percent", share(t.truncated)),
        ] {
            summary.extra.insert(key.into(), value.into());
        }
        if let Some(tv) = tv {
            summary.extra.insert("density_tv".into(), tv.into());
        }
        if let Some(tv) = sim.waypoint_tv() {
            summary
                .extra
                .insert("waypoint_density_tv".into(), tv.into());
        }
        let reached: serde_json::Map<String, serde_json::Value> = sim
            .groups
            .iter()
            .zip(&sim.measures.routes)
            .filter_map(|(g, r)| {
                let name = by_scalar!(g, g => g.name.clone());
                Some((name, r.as_ref()?.reached.clone().into()))
            })
            .collect();
        if !reached.is_empty() {
            summary
                .extra
                .insert("lights_reached_at_step".into(), reached.into());
        }
        summary
            .extra
            .insert("world_corrections".into(), t.corrected.into());
        format!(
            "accumulated density {} from the target (total variation), {centroid:.3} from \
             the centroid and polarisation {polarisation:.2} on average; {proposals:.2} \
             proposals per arrival ({held:.2} % held), ORCA infeasible for {:.3} % of the \
             decisions, {} world corrections",
            tv.map_or("not measured".into(), |tv| format!("{tv:.3}")),
            share(t.infeasible),
            t.corrected
        )
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
