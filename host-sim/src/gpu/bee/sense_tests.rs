//! Bee sensing on the GPU (`shaders/bee_sense.wgsl`, lavapipe where there is no GPU) against
//! the CPU's `bee_frame` (`host-sim/src/bees/sense.rs`), every word of every bee's frame:
//!
//! * real simulations of the three built-in bee scenarios (the ground box, the shafts, the
//!   targets' particles and goals), advanced on the CPU and sensed at every recorded step, in
//!   both scalars: over `Fx` bit for bit, over `f32` measured with a floor;
//! * hand-built worlds of edge cases: bees on the grid's cell boundaries, on the volume's faces
//!   and corners and outside it, neighbours exactly at the range (not sensed: strictly within)
//!   and one `Fx` ulp inside it, crowds of more than sixteen candidates with ties in distance
//!   (broken by ids that are not the slots), bees inside and on obstacles of each shape (a
//!   sphere's centre, a box's faces, edges and corners, closed faces on the volume's bounds, a
//!   box filling the volume, a shaft's axis, caps and rim, closed caps), inside two obstacles at
//!   once, inactive obstacles and targets, more particles in range than the frame holds, a bee
//!   at a target's centre, goals of active, inactive and missing targets.
//!
//! `cargo test -p swarm-sim --lib gpu::bee::sense -- --nocapture` prints the figures.

use std::sync::Mutex;
use std::time::Instant;

use rayon::prelude::*;
use swarm_core::Fx;

use super::layout::{FRAME_WORDS, read_frame, write_frame};
use super::sense::{BeeSense, FrameWords, SENSE_KERNEL, modules};
use super::world::*;
use crate::bees::{
    BeeObstacle, BeeSim, BeeTarget, BeeWorld, N, P, Shape3, bee_frame, bee_frame_time,
};
use crate::engine::{Engine, apply_due_events};
use crate::gpu::ant::scalar_module;
use crate::gpu::shaders::{BEE_SENSE, BEE_WORLD};
use crate::gpu::tests::Rng;
use crate::gpu::tests::harness::{
    BeeGroups, PerScalar, Tally, TestScalar, assert_constants, assert_valid_wgsl, first_difference,
    keep_first, shortened,
};
use crate::gpu::{Gpu, test_gpu};
use crate::scalar::{a3, v3};
use crate::scenario::builtin_names;

/// The test GPU and the sensing kernels over `S`, made once for every test.
fn sense<S: TestScalar>() -> &'static Mutex<(Gpu, BeeSense)> {
    static SENSE: PerScalar<Mutex<(Gpu, BeeSense)>> = PerScalar::new();
    SENSE.get::<S>(|| {
        let gpu = test_gpu();
        let k = BeeSense::new::<S>(&gpu).expect("the sensing kernels compile");
        Mutex::new((gpu, k))
    })
}

/// Every bee's frame of `w` sensed on the GPU over `S`.
fn gpu_frames<S: TestScalar>(w: &BeeWorld, inputs: &[FrameInput<S>]) -> FrameWords {
    let mut guard = sense::<S>().lock().unwrap_or_else(|e| e.into_inner());
    let (gpu, k) = &mut *guard;
    k.frames::<S>(gpu, w, inputs)
        .expect("the sensing kernels run")
}

/// How the GPU's frames compare with the CPU's, and what they cover.
#[derive(Debug, Default)]
struct Agreement {
    /// Frames compared, and those with every word equal.
    frames: Tally,
    /// The first difference, described.
    first: Option<String>,
    /// Frames with neighbours, with a full list of them (more candidates than it holds: the
    /// 16 nearest kept), with target particles, with a full list of them, with a goal, with an
    /// obstacle.
    neighbours: usize,
    full: usize,
    targets: usize,
    full_targets: usize,
    goals: usize,
    obstacles: usize,
    /// Frames whose bee is inside an obstacle (an active one).
    inside: usize,
}

impl Agreement {
    fn add(&mut self, o: Agreement) {
        self.frames.add(o.frames);
        keep_first(&mut self.first, o.first);
        self.neighbours += o.neighbours;
        self.full += o.full;
        self.targets += o.targets;
        self.full_targets += o.full_targets;
        self.goals += o.goals;
        self.obstacles += o.obstacles;
        self.inside += o.inside;
    }

