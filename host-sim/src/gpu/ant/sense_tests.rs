//! Ant sensing on the GPU (`shaders/ant_sense.wgsl`, lavapipe where there is no GPU) against
//! the CPU's `plan_frame` and `resolve_frame` (`host-sim/src/ants/sense.rs`), every word of
//! every ant's frames:
//!
//! * real simulations of built-in ant scenarios (obstacles of both shapes, the heart's
//!   polygons, dynamic obstacles and a disturbance coming and going, a route of way points),
//!   advanced on the CPU and sensed at several ticks after the plan phase (predictions
//!   published), in both scalars: over `Fx` bit for bit, over `f32` measured with a floor;
//! * hand-built worlds of edge cases: ants on the grid's cell boundaries and the arena's
//!   corners, neighbours exactly at the contact and collision ranges, crowds of more than eight
//!   neighbours in one cell with ties in distance (broken by ids that are not the slots), ants
//!   inside polygons and discs, on a vertex, on an edge, at a disc's centre, a comb of more than
//!   24 obstacle pieces within one step, concave and clockwise polygons, inactive objects, food
//!   with amounts and exhausted, disturbances, and a route whose legs filter neighbours and
//!   objects.
//!
//! `cargo test -p swarm-sim --lib gpu::ant::sense -- --nocapture` prints the figures.

use std::sync::Mutex;
use std::time::Instant;

use rayon::prelude::*;
use swarm_core::Fx;
use swarm_core::ant::{AntObject, Label};

use super::layout::{
    PLAN_FRAME_WORDS, RESOLVE_FRAME_WORDS, read_plan_frame, read_resolve_frame, write_plan_frame,
    write_resolve_frame,
};
use super::scalar_module;
use super::sense::{AntSense, SENSE_KERNEL, modules};
use super::world::*;
use crate::ants::{
    AntObjectDef, AntObjectKind, AntSim, AntWorld, N, Shape2, plan_frame, resolve_frame,
};
use crate::engine::apply_due_events;
use crate::gpu::shaders::{ANT_SENSE, ANT_WORLD};
use crate::gpu::tests::Rng;
use crate::gpu::tests::harness::{
    PerScalar, Tally, TestScalar, assert_constants, assert_valid_wgsl, first_difference,
    keep_first, shortened,
};
use crate::gpu::{Gpu, test_gpu};
use crate::scenario::ObjectKind;

/// The test GPU and the sensing kernels over `S`, made once for every test.
fn sense<S: TestScalar>() -> &'static Mutex<(Gpu, AntSense)> {
    static SENSE: PerScalar<Mutex<(Gpu, AntSense)>> = PerScalar::new();
    SENSE.get::<S>(|| {
        let gpu = test_gpu();
        let k = AntSense::new::<S>(&gpu).expect("the sensing kernels compile");
        Mutex::new((gpu, k))
    })
}

/// How the GPU's frames compare with the CPU's, and what they cover.
#[derive(Debug, Default)]
struct Agreement {
    /// Plan frames compared, and those with every word equal.
    plans: Tally,
    /// Resolve frames compared, and those with every word equal.
    resolves: Tally,
    /// The first difference, described.
    first: Option<String>,
    /// Plan frames with a full neighbour list, with an obstacle (a polygon's, a disc's), a
    /// disturbance, a nest, food.
    full: usize,
    obstacles: usize,
    disturbances: usize,
    nests: usize,
    food: usize,
    /// Resolve frames with obstacle surfaces, with a full list of them, with neighbours.
    surfaces: usize,
    full_surfaces: usize,
    resolve_neighbours: usize,
}

impl Agreement {
    fn add(&mut self, o: Agreement) {
        self.plans.add(o.plans);
        self.resolves.add(o.resolves);
        keep_first(&mut self.first, o.first);
        self.full += o.full;
        self.obstacles += o.obstacles;
        self.disturbances += o.disturbances;
        self.nests += o.nests;
        self.food += o.food;
        self.surfaces += o.surfaces;
        self.full_surfaces += o.full_surfaces;
        self.resolve_neighbours += o.resolve_neighbours;
    }

    fn share(&self) -> (f64, f64) {
        (self.plans.share(), self.resolves.share())
    }

    fn coverage(&self) -> String {
        format!(
            "plan frames with 8 neighbours {}, an obstacle {}, a disturbance {}, a nest {}, \
             food {}; resolve frames with obstacle surfaces {} (6 of them {}), with neighbours {}",
            self.full,
            self.obstacles,
            self.disturbances,
            self.nests,
            self.food,
            self.surfaces,
            self.full_surfaces,
            self.resolve_neighbours,
        )
    }

    /// Panics unless every frame was identical.
    fn assert_identical(&self, what: &str) {
        if let Some(first) = &self.first {
            panic!(
                "{what}: {} of {} plan frames and {} of {} resolve frames differ; the first: \
                 {first}",
                self.plans.differ(),
                self.plans.total,
                self.resolves.differ(),
                self.resolves.total,
            );
        }
    }
}

/// Every ant's frames of `w` sensed on the GPU over `S`, against the CPU's (the world has its
/// predictions published and its grid indexed, as after `AntSim::plan_phase`).
fn compare<S: TestScalar>(what: &str, w: &AntWorld) -> Agreement {
    let got = {
        let mut guard = sense::<S>().lock().unwrap_or_else(|e| e.into_inner());
        let (gpu, k) = &mut *guard;
        k.frames::<S>(gpu, w).expect("the sensing kernels run")
    };
    let n = w.len();
    assert_eq!(got.plan.len(), n * PLAN_FRAME_WORDS);
    assert_eq!(got.resolve.len(), n * RESOLVE_FRAME_WORDS);
    let per_ant: Vec<Agreement> = (0..n)
        .into_par_iter()
        .map(|i| {
            let mut a = Agreement::default();
            let plan = plan_frame::<S>(w, i);
            let mut want = Vec::with_capacity(PLAN_FRAME_WORDS);
            write_plan_frame(&mut want, &plan);
            let g = &got.plan[i * PLAN_FRAME_WORDS..(i + 1) * PLAN_FRAME_WORDS];
            a.plans = Tally::one(g == want);
            if g != want {
                a.first = Some(format!(
                    "{what}: the plan frame of slot {i} (at {:?})\n  CPU {plan:?}\n  GPU {:?}",
                    w.sensed.pos[i],
                    read_plan_frame::<S>(g),
                ));
            }
            a.full = usize::from(plan.neighbours.len() == N);
            let has = |f: &dyn Fn(&AntObject<S>) -> bool| usize::from(plan.objects.iter().any(f));
            a.obstacles = has(&|o| matches!(o, AntObject::Obstacle(_)));
            a.disturbances = has(&|o| matches!(o, AntObject::Disturbance { .. }));
            a.nests = has(&|o| matches!(o, AntObject::Nest { .. }));
            a.food = has(&|o| matches!(o, AntObject::Food { .. }));

            let resolve = resolve_frame::<S>(w, i);
            let mut want = Vec::with_capacity(RESOLVE_FRAME_WORDS);
            write_resolve_frame(&mut want, &resolve);
            let g = &got.resolve[i * RESOLVE_FRAME_WORDS..(i + 1) * RESOLVE_FRAME_WORDS];
            a.resolves = Tally::one(g == want);
            if g != want && a.first.is_none() {
                a.first = Some(format!(
                    "{what}: the resolve frame of slot {i} (at {:?}, predicted {:?})\n  CPU \
                     {resolve:?}\n  GPU {:?}",
                    w.sensed.pos[i],
                    w.predicted[i],
                    read_resolve_frame::<S>(g),
                ));
            }
            a.surfaces = usize::from(!resolve.obstacles.is_empty());
            a.full_surfaces = usize::from(resolve.obstacles.is_full());
            a.resolve_neighbours = usize::from(!resolve.neighbours.is_empty());
            a
        })
        .collect();
    let mut a = Agreement::default();
    per_ant.into_iter().for_each(|x| a.add(x));
    a
}

// ---- real simulations ----