    fn share(&self) -> f64 {
        self.frames.share()
    }

    fn coverage(&self) -> String {
        format!(
            "with neighbours {} (16 of them {}), with target particles {} (16 of them {}), with \
             a goal {}, with an obstacle {} (inside one {})",
            self.neighbours,
            self.full,
            self.targets,
            self.full_targets,
            self.goals,
            self.obstacles,
            self.inside,
        )
    }

    /// Panics unless every frame was identical.
    fn assert_identical(&self, what: &str) {
        if let Some(first) = &self.first {
            panic!(
                "{what}: {} of {} frames differ; the first: {first}",
                self.frames.differ(),
                self.frames.total,
            );
        }
    }
}

/// Every bee's frame of `w` sensed on the GPU over `S` (bee `i` with `inputs[i]`), against the
/// CPU's `bee_frame` (the world has its grid indexed, as in a step).
fn compare<S: TestScalar>(what: &str, w: &BeeWorld, inputs: &[FrameInput<S>]) -> Agreement {
    let got = gpu_frames::<S>(w, inputs);
    let n = w.len();
    assert_eq!(got.frames.len(), n * FRAME_WORDS);
    let per_bee: Vec<Agreement> = (0..n)
        .into_par_iter()
        .map(|i| {
            let mut a = Agreement::default();
            let input = inputs[i];
            let goal = input.goal.and_then(|g| w.target_center(g));
            let frame = bee_frame::<S>(w, i, goal, input.t);
            let mut want = Vec::with_capacity(FRAME_WORDS);
            write_frame(&mut want, &frame);
            let g = &got.frames[i * FRAME_WORDS..(i + 1) * FRAME_WORDS];
            a.frames = Tally::one(g == want);
            if g != want {
                a.first = Some(format!(
                    "{what}: the frame of slot {i} (at {:?}, id {})\n  CPU {frame:?}\n  GPU {:?}",
                    w.sensed.pos[i],
                    w.sensed.id[i],
                    read_frame::<S>(g),
                ));
            }
            a.neighbours = usize::from(!frame.neighbours.is_empty());
            a.full = usize::from(frame.neighbours.len() == N);
            a.targets = usize::from(!frame.targets.is_empty());
            a.full_targets = usize::from(frame.targets.len() == P);
            a.goals = usize::from(frame.goal.is_some());
            a.obstacles = usize::from(frame.obstacle.is_some());
            a.inside = usize::from(w.inside_obstacle(v3::<S>(w.sensed.pos[i])).is_some());
            a
        })
        .collect();
    let mut a = Agreement::default();
    per_bee.into_iter().for_each(|x| a.add(x));
    a
}

// ---- real simulations ----

/// The bee scenarios sensed: steps simulated, and every how many the bees are sensed on the GPU
/// (long enough for the swarms to reach the shafts, the nest and the gathering point).
const SCENARIOS: &[(&str, u32, u32)] = &[
    ("bees-fig11-grassland", 45, 3),
    ("bees-fig14-shafts", 400, 4),
    ("bees-fig15-nest", 240, 4),
];

/// Every bee's frame input in `sim` at its current step: its own clock and its group's goal
/// (as `BeeGroup::decide` gives them).
fn inputs_of<S: TestScalar>(sim: &BeeSim) -> Vec<FrameInput<S>> {
    let mut inputs = vec![
        FrameInput {
            t: S::ZERO,
            goal: None
        };
        sim.agents()
    ];
    for g in &sim.groups {
        let g = S::pick::<BeeGroups>(g).expect("every group in the scalar asked for");
        let dt = g.params.dt.to_f64();
        for (k, &id) in g.ids.iter().enumerate() {
            inputs[g.first + k] = FrameInput {
                t: S::from_f64(bee_frame_time(sim.seed, id, sim.step, dt)),
                goal: g.goal,
            };
        }
    }
    inputs
}