/// The built-in ant scenarios sensed: obstacles (discs; the heart's polygons), obstacles
/// dropped and removed, a disturbance started and stopped, three colonies with obstacles, a
/// route of way points.
const SCENARIOS: &[&str] = &[
    "ants-fig7a-single-colony",
    "ants-fig7b-obstacles",
    "ants-fig8b-hybrid-obstacles",
    "ants-fig1c-heart",
    "ants-fig11-dynamic-obstacles",
    "ants-fig13-disturbance",
    "ants-fig14-waypoints",
];

/// Ticks simulated (the scenarios' events at the same fraction of this shortened run; the
/// simulation in a debug build is most of the test's time), and every how many ticks the ants
/// are sensed on the GPU (tick 0 included).
const RUN: u32 = 120;
const EVERY: u32 = 10;

/// The worlds of scenario `name` simulated in `S` for [`RUN`] ticks, after the plan phase of
/// every [`EVERY`]th tick; for the route of way points, also with the ants' nests dealt out
/// over the route's legs (the simulation has few ants past the first way point by then). The
/// disturbance of fig. 13 is moved from the middle of the trail to 17 units from the nest, so
/// that ants meet it in the shortened run.
fn worlds<S: TestScalar>(name: &str) -> Vec<(String, AntWorld)> {
    let mut sc = shortened::<S>(name, RUN);
    sc.steps = RUN + 1;
    for o in &mut sc.objects {
        if let ObjectKind::Disturbance { center, .. } = &mut o.kind {
            *center = [67.0, 60.0];
        }
    }
    let mut sim = AntSim::from_scenario(&sc, sc.seed).expect("the scenario builds");
    let mut out = Vec::new();
    for t in 0..=RUN {
        apply_due_events(&mut sim, &sc);
        sim.plan_phase().expect("plan");
        if t % EVERY == 0 {
            out.push((format!("{name} tick {t}"), sim.world.clone()));
            if !sim.world.route.is_empty() {
                let mut w = sim.world.clone();
                let nests = w.objects.iter().filter(|o| o.kind == AntObjectKind::Nest);
                let legs: Vec<u16> = nests.map(|o| o.id).chain(w.route.iter().copied()).collect();
                for (k, nest) in w.sensed.nest.iter_mut().enumerate() {
                    *nest = legs[k % legs.len()];
                }
                out.push((format!("{name} tick {t}, nests dealt over the legs"), w));
            }
        }
        sim.resolve_phase().expect("resolve");
    }
    out
}

/// Every scenario of [`SCENARIOS`] in `S`, sensed on the GPU against the CPU; `check` sees each
/// world's agreement.
fn real<S: TestScalar>(check: impl Fn(&str, &Agreement)) -> Agreement {
    let all: Vec<Vec<(String, AntWorld)>> = SCENARIOS.par_iter().map(|n| worlds::<S>(n)).collect();
    let mut total = Agreement::default();
    for (what, w) in all.iter().flatten() {
        let a = compare::<S>(what, w);
        check(what, &a);
        total.add(a);
    }
    total
}

/// Fixed point: every frame of every ant of the built-in scenarios, bit for bit.
#[test]
fn fx_frames_of_builtin_scenarios_are_bit_for_bit() {
    let t0 = Instant::now();
    let total = real::<Fx>(|what, a| a.assert_identical(what));
    println!(
        "fixed point, {} scenarios for {RUN} ticks, sensed every {EVERY}: {} plan and {} \
         resolve frames identical on the GPU ({:.1} s)\n  {}",
        SCENARIOS.len(),
        total.plans.same,
        total.resolves.same,
        t0.elapsed().as_secs_f64(),
        total.coverage(),
    );
    assert_eq!(total.plans.total, total.plans.same);
    assert_eq!(total.resolves.total, total.resolves.same);
    assert!(total.plans.total >= 50_000, "{}", total.plans.total);
    // What the frames covered.
    assert!(total.full > 500 && total.obstacles > 100 && total.disturbances > 10);
    assert!(total.surfaces > 100 && total.resolve_neighbours > 1000);
}

/// The least share of `f32` frames the GPU must reproduce bit for bit.
const F32_FLOOR: f64 = 0.999;

/// `f32`: the same scenarios simulated in `f32`, measured (docs/gpu.md: not promised).
#[test]
fn f32_frames_of_builtin_scenarios_are_measured() {
    let t0 = Instant::now();
    let total = real::<f32>(|_, _| {});
    let (plans, resolves) = total.share();
    println!(
        "f32 on {}, {} scenarios for {RUN} ticks, sensed every {EVERY}: plan frames {:.3} % \
         bit-identical ({} of {}), resolve frames {:.3} % ({} of {}) ({:.1} s){}",
        sense::<f32>()
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .0
            .info()
            .name,
        SCENARIOS.len(),
        100.0 * plans,
        total.plans.same,
        total.plans.total,
        100.0 * resolves,
        total.resolves.same,
        total.resolves.total,
        t0.elapsed().as_secs_f64(),
        first_difference(total.first.as_ref()),
    );
    assert!(plans >= F32_FLOOR && resolves >= F32_FLOOR, "{total:?}");
}

// ---- edge cases ----

/// A world of 60 × 40 with contact range 2 and collision range 1.5 (the built-ins'), grid cells
/// of 2 (for 600 ants), its objects, and 600 ants placed on the edge cases (see the module's
/// documentation); `routed`: with a route of two way points, the ants' nests dealt over its
/// legs.
fn edge_world(routed: bool) -> AntWorld {
    let mut w = AntWorld::new([0.0, 0.0], [60.0, 40.0], 2.0, 1.5);
    let circle = |center: [f32; 2], radius| Shape2::Circle { center, radius };
    let object = |id: u16, kind, shape, active| AntObjectDef {
        id,
        name: format!("object-{id}"),
        kind,
        shape,
        active,
    };
    // A comb of teeth 0.04 apart: more than 24 pieces within one step of an ant above it,
    // and above its right end more than 24 before (in edge order) the nearest ones.
    let mut comb = vec![[40.0, 5.0]];
    for k in 0..=100 {
        let x = 40.0 + 0.02 * k as f32;
        comb.push([x, if k % 2 == 0 { 10.0 } else { 10.5 }]);
    }
    comb.push([42.0, 5.0]);
    w.objects = vec![
        object(0, AntObjectKind::Nest, circle([10.0, 10.0], 3.0), true),
        object(
            1,
            AntObjectKind::Food { amount: Some(3) },
            circle([50.0, 30.0], 2.0),
            true,
        ),
        object(
            2,
            AntObjectKind::Food { amount: Some(0) },
            circle([45.0, 20.0], 2.0),
            false,
        ),
        object(3, AntObjectKind::Obstacle, circle([30.0, 20.0], 2.5), true),
        // A counter-clockwise square.
        object(
            4,
            AntObjectKind::Obstacle,
            Shape2::Polygon {
                points: vec![[20.0, 30.0], [26.0, 30.0], [26.0, 36.0], [20.0, 36.0]],
            },
            true,
        ),
        // A clockwise, concave L.
        object(
            5,
            AntObjectKind::Obstacle,
            Shape2::Polygon {
                points: vec![
                    [5.0, 20.0],
                    [5.0, 28.0],
                    [8.0, 28.0],
                    [8.0, 23.0],
                    [12.0, 23.0],
                    [12.0, 20.0],
                ],
            },
            true,
        ),
        object(
            6,
            AntObjectKind::Obstacle,
            Shape2::Polygon { points: comb },
            true,
        ),
        // Overlapping the disc: an ant inside both senses both at distance 0 (a tie).
        object(
            7,
            AntObjectKind::Disturbance,
            circle([33.0, 20.0], 3.0),
            true,
        ),
        object(8, AntObjectKind::Obstacle, circle([15.0, 5.0], 1.0), false),
        object(
            9,
            AntObjectKind::Waypoint { order: 1 },
            circle([5.0, 35.0], 2.0),
            true,
        ),
        object(
            10,
            AntObjectKind::Waypoint { order: 2 },
            circle([55.0, 5.0], 2.0),
            true,
        ),
        object(11, AntObjectKind::Nest, circle([50.0, 10.0], 2.0), true),
        // A triangle with a slanted edge, an ant exactly on it.
        object(
            12,
            AntObjectKind::Obstacle,
            Shape2::Polygon {
                points: vec![[44.0, 32.0], [50.0, 38.0], [44.0, 38.0]],
            },
            true,
        ),
    ];
    if routed {
        w.set_route();
    } else {
        w.objects
            .retain(|o| !matches!(o.kind, AntObjectKind::Waypoint { .. }));
    }

    let mut pos: Vec<[f64; 2]> = Vec::new();
    let mut pred: Vec<[f64; 2]> = Vec::new();
    // On the cell boundaries (cells of 2), 2 apart: neighbours exactly at the contact range;
    // predictions 1.5 apart: exactly at the collision range (not sensed: strictly within).
    for k in 0..=30 {
        for y in [0.0, 2.0, 4.0] {
            pos.push([2.0 * f64::from(k), y]);
            pred.push([1.5 * f64::from(k) + 7.5, y * 0.75]);
        }
    }
    // The arena's corners.
    for p in [[0.0, 40.0], [60.0, 0.0], [60.0, 40.0]] {
        pos.push(p);
        pred.push(p);
    }
    // A crowd: 30 ants on one point, 24 on a circle of radius 1 around it (equal keys), each
    // predicted on a point of its own or shared.
    for k in 0..30 {
        pos.push([15.0, 15.0]);
        pred.push([15.0 + 0.25 * f64::from(k % 3), 15.0]);
    }
    for k in 0..24 {
        let a = f64::from(k) * std::f64::consts::TAU / 24.0;
        pos.push([15.0 + a.cos(), 15.0 + a.sin()]);
        pred.push([15.0 + 0.5 * a.cos(), 15.0 + 0.5 * a.sin()]);
    }
    // Special points: inside the square, on its vertex, on its edges, at the disc's centre,
    // inside it, on its rim (twice), on the triangle's slanted edge (twice), at the
    // disturbance's centre, inside both, above the comb, in one of
    // its teeth, inside the L, on the
    // L's reflex vertex, in the nest, in the food, in the exhausted food, at the inactive
    // disc's centre, on the way points.
    for p in [
        [23.0, 33.0],
        [20.0, 30.0],
        [23.0, 30.0],
        [26.0, 36.0],
        [30.0, 20.0],
        [30.5, 20.25],
        [32.5, 20.0],
        [31.5, 22.0],
        [47.0, 35.0],
        [45.5, 33.5],
        [44.1, 32.1],
        [44.3, 32.3],
        [45.7, 33.7],
        [46.9, 34.9],
        [48.45, 36.45],
        [49.3, 37.3],
        [33.0, 20.0],
        [31.5, 20.0],
        [41.0, 10.8],
        [41.98, 10.8],
        [40.05, 10.2],
        [6.0, 21.0],
        [8.0, 23.0],
        [8.5, 23.5],
        [10.0, 10.0],
        [50.0, 30.0],
        [45.0, 20.0],
        [15.0, 5.0],
        [5.0, 35.0],
        [55.0, 5.0],
        [43.0, 5.0],
        [19.5, 29.5],
    ] {
        pos.push(p);
        pred.push([p[0] + 0.3, p[1] - 0.2]);
    }
    // The rest spread out at random, predicted within a step.
    let mut rng = Rng::new(if routed { 77 } else { 78 });
    let mut unit = || f64::from(rng.next()) / 4_294_967_296.0;
    while pos.len() < 600 {
        let p = [60.0 * unit(), 40.0 * unit()];
        let a = unit() * std::f64::consts::TAU;
        let r = unit();
        pos.push(p);
        pred.push([p[0] + r * a.cos(), p[1] + r * a.sin()]);
    }

    let n = pos.len();
    w.sensed.resize(n);
    let nests: Vec<u16> = if routed {
        vec![0, 9, 10, 11]
    } else {
        vec![0, 11]
    };
    let mut rng = Rng::new(5);
    w.sensed.pos = pos;
    for j in 0..n {
        let s = &mut w.sensed;
        // Ids are not the slots: ties in distance are broken by id.
        s.id[j] = ((j * 7919 + 13) % n) as u32 + 1000;
        s.label[j] = [Label::Nothing, Label::Food, Label::Nest][rng.below(3) as usize];
        s.nest[j] = nests[rng.below(nests.len() as u32) as usize];
        s.origin[j] = if s.label[j] == Label::Nest {
            s.nest[j]
        } else {
            rng.below(12) as u16
        };
        s.arrival[j] = [f64::from(rng.below(60)), f64::from(rng.below(40)) + 0.5];
    }
    w.predicted = pred;
    w.size_grids(n);
    index(&mut w);
    w
}