/// The built-in scenario `name` simulated in `S` for `steps` steps (its events at the same
/// fraction of the shortened run), every bee's frame sensed on the GPU against the CPU's every
/// `every` steps (the world indexed as the step's decisions read it).
fn simulate<S: TestScalar>(name: &str, steps: u32, every: u32) -> Agreement {
    let sc = shortened::<S>(name, steps);
    let mut sim = BeeSim::from_scenario(&sc, sc.seed).expect("the scenario builds");
    let mut total = Agreement::default();
    for t in 0..steps {
        apply_due_events(&mut sim, &sc);
        Engine::decide(&mut sim, 0).expect("step");
        if t % every == 0 {
            let what = format!("{name} step {t}");
            total.add(compare::<S>(&what, &sim.world, &inputs_of::<S>(&sim)));
        }
        Engine::publish(&mut sim, 0).expect("publish");
    }
    total
}

/// Every scenario of [`SCENARIOS`] in `S`; `check` sees each scenario's agreement.
fn real<S: TestScalar>(check: impl Fn(&str, &Agreement)) -> Agreement {
    let runs: Vec<Agreement> = SCENARIOS
        .par_iter()
        .map(|&(name, steps, every)| simulate::<S>(name, steps, every))
        .collect();
    let mut total = Agreement::default();
    for (&(name, _, _), a) in SCENARIOS.iter().zip(runs) {
        check(name, &a);
        total.add(a);
    }
    total
}

/// The real simulations cover every built-in bee scenario.
#[test]
fn every_bee_scenario_is_sensed() {
    for name in builtin_names().iter().filter(|n| n.starts_with("bees-")) {
        assert!(
            SCENARIOS.iter().any(|s| s.0 == *name),
            "{name} is not in SCENARIOS"
        );
    }
}

/// Fixed point: every frame of every bee of the built-in scenarios, bit for bit.
#[test]
fn fx_frames_of_builtin_scenarios_are_bit_for_bit() {
    let t0 = Instant::now();
    let total = real::<Fx>(|name, a| a.assert_identical(name));
    println!(
        "fixed point, {} bee scenarios: {} frames identical on the GPU ({:.1} s)\n  {}",
        SCENARIOS.len(),
        total.frames.same,
        t0.elapsed().as_secs_f64(),
        total.coverage(),
    );
    assert_eq!(total.frames.total, total.frames.same);
    assert!(total.frames.total >= 40_000, "{}", total.frames.total);
    // What the frames covered.
    assert!(total.full > 200 && total.full_targets > 200 && total.obstacles > 4000);
    assert!(total.goals > 40_000 && total.targets > 500);
}

/// The least share of `f32` frames the GPU must reproduce bit for bit.
const F32_FLOOR: f64 = 0.999;

/// `f32`: the same scenarios simulated in `f32`, measured (docs/gpu.md: not promised).
#[test]
fn f32_frames_of_builtin_scenarios_are_measured() {
    let t0 = Instant::now();
    let total = real::<f32>(|_, _| {});
    println!(
        "f32 on {}, {} bee scenarios: {:.3} % of {} frames bit-identical ({:.1} s){}",
        sense::<f32>()
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .0
            .info()
            .name,
        SCENARIOS.len(),
        100.0 * total.share(),
        total.frames.total,
        t0.elapsed().as_secs_f64(),
        first_difference(total.first.as_ref()),
    );
    assert!(total.share() >= F32_FLOOR, "{total:?}");
}

// ---- edge cases ----

/// The neighbour range and the obstacle sensing range of the edge worlds (the built-ins'
/// h + 2r and 2·d0).
const RANGE: f32 = 3.5;
const SENSE: f32 = 4.0;