/// Indexes the ants of `w` and sets its largest shift, as `AntSim::plan_phase` does.
fn index(w: &mut AntWorld) {
    w.index_positions();
    // As AntSim::publish_plans: the largest distance between a prediction and its ant.
    w.max_shift = w
        .predicted
        .iter()
        .zip(&w.sensed.pos)
        .map(|(p, q)| {
            let d = [p[0] - q[0], p[1] - q[1]];
            (d[0] * d[0] + d[1] * d[1]).sqrt() as f32
        })
        .fold(0.0, f32::max);
}

/// The edge worlds in `S`: the GPU's frames against the CPU's, and its grid cells against the
/// key function's.
fn edge_cases<S: TestScalar>() -> Agreement {
    let mut total = Agreement::default();
    for routed in [false, true] {
        let mut w = edge_world(routed);
        // The positions as the ants' scalar has them (an f32 ant senses f32 positions).
        let exact = |p: &mut [f64; 2]| *p = crate::scalar::a2(crate::scalar::v2::<S>(*p));
        w.sensed.pos.iter_mut().for_each(exact);
        w.predicted.iter_mut().for_each(exact);
        index(&mut w);
        let what = if routed {
            "edge world, routed"
        } else {
            "edge world"
        };
        total.add(compare::<S>(what, &w));
    }
    total
}

/// Fixed point: every edge case bit for bit; the grid's cells of the ants on the cell
/// boundaries are the cells they start.
#[test]
fn fx_edge_cases_are_bit_for_bit() {
    let total = edge_cases::<Fx>();
    total.assert_identical("fixed point");
    println!(
        "fixed point, edge worlds: {} plan and {} resolve frames identical\n  {}",
        total.plans.same,
        total.resolves.same,
        total.coverage()
    );
    assert!(total.full > 50 && total.full_surfaces > 0 && total.disturbances > 0);

    let w = edge_world(false);
    let got = {
        let mut guard = sense::<Fx>().lock().unwrap_or_else(|e| e.into_inner());
        let (gpu, k) = &mut *guard;
        k.frames::<Fx>(gpu, &w).expect("the sensing kernels run")
    };
    let shape = GridShape::of(&w, w.len());
    assert_eq!((shape.cell, shape.nx, shape.ny), (2.0, 30, 20));
    for (j, p) in w.sensed.pos.iter().enumerate().take(93) {
        let c = |x: f64, n: u32| ((x / 2.0) as u32).min(n - 1);
        assert_eq!(
            got.cells[j],
            c(p[1], shape.ny) * shape.nx + c(p[0], shape.nx),
            "the cell of {p:?}"
        );
    }
}

/// `f32`: the edge cases, measured.
#[test]
fn f32_edge_cases_are_measured() {
    let total = edge_cases::<f32>();
    let (plans, resolves) = total.share();
    println!(
        "f32, edge worlds: plan frames {:.2} % bit-identical, resolve frames {:.2} %{}",
        100.0 * plans,
        100.0 * resolves,
        first_difference(total.first.as_ref()),
    );
    assert!(plans >= F32_FLOOR && resolves >= F32_FLOOR, "{total:?}");
}

// ---- the layout ----

/// The sensing kernels compile (naga, as wgpu would) over both scalars.
#[test]
fn the_sensing_kernels_are_valid_wgsl() {
    assert_valid_wgsl("sensing", modules, SENSE_KERNEL);
    assert_eq!(scalar_module::<Fx>().name, "scalar_fx");
}

/// Both sides of the world's layout have the same constants.
#[test]
fn the_world_constants_are_the_shaders() {
    let wgsl = format!("{}{}", ANT_WORLD.source, ANT_SENSE.source);
    assert_constants(&wgsl, WGSL_CONSTANTS, true);
}