/// A world of 40 × 20 × 40 (from the origin) with the edge cases' obstacles and targets (see
/// the module's documentation), and `n` bees placed on the edge cases, the rest at random;
/// `filled`: a box fills the whole volume (every face on the bounds: all open).
fn edge_world(filled: bool) -> BeeWorld {
    let (min, max) = ([0.0; 3], [40.0, 20.0, 40.0]);
    let mut w = BeeWorld::new(min, max, RANGE, SENSE);
    let obstacle = |id: u16, shape, active| BeeObstacle::new(id, format!("o{id}"), shape, active);
    w.obstacles = vec![
        obstacle(
            0,
            Shape3::Sphere {
                center: [10.0, 10.0, 10.0],
                radius: 2.0,
            },
            true,
        ),
        // The ground under half the volume: its bottom and three sides on the bounds (closed),
        // its top and its +z side open.
        obstacle(
            1,
            Shape3::Box {
                min: [0.0, 0.0, 0.0],
                max: [40.0, 1.0, 20.0],
            },
            true,
        ),
        // A free box.
        obstacle(
            2,
            Shape3::Box {
                min: [20.0, 5.0, 5.0],
                max: [24.0, 9.0, 8.0],
            },
            true,
        ),
        // A shaft from floor to ceiling (both caps closed) and a free one (both open).
        obstacle(
            3,
            Shape3::Shaft {
                center: [30.0, 30.0],
                radius: 1.5,
                y_min: 0.0,
                y_max: 20.0,
            },
            true,
        ),
        obstacle(
            4,
            Shape3::Shaft {
                center: [10.0, 30.0],
                radius: 2.0,
                y_min: 6.0,
                y_max: 12.0,
            },
            true,
        ),
        // Overlapping the sphere: a bee inside both is at distance 0 of each (a tie: the first).
        obstacle(
            5,
            Shape3::Box {
                min: [11.0, 9.0, 9.0],
                max: [14.0, 11.0, 11.0],
            },
            true,
        ),
        // Inactive: never sensed.
        obstacle(
            6,
            Shape3::Sphere {
                center: [20.0, 15.0, 20.0],
                radius: 3.0,
            },
            false,
        ),
        // Beyond the volume, on its bounds: a box whose +x face lies past max x (closed).
        obstacle(
            7,
            Shape3::Box {
                min: [36.0, 14.0, 2.0],
                max: [41.0, 16.0, 6.0],
            },
            true,
        ),
    ];
    // A shaft standing on the floor (its bottom closed, its top open), and a small sphere by its
    // foot, nearer than its side to a bee on its closed bottom: that bee is inside the shaft
    // (distance 0) and senses it, not the sphere.
    w.obstacles.push(obstacle(
        8,
        Shape3::Shaft {
            center: [35.0, 30.0],
            radius: 1.5,
            y_min: 0.0,
            y_max: 8.0,
        },
        true,
    ));
    w.obstacles.push(obstacle(
        9,
        Shape3::Sphere {
            center: [35.0, 0.0, 31.5],
            radius: 0.5,
        },
        true,
    ));
    if filled {
        w.obstacles
            .push(obstacle(10, Shape3::Box { min, max }, true));
    }
    w.targets = vec![
        BeeTarget::new(11, "nest", [30.0, 10.0, 12.0], 2.0, 300),
        BeeTarget::new(12, "flower", [5.0, 15.0, 35.0], 1.0, 40),
        BeeTarget {
            active: false,
            ..BeeTarget::new(13, "gone", [20.0, 10.0, 30.0], 1.5, 50)
        },
    ];
    w.index_targets();

    let mut pos: Vec<[f64; 3]> = Vec::new();
    // On the cell boundaries of the GPU's grid and of the CPU's, along each axis.
    let cell = f64::from(GridShape3::of(&w, 600).cell);
    for k in 0..=10 {
        let x = cell * f64::from(k);
        pos.push([x.min(40.0), 3.0, 3.0]);
        pos.push([3.0, (x / 2.0).min(20.0), 3.0]);
        pos.push([3.0, 3.0, x.min(40.0)]);
        pos.push([3.5 * f64::from(k), 18.0, 20.0]);
    }
    // Neighbours exactly at the range (not sensed) and one ulp inside it (sensed), on each
    // axis.
    let ulp = 1.0 / 65_536.0;
    for (k, base) in [[15.0, 16.0, 20.0], [25.0, 4.0, 25.0]].iter().enumerate() {
        pos.push(*base);
        let mut p = *base;
        p[k] += 3.5;
        pos.push(p);
        let mut p = *base;
        p[2] -= 3.5 - ulp;
        pos.push(p);
    }
    // The volume's corners, a face, and outside it.
    for p in [
        [0.0, 0.0, 0.0],
        [40.0, 20.0, 40.0],
        [40.0, 0.0, 40.0],
        [0.0, 20.0, 0.0],
        [40.0, 10.0, 20.0],
        [-3.0, 10.0, 20.0],
        [45.0, 25.0, -4.0],
        [20.0, -2.0, 41.0],
    ] {
        pos.push(p);
    }
    // A crowd: 30 bees on one point and 26 on a sphere of radius 1 around it (equal distances),
    // more than 16 candidates with ties broken by id.
    for _ in 0..30 {
        pos.push([20.0, 15.0, 30.0]);
    }
    for k in 0..26 {
        let (a, b) = (f64::from(k) * 0.8, f64::from(k % 5) * 0.6 - 1.2);
        pos.push([
            20.0 + a.cos() * b.cos(),
            15.0 + b.sin(),
            30.0 + a.sin() * b.cos(),
        ]);
    }
    for d in [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
    ] {
        pos.push([20.0 + d[0], 15.0 + d[1], 30.0 + d[2]]);
    }
    // Obstacles: the sphere's centre, inside it, on it, just outside; inside both the sphere
    // and the box over it; the ground (inside, on its top, on its closed bottom and sides);
    // the free box's faces, edges, corners and inside it (nearest each face); the full shaft
    // (axis, inside, on its side, on its closed caps) and the free one (caps, rim, axis);
    // the inactive sphere; the box past the volume.
    for p in [
        [10.0, 10.0, 10.0],
        [10.5, 10.25, 9.0],
        [12.0, 10.0, 10.0],
        [10.0, 12.0, 10.0],
        [13.5, 10.0, 10.0],
        [11.5, 10.0, 10.0],
        [12.5, 10.5, 10.0],
        [5.0, 0.5, 5.0],
        [5.0, 1.0, 5.0],
        [5.0, 0.0, 5.0],
        [0.0, 0.5, 5.0],
        [40.0, 0.5, 5.0],
        [5.0, 0.75, 0.0],
        [20.0, 7.0, 6.0],
        [24.0, 7.0, 6.0],
        [22.0, 5.0, 6.0],
        [22.0, 9.0, 8.0],
        [20.0, 5.0, 5.0],
        [24.0, 9.0, 8.0],
        [25.0, 10.0, 9.0],
        [19.0, 4.0, 6.0],
        [20.5, 7.0, 6.5],
        [23.5, 7.0, 6.5],
        [22.0, 5.25, 6.5],
        [22.0, 8.75, 6.5],
        [22.0, 7.0, 5.25],
        [22.0, 7.0, 7.75],
        [22.0, 7.0, 6.5],
        [30.0, 10.0, 30.0],
        [30.5, 10.0, 30.25],
        [31.5, 10.0, 30.0],
        [30.0, 0.0, 30.0],
        [30.0, 20.0, 30.5],
        [33.0, 10.0, 30.0],
        [10.0, 6.0, 30.0],
        [10.0, 12.0, 30.0],
        [10.5, 6.25, 30.0],
        [10.5, 11.5, 30.5],
        [12.0, 12.0, 30.0],
        [13.0, 13.0, 30.0],
        [10.0, 5.0, 30.0],
        [10.0, 9.0, 30.0],
        [35.0, 0.0, 30.0],
        [35.0, 0.5, 30.0],
        [35.0, 4.0, 30.0],
        [35.0, 7.5, 30.5],
        [35.0, 8.0, 30.0],
        [5.0, 0.5, 20.0],
        [5.0, 0.75, 19.875],
        // Exactly at the sensing range of the free box's top and of the sphere (sensed), and
        // one ulp beyond.
        [22.0, 13.0, 6.5],
        [10.0, 10.0, 16.0],
        [22.0, 13.0 + 1.0 / 65_536.0, 6.5],
        [20.0, 15.0, 20.0],
        [38.0, 15.0, 4.0],
        [40.0, 15.0, 4.0],
        [35.0, 15.0, 4.0],
    ] {
        pos.push(p);
    }
    // Targets: at the nest's centre (300 particles at one distance: ties by index), near it
    // (more than 16 in range), at the flower, at the inactive target.
    for p in [
        [30.0, 10.0, 12.0],
        [30.0, 10.0, 14.5],
        [31.0, 11.0, 12.5],
        [28.5, 9.0, 11.0],
        [5.0, 15.0, 35.0],
        [7.0, 15.0, 35.0],
        [20.0, 10.0, 30.0],
    ] {
        pos.push(p);
    }
    // Exactly at the range of the particle farthest along +x and of the one farthest along -x
    // (as the bees' fixed point has them; every other particle is farther), and one ulp
    // inside it.
    let fx = |x: f32| (f64::from(x) * 65_536.0).round_ties_even() / 65_536.0;
    let by_x = |a: &&[f32; 3], b: &&[f32; 3]| a[0].total_cmp(&b[0]);
    for (q, dir) in [
        (w.particles.iter().max_by(by_x), 1.0),
        (w.particles.iter().min_by(by_x), -1.0),
    ] {
        let q = q.expect("particles").map(fx);
        for d in [3.5, 3.5 - 1.0 / 65_536.0] {
            pos.push([q[0] + dir * d, q[1], q[2]]);
        }
    }
    // The rest at random, a few of them near the nest and the sphere.
    let mut rng = Rng::new(if filled { 21 } else { 22 });
    let mut unit = || f64::from(rng.next()) / 4_294_967_296.0;
    while pos.len() < 600 {
        let p = if pos.len().is_multiple_of(5) {
            [26.0 + 8.0 * unit(), 6.0 + 8.0 * unit(), 8.0 + 8.0 * unit()]
        } else {
            [40.0 * unit(), 20.0 * unit(), 40.0 * unit()]
        };
        pos.push(p);
    }
    let n = pos.len();
    w.sensed.resize(n);
    w.sensed.pos = pos;
    let mut rng = Rng::new(5);
    for j in 0..n {
        let s = &mut w.sensed;
        // Ids are not the slots: ties in distance are broken by id.
        s.id[j] = ((j * 7919 + 13) % n) as u32 + 1000;
        let mut r = || f64::from(rng.below(2001)) / 500.0 - 2.0;
        s.vel[j] = [r(), r(), r()];
        s.density[j] = f64::from(rng.below(1000)) / 64.0;
    }
    w.size_grids(n);
    w
}

/// The frame inputs of the edge worlds: times, and goals of the active targets, the inactive
/// one, a missing id and none.
fn edge_inputs<S: TestScalar>(n: usize) -> Vec<FrameInput<S>> {
    let goals = [Some(11), Some(12), Some(13), Some(14), None];
    (0..n)
        .map(|i| FrameInput {
            t: S::from_f32(i as f32 * 0.37),
            goal: goals[i % goals.len()],
        })
        .collect()
}

/// The edge worlds in `S`: the GPU's frames against the CPU's.
fn edge_cases<S: TestScalar>() -> Agreement {
    let mut total = Agreement::default();
    for filled in [false, true] {
        let mut w = edge_world(filled);
        // The sensed values as the bees' scalar has them (an f32 bee senses f32 positions).
        let exact = |p: &mut [f64; 3]| *p = a3(v3::<S>(*p));
        w.sensed.pos.iter_mut().for_each(exact);
        w.sensed.vel.iter_mut().for_each(exact);
        w.index_positions();
        let what = if filled {
            "edge world, filled"
        } else {
            "edge world"
        };
        let inputs = edge_inputs::<S>(w.len());
        total.add(compare::<S>(what, &w, &inputs));
    }
    total
}

/// Fixed point: every edge case bit for bit; the GPU grid's cells are the key function's.
#[test]
fn fx_edge_cases_are_bit_for_bit() {
    let total = edge_cases::<Fx>();
    total.assert_identical("fixed point");
    println!(
        "fixed point, edge worlds: {} frames identical\n  {}",
        total.frames.same,
        total.coverage()
    );
    assert!(total.full > 50 && total.full_targets > 10 && total.inside > 50);
    assert!(total.obstacles > 100 && total.goals > 100);

    let w = edge_world(false);
    let inputs = edge_inputs::<Fx>(w.len());
    let got = gpu_frames::<Fx>(&w, &inputs);
    let shape = GridShape3::of(&w, w.len());
    for (j, &p) in w.sensed.pos.iter().enumerate() {
        assert_eq!(
            got.cells[j],
            shape.cell_of(v3::<Fx>(p)),
            "the cell of {p:?}"
        );
    }
    // The cells of the bees on the cell boundaries are the cells they start.
    let cell = f64::from(shape.cell);
    for (j, p) in w.sensed.pos.iter().enumerate().take(40).step_by(4) {
        let x = (p[0] / cell).round() as u32;
        if p[0] == cell * f64::from(x) && x < shape.size[0] {
            assert_eq!(shape.cell_xyz(v3::<Fx>(*p))[0], x, "bee {j} at {p:?}");
        }
    }
}

/// `f32`: the edge cases, measured.
#[test]
fn f32_edge_cases_are_measured() {
    let total = edge_cases::<f32>();
    println!(
        "f32, edge worlds: {:.2} % of {} frames bit-identical{}",
        100.0 * total.share(),
        total.frames.total,
        first_difference(total.first.as_ref()),
    );
    assert!(total.share() >= F32_FLOOR, "{total:?}");
}

/// A world without obstacles, targets or goals, and a world of one bee: empty frames but for
/// the time and the neighbours.
#[test]
fn bare_worlds_are_bit_for_bit() {
    let mut w = BeeWorld::new([0.0; 3], [10.0; 3], RANGE, SENSE);
    w.sensed.resize(3);
    w.sensed.pos = vec![[1.0, 1.0, 1.0], [2.0, 1.0, 1.0], [9.0, 9.0, 9.0]];
    w.sensed.id = vec![7, 3, 5];
    w.index_targets();
    w.size_grids(3);
    w.index_positions();
    let inputs = edge_inputs::<Fx>(3);
    compare::<Fx>("bare world", &w, &inputs).assert_identical("bare world");
    w.sensed.resize(1);
    w.size_grids(1);
    w.index_positions();
    compare::<Fx>("one bee", &w, &inputs[..1]).assert_identical("one bee");
}

// ---- the layout ----

/// The sensing kernels compile (naga, as wgpu would) over both scalars.
#[test]
fn the_sensing_kernels_are_valid_wgsl() {
    assert_valid_wgsl("bee sensing", modules, SENSE_KERNEL);
    assert_eq!(scalar_module::<Fx>().name, "scalar_fx");
}

/// Both sides of the world's layout have the same constants.
#[test]
fn the_world_constants_are_the_shaders() {
    let wgsl = format!("{}{}", BEE_WORLD.source, BEE_SENSE.source);
    assert_constants(&wgsl, WGSL_CONSTANTS, true);
}

/// The open faces are `Shape3::surface`'s: a box's faces on or past the bounds closed, a
/// shaft's caps likewise, and the GPU's surface with them is the CPU's (checked by the edge
/// worlds); here the flags themselves.
#[test]
fn open_faces_are_the_cpus() {
    let (lo, hi) = ([0.0; 3], [40.0, 20.0, 40.0]);
    let ground = Shape3::Box {
        min: [0.0; 3],
        max: [40.0, 1.0, 40.0],
    };
    assert_eq!(open_faces(&ground, lo, hi), 1 << 3);
    let free = Shape3::Box {
        min: [1.0; 3],
        max: [2.0; 3],
    };
    assert_eq!(open_faces(&free, lo, hi), 0x3f);
    let shaft = |y_min, y_max| Shape3::Shaft {
        center: [5.0, 5.0],
        radius: 1.0,
        y_min,
        y_max,
    };
    assert_eq!(open_faces(&shaft(0.0, 20.0), lo, hi), 0);
    assert_eq!(open_faces(&shaft(1.0, 20.0), lo, hi), 1);
    assert_eq!(open_faces(&shaft(0.0, 19.0), lo, hi), 2);
    let sphere = Shape3::Sphere {
        center: [1.0; 3],
        radius: 1.0,
    };
    assert_eq!(open_faces(&sphere, lo, hi), 0);
    // The particles' grid holds every particle once, sorted by its cell.
    let w = edge_world(false);
    let words = world_words::<Fx>(&w, &GridShape3::of(&w, w.len()));
    let count = words[H_PARTICLES] as usize;
    assert_eq!(count, w.particles.len());
    let at = words[H_PARTICLES_AT] as usize;
    let mut seen: Vec<u32> = (0..count)
        .map(|k| words[at + k * PARTICLE_WORDS + 3])
        .collect();
    seen.sort_unstable();
    assert!(seen.iter().enumerate().all(|(k, &j)| j == k as u32));
}
