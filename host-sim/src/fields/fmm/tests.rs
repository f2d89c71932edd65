//! Tests of the cost field and its guide (spec §4 W-T8 to W-T11).

use swarm_core::{Fx, Scalar, Vec3};

use super::*;

/// splitmix64: a small deterministic generator for test layouts and start points.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [a, b).
    fn range(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * ((self.next() >> 40) as f32 / (1u64 << 24) as f32)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// A scene: world bounds, obstacles, goal regions.
struct Layout {
    name: String,
    lo: [f32; 3],
    hi: [f32; 3],
    obstacles: Vec<Shape3>,
    goals: Vec<Shape3>,
}

impl Layout {
    fn build(&self) -> (CellGrid, SignedDistance, CostField) {
        let grid = CellGrid::new(self.lo, self.hi, 1.0).unwrap();
        let (sdf, field) = CostField::build(
            &grid,
            &self.obstacles,
            &self.goals,
            self.lo,
            self.hi,
            CostWeights::default(),
        )
        .unwrap();
        (grid, sdf, field)
    }

    /// Whether `p` lies inside an obstacle (exact shapes).
    fn blocked(&self, p: Vec3<f32>) -> bool {
        self.obstacles
            .iter()
            .any(|s| s.surface(p, self.lo, self.hi).inside)
    }
}

/// spec §3.2 wang-fig6 at half size: a 30 × 20 × 56 m world, two blocks filling it but for a
/// 6 m passage at x ∈ [12, 18], z ∈ [25, 31]; goal box z ∈ [50, 55].
fn two_blocks() -> Layout {
    Layout {
        name: "two blocks".into(),
        lo: [0.0; 3],
        hi: [30.0, 20.0, 56.0],
        obstacles: vec![
            Shape3::Box {
                min: [0.0, 0.0, 25.0],
                max: [12.0, 20.0, 31.0],
            },
            Shape3::Box {
                min: [18.0, 0.0, 25.0],
                max: [30.0, 20.0, 31.0],
            },
        ],
        goals: vec![Shape3::Box {
            min: [2.0, 2.0, 50.0],
            max: [28.0, 18.0, 55.0],
        }],
    }
}

fn spheres() -> Layout {
    Layout {
        name: "spheres".into(),
        lo: [0.0; 3],
        hi: [24.0; 3],
        obstacles: vec![
            Shape3::Sphere {
                center: [12.0, 12.0, 12.0],
                radius: 5.0,
            },
            Shape3::Sphere {
                center: [5.0, 18.0, 8.0],
                radius: 3.0,
            },
            Shape3::Sphere {
                center: [19.0, 5.0, 17.0],
                radius: 2.5,
            },
        ],
        goals: vec![Shape3::Sphere {
            center: [21.0, 20.0, 3.0],
            radius: 2.0,
        }],
    }
}

fn shaft_and_ground() -> Layout {
    Layout {
        name: "shaft and ground".into(),
        lo: [0.0; 3],
        hi: [30.0, 15.0, 20.0],
        obstacles: vec![
            Shape3::Box {
                min: [0.0, 0.0, 0.0],
                max: [30.0, 2.0, 20.0],
            },
            Shape3::Shaft {
                center: [15.0, 10.0],
                radius: 2.0,
                y_min: 0.0,
                y_max: 12.0,
            },
            Shape3::Sphere {
                center: [15.0, 12.5, 10.0],
                radius: 1.0,
            },
        ],
        goals: vec![Shape3::Sphere {
            center: [26.0, 5.0, 10.0],
            radius: 1.5,
        }],
    }
}

/// A random layout: a world of 16-28 m per side, 3-8 spheres, boxes and shafts, one goal
/// sphere (possibly touching an obstacle).
fn random_layout(seed: u64) -> Layout {
    let mut r = Rng(seed);
    let hi = [
        r.range(16.0, 28.0),
        r.range(16.0, 28.0),
        r.range(16.0, 28.0),
    ];
    let point = |r: &mut Rng| {
        [
            r.range(0.0, hi[0]),
            r.range(0.0, hi[1]),
            r.range(0.0, hi[2]),
        ]
    };
    let mut obstacles = Vec::new();
    for _ in 0..3 + r.below(6) {
        let c = point(&mut r);
        obstacles.push(match r.below(3) {
            0 => Shape3::Sphere {
                center: c,
                radius: r.range(1.0, 5.0),
            },
            1 => {
                let h = [r.range(0.5, 5.0), r.range(0.5, 5.0), r.range(0.5, 5.0)];
                Shape3::Box {
                    min: std::array::from_fn(|k| c[k] - h[k]),
                    max: std::array::from_fn(|k| c[k] + h[k]),
                }
            }
            _ => Shape3::Shaft {
                center: [c[0], c[2]],
                radius: r.range(0.5, 3.0),
                y_min: r.range(0.0, 0.5 * hi[1]),
                y_max: r.range(0.5 * hi[1], hi[1]),
            },
        });
    }
    let goal = Shape3::Sphere {
        center: point(&mut r),
        radius: r.range(0.3, 3.0),
    };
    Layout {
        name: format!("random layout {seed}"),
        lo: [0.0; 3],
        hi,
        obstacles,
        goals: vec![goal],
    }
}

/// W-T8: no obstacles, a point goal, F = A: the first-order FMM lies between the Euclidean
/// distance and the 6-connected (Manhattan) path cost, within 20 % beyond 5 cells and 12 %
/// beyond 10 (the Python prototype's 41³ grid: 17.9 % and 11.7 %).
#[test]
fn fmm_against_euclidean_and_manhattan_distance() {
    for l in [1.0f32, 0.25] {
        let n = 41.0 * l;
        let grid = CellGrid::new([0.0; 3], [n; 3], l).unwrap();
        assert_eq!(grid.dims, [41; 3]);
        let centre = grid.index([20; 3]);
        let mut goal = vec![false; grid.len()];
        goal[centre] = true;
        let w = CostWeights::default();
        let field = CostField::solve(&grid, &SignedDistance::empty(&grid), &goal, w).unwrap();
        let a = f64::from(w.a) * f64::from(l);
        let (mut worst5, mut worst10) = (0.0f64, 0.0f64);
        for i in 0..grid.len() {
            let c = grid.coords(i).map(|v| f64::from(v) - 20.0);
            let euclid = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            let manhattan = c[0].abs() + c[1].abs() + c[2].abs();
            let cost = f64::from(field.cost[i]);
            let tol = 1e-6 * (1.0 + cost);
            assert!(
                cost >= a * euclid - tol,
                "{:?}: C {cost} < A·d",
                grid.coords(i)
            );
            assert!(
                cost <= a * manhattan + tol,
                "{:?}: C {cost} > A·|d|₁",
                grid.coords(i)
            );
            let rel = (cost - a * euclid) / (a * euclid);
            if euclid >= 5.0 {
                worst5 = worst5.max(rel);
            }
            if euclid >= 10.0 {
                worst10 = worst10.max(rel);
            }
        }
        assert!(worst5 <= 0.20, "l = {l}: {worst5} at >= 5 cells");
        assert!(worst10 <= 0.12, "l = {l}: {worst10} at >= 10 cells");
        assert_eq!(field.solve.reachable, grid.len());
        assert_eq!(field.solve.goal_cells, 1);
    }
}

/// Every reachable non-goal cell has a 6-neighbour of strictly smaller cost.
fn assert_no_local_minimum(name: &str, field: &CostField) {
    let grid = &field.grid;
    let mut reachable = 0;
    for i in 0..grid.len() {
        let c = field.cost[i];
        if field.is_goal(i) {
            assert_eq!(c, 0.0, "{name}: goal cell {:?}", grid.coords(i));
            assert_eq!(field.guide(i), [0.0; 3]);
            continue;
        }
        if !c.is_finite() {
            assert_eq!(field.guide(i), [0.0; 3]);
            continue;
        }
        reachable += 1;
        assert!(c > 0.0);
        let lower = grid
            .neighbours(i)
            .into_iter()
            .flatten()
            .any(|j| field.cost[j] < c);
        assert!(
            lower,
            "{name}: cell {:?} (C = {c}) is a local minimum",
            grid.coords(i)
        );
        // Unit length up to the quantisation: each component within 1/254 (GuideCell).
        let g = field.guide(i);
        let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        assert!(
            (len - 1.0).abs() < 3f32.sqrt() / 254.0,
            "{name}: guide {g:?} at {:?}",
            grid.coords(i)
        );
    }
    assert_eq!(
        reachable + field.solve.goal_cells,
        field.solve.reachable,
        "{name}"
    );
}

/// W-T9 (§5.2, "there is no local minimum in the solved cost field"), on fixed and random
/// layouts, with the default and the paper's obstacle costs.
#[test]
fn no_local_minimum() {
    let mut layouts = vec![two_blocks(), spheres(), shaft_and_ground()];
    layouts.extend((1..=6).map(random_layout));
    for layout in &layouts {
        let grid = CellGrid::new(layout.lo, layout.hi, 1.0).unwrap();
        for w in [CostWeights::default(), CostWeights::paper()] {
            let (_, field) = CostField::build(
                &grid,
                &layout.obstacles,
                &layout.goals,
                layout.lo,
                layout.hi,
                w,
            )
            .unwrap();
            assert!(field.solve.goal_cells > 0);
            assert_no_local_minimum(&layout.name, &field);
        }
    }
}

/// With a finite cost inside obstacles every cell is reachable (C = +∞ is left for cells a
/// goal cannot reach at all, which only an infinite cost could make).
#[test]
fn every_cell_is_reachable_with_finite_obstacle_cost() {
    let (grid, _, field) = shaft_and_ground().build();
    assert_eq!(field.solve.reachable, grid.len());
    assert!(field.cost.iter().all(|c| c.is_finite()));
}

/// Flies from the centre of cell `start` along the guide alone in scalar `S` (speed `s0` = 1,
/// Δt = 0.1·l) until it is in a goal cell; the time it took in units of (C/A)/s0. Fails if that
/// passes 3 or the path enters an obstacle.
fn navigate<S: Scalar>(layout: &Layout, field: &CostField, start: usize) -> f32 {
    let grid = &field.grid;
    let a = CostWeights::default().a;
    let dt = 0.1 * grid.cell;
    let limit = 3.0 * field.cost[start] / a;
    let mut p = grid.center_vec::<S>(start);
    let step = S::from_f32(dt);
    let mut t = 0.0f32;
    loop {
        let q = p.to_f32();
        if grid
            .cell_of([q.x, q.y, q.z])
            .is_some_and(|c| field.is_goal(grid.index(c)))
        {
            return t / limit * 3.0;
        }
        assert!(
            t <= limit,
            "{} ({:?}): from {:?} (C = {}): not in the goal after {t} s, at {q:?}",
            layout.name,
            S::KIND,
            grid.coords(start),
            field.cost[start]
        );
        p += field.guide_at(p) * step;
        t += dt;
        assert!(
            !layout.blocked(p.to_f32()),
            "{} ({:?}): from {:?}: entered an obstacle at {:?}",
            layout.name,
            S::KIND,
            grid.coords(start),
            p.to_f32()
        );
    }
}

/// W-T10: from 1000 random free cells, the guide alone (Δt = 0.1·l/s0, s0 = 1) reaches the
/// goal within 3·(C/A)/s0 seconds, every time, without entering an obstacle; in f32 on the
/// two-blocks and spheres layouts, and from 200 of the cells in fixed point.
#[test]
fn navigation_completes() {
    for layout in [two_blocks(), spheres()] {
        let (grid, sdf, field) = layout.build();
        let mut rng = Rng(2014);
        let mut slowest = 0.0f32;
        let mut starts = 0;
        while starts < 1000 {
            let i = rng.below(grid.len());
            if sdf.phi[i] <= 0.0 || field.is_goal(i) {
                continue;
            }
            starts += 1;
            slowest = slowest.max(navigate::<f32>(&layout, &field, i));
            if starts <= 200 {
                slowest = slowest.max(navigate::<Fx>(&layout, &field, i));
            }
        }
        // A straight path at speed s0 would take 1 (C/A)/s0.
        assert!(slowest < 3.0, "{}: {slowest}", layout.name);
    }
}

/// W-T11: the signed distance, cost and guide are the same bits on every run, inside rayon
/// pools of 1 and 2 threads.
#[test]
fn solves_are_deterministic_for_any_thread_count() {
    for layout in [two_blocks(), random_layout(7)] {
        let bits = || {
            let (_, sdf, field) = layout.build();
            (
                sdf.phi.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                field.cost.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                (0..field.grid.len())
                    .flat_map(|i| field.guide(i).map(f32::to_bits))
                    .collect::<Vec<_>>(),
            )
        };
        let reference = bits();
        assert_eq!(bits(), reference);
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            assert_eq!(pool.install(bits), reference, "{threads} threads");
        }
    }
}

#[test]
fn refuses_bad_input() {
    let grid = CellGrid::new([0.0; 3], [4.0; 3], 1.0).unwrap();
    let sdf = SignedDistance::empty(&grid);
    let w = CostWeights::default();
    let none = vec![false; grid.len()];
    let e = CostField::solve(&grid, &sdf, &none, w).unwrap_err();
    assert!(matches!(e, SimError::FieldNoGoal { cells: 64 }), "{e}");
    let e = CostField::solve(&grid, &sdf, &none[1..], w).unwrap_err();
    assert!(
        matches!(
            e,
            SimError::FieldLength {
                len: 63,
                cells: 64,
                ..
            }
        ),
        "{e}"
    );
    let mut goal = none.clone();
    goal[0] = true;
    let short = SignedDistance { phi: vec![1.0; 3] };
    assert!(CostField::solve(&grid, &short, &goal, w).is_err());
    for bad in [
        CostWeights { a: 0.0, ..w },
        CostWeights { b: -0.1, ..w },
        CostWeights { inside: 0.0, ..w },
        CostWeights { a: f32::NAN, ..w },
        CostWeights {
            inside: f32::INFINITY,
            ..w
        },
    ] {
        let e = CostField::solve(&grid, &sdf, &goal, bad).unwrap_err();
        assert!(matches!(e, SimError::FieldWeights { .. }), "{e}");
    }
    let ok = CostField::solve(&grid, &sdf, &goal, w).unwrap();
    assert!(ok.is_goal(0) && !ok.is_goal(1) && !ok.is_goal(usize::MAX));
    assert!(
        ok.solve
            .to_string()
            .starts_with("cost field: 64 cells (64 reachable, 1 goal cells) in ")
    );
    let flat = CellGrid {
        dims: [4, 4, 0],
        ..grid.clone()
    };
    let e = CostField::solve(&flat, &SignedDistance { phi: vec![] }, &[], w).unwrap_err();
    assert!(matches!(e, SimError::FieldGridInvalid { .. }), "{e}");
}

/// Random points in and a little beyond the grid of `layout`.
fn random_points(grid: &CellGrid, seed: u64, n: usize) -> Vec<[f32; 3]> {
    let mut r = Rng(seed);
    let hi = grid.max();
    (0..n)
        .map(|_| std::array::from_fn(|k| r.range(grid.min[k] - 2.0, hi[k] + 2.0)))
        .collect()
}

/// The guide at points: f32 and Fx agree within 1e-3, unit length unless the nearest cell is a
/// goal cell, zero among goal cells, the border cells' values outside the grid, zero for
/// non-finite input.
#[test]
fn guide_at_points() {
    for layout in [two_blocks(), spheres(), random_layout(3)] {
        let (grid, _, field) = layout.build();
        let mut worst = 0.0f32;
        let mut apart = 0;
        for p in random_points(&grid, 11, 20_000) {
            let v = field.guide_at(Vec3::new(p[0], p[1], p[2]));
            let fx = field
                .guide_at(Vec3::<Fx>::from_f32(p[0], p[1], p[2]))
                .to_f32();
            let d = (v - fx).length();
            // Where the 8 vectors nearly cancel, normalising amplifies the rounding of the
            // weights (2⁻¹⁶ in Fx) by 1/|sum|: the agreement holds where |sum| ≥ 0.05, and at all
            // but a few points per thousand elsewhere.
            let (sum, _, _) = field.interpolate(Vec3::new(p[0], p[1], p[2])).unwrap();
            if sum.length() >= 0.05 {
                assert!(d < 1e-3, "{}: at {p:?} f32 {v:?} Fx {fx:?}", layout.name);
            }
            if d >= 1e-3 {
                apart += 1;
            }
            worst = worst.max(d);
            // The nearest cell centre to p, per axis the rounded (p − min)/cell − ½.
            let near: [u32; 3] = std::array::from_fn(|k| {
                let u = (p[k] - grid.min[k]) / grid.cell - 0.5;
                u.round().clamp(0.0, (grid.dims[k] - 1) as f32) as u32
            });
            let len = v.length();
            // Unit length, faded by the weight of the corners outside the goal within a cell
            // of it.
            let (_, _, reach) = field.interpolate(Vec3::new(p[0], p[1], p[2])).unwrap();
            if !field.is_goal(grid.index(near)) {
                assert!(
                    (len - reach.min(1.0)).abs() < 1e-3,
                    "{}: |v| = {len} at {p:?} (reach {reach})",
                    layout.name
                );
            }
        }
        assert!(
            apart <= 20,
            "{}: {apart} of 20000 points, worst {worst}",
            layout.name
        );
        // Zero deep in a goal region: at goal cell centres all of whose neighbours are goal
        // cells, and between such centres.
        let mut deep = 0;
        for i in 0..grid.len() {
            let all_goal = field.is_goal(i)
                && grid
                    .neighbours(i)
                    .into_iter()
                    .flatten()
                    .all(|j| field.is_goal(j));
            if all_goal {
                deep += 1;
                let c = grid.center_vec::<f32>(i);
                assert_eq!(field.guide_at(c), Vec3::zero());
                assert_eq!(field.guide_at(c.cast::<Fx>()), Vec3::zero());
            }
            if field.is_goal(i) {
                let c = grid.center_vec::<f32>(i);
                assert_eq!(field.guide_at(c), Vec3::zero(), "goal cell centre");
            }
        }
        assert!(deep > 0, "{}", layout.name);
        // Outside the grid: the value at the border.
        let hi = grid.max();
        let mut r = Rng(5);
        for _ in 0..200 {
            let p: [f32; 3] = std::array::from_fn(|k| r.range(grid.min[k], hi[k]));
            for k in 0..3 {
                for (out, border) in [
                    (grid.min[k] - 7.5, grid.min[k] + 0.5 * grid.cell),
                    (hi[k] + 3.0, hi[k] - 0.5 * grid.cell),
                    (-1e30, grid.min[k] + 0.5 * grid.cell),
                    (1e30, hi[k] - 0.5 * grid.cell),
                ] {
                    let (mut a, mut b) = (p, p);
                    a[k] = out;
                    b[k] = border;
                    let va = field.guide_at(Vec3::new(a[0], a[1], a[2]));
                    let vb = field.guide_at(Vec3::new(b[0], b[1], b[2]));
                    assert!((va - vb).length() < 1e-6, "{a:?}: {va:?} vs {b:?}: {vb:?}");
                }
            }
        }
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            assert_eq!(field.guide_at(Vec3::new(bad, 1.0, 1.0)), Vec3::zero());
            assert_eq!(field.guide_at(Vec3::new(1.0, 1.0, bad)), Vec3::zero());
        }
        let big = Vec3::<Fx>::from_f32(30000.0, -30000.0, 0.0);
        let v = field.guide_at(big).to_f32();
        assert!(v.length() < 1.001);
    }
}

/// An obstacle between start and goal: the guide at the start points around it (its ray
/// misses the obstacle), not into it, on the symmetry axis too (the one-sided gradient breaks
/// the tie).
#[test]
fn guide_goes_around_an_obstacle() {
    let r = 4.0;
    let centre = [20.5, 10.5, 10.5];
    let layout = Layout {
        name: "sphere on the way".into(),
        lo: [0.0; 3],
        hi: [40.0, 21.0, 21.0],
        obstacles: vec![Shape3::Sphere {
            center: centre,
            radius: r,
        }],
        goals: vec![Shape3::Sphere {
            center: [35.5, 10.5, 10.5],
            radius: 2.0,
        }],
    };
    let (_, _, field) = layout.build();
    let c = Vec3::new(centre[0], centre[1], centre[2]);
    for start in [[10.5, 10.5, 10.5], [10.5, 12.5, 10.5], [12.0, 10.0, 8.5]] {
        let s = Vec3::new(start[0], start[1], start[2]);
        let v = field.guide_at(s);
        assert!((v.length() - 1.0).abs() < 1e-3);
        // Closest approach of the ray s + t·v (t ≥ 0) to the centre.
        let t = (c - s).dot(v).max(0.0);
        let miss = (s + v * t - c).length();
        assert!(v.x > 0.0, "from {start:?}: {v:?} goes back");
        assert!(
            miss > r,
            "from {start:?}: {v:?} passes {miss} from the centre"
        );
    }
    let v = field.guide_at(Vec3::new(10.5f32, 12.5, 10.5));
    assert!(v.y > 0.0, "{v:?}: around the near side");
}

/// A scenario event that moves the goal: one `CostField::build` with the new goal turns the
/// guide around; moving an obstacle onto a point makes the guide there point out of it.
#[test]
fn rebuilding_follows_a_moved_goal_or_obstacle() {
    let (lo, hi) = ([0.0; 3], [30.0, 10.0, 10.0]);
    let grid = CellGrid::new(lo, hi, 1.0).unwrap();
    let w = CostWeights::default();
    let goal_at = |x: f32| Shape3::Sphere {
        center: [x, 5.0, 5.0],
        radius: 1.0,
    };
    let p = Vec3::new(15.2f32, 5.1, 4.9);
    let (_, east) = CostField::build(&grid, &[], &[goal_at(27.0)], lo, hi, w).unwrap();
    let (_, west) = CostField::build(&grid, &[], &[goal_at(3.0)], lo, hi, w).unwrap();
    assert!(east.guide_at(p).x > 0.99, "{:?}", east.guide_at(p));
    assert!(west.guide_at(p).x < -0.99, "{:?}", west.guide_at(p));
    let rock = Shape3::Sphere {
        center: [15.0, 5.0, 5.0],
        radius: 3.0,
    };
    let q = Vec3::new(16.5f32, 5.5, 5.5);
    let (sdf, moved) = CostField::build(&grid, &[rock], &[goal_at(27.0)], lo, hi, w).unwrap();
    assert!(sdf.inside(grid.index(grid.cell_of([16.5, 5.5, 5.5]).unwrap())));
    let v = moved.guide_at(q);
    // Out of the rock (away from its centre, and towards the goal).
    let out = (q - Vec3::new(15.0, 5.0, 5.0)).normalized().unwrap();
    assert!(v.dot(out) > 0.7 && v.x > 0.5, "{v:?}");
    assert!(moved.cost[grid.index([16, 5, 5])] > 1000.0);
}

/// Solve times on Table 1's largest grids (release: `cargo test --release -p swarm-sim --lib
/// fields -- --ignored --nocapture`).
#[test]
#[ignore = "timing, run by hand in release"]
fn solve_times() {
    let houses: Vec<Shape3> = (0..8)
        .map(|h| {
            let x = 35.0 + 12.0 * (h % 4) as f32;
            let z = if h < 4 { 10.0 } else { 35.0 };
            Shape3::Box {
                min: [x, 0.0, z],
                max: [x + 8.0, 6.0, z + 8.0],
            }
        })
        .collect();
    let cases = [
        (
            "phototaxis 100x100x100",
            [100.0, 100.0, 100.0],
            vec![
                Shape3::Shaft {
                    center: [50.0, 50.0],
                    radius: 0.2,
                    y_min: 0.0,
                    y_max: 6.0,
                },
                Shape3::Sphere {
                    center: [50.0, 6.5, 50.0],
                    radius: 0.5,
                },
            ],
            Shape3::Sphere {
                center: [50.0, 6.5, 50.0],
                radius: 3.0,
            },
        ),
        (
            "locusts 120x50x55",
            [120.0, 50.0, 55.0],
            houses,
            Shape3::Box {
                min: [105.0, 0.0, 0.0],
                max: [115.0, 50.0, 55.0],
            },
        ),
        (
            "two blocks 60x40x112",
            [60.0, 40.0, 112.0],
            vec![
                Shape3::Box {
                    min: [0.0, 0.0, 50.0],
                    max: [27.0, 40.0, 62.0],
                },
                Shape3::Box {
                    min: [33.0, 0.0, 50.0],
                    max: [60.0, 40.0, 62.0],
                },
            ],
            Shape3::Box {
                min: [0.0, 0.0, 100.0],
                max: [60.0, 40.0, 110.0],
            },
        ),
    ];
    for (name, hi, obstacles, goal) in cases {
        let lo = [0.0; 3];
        let grid = CellGrid::new(lo, hi, 1.0).unwrap();
        let t = Instant::now();
        let sdf = SignedDistance::build(&grid, &obstacles, lo, hi);
        let t_sdf = t.elapsed().as_secs_f64();
        let mask = grid.mask(std::slice::from_ref(&goal), lo, hi);
        let field = CostField::solve(&grid, &sdf, &mask, CostWeights::default()).unwrap();
        println!(
            "{name}: {} cells, signed distance {:.3} s, fast marching + guide {:.3} s ({} goal \
             cells, {} threads)",
            field.solve.cells,
            t_sdf,
            field.solve.seconds,
            field.solve.goal_cells,
            rayon::current_num_threads()
        );
        assert_no_local_minimum(name, &field);
    }
}

/// A record keeps the goal flag and each component within half a step (1/254) of the unit
/// vector it was made from, negative components included; zero stays zero.
#[test]
fn guide_records_round_trip() {
    assert_eq!(GuideCell::new([0.0; 3], false).0, 0);
    assert_eq!(GuideCell::new([0.0; 3], true).guide(), [0.0; 3]);
    assert!(GuideCell::new([0.0; 3], true).is_goal());
    let mut r = Rng(5);
    for _ in 0..10_000 {
        let v: [f32; 3] = std::array::from_fn(|_| r.range(-1.0, 1.0));
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let unit = v.map(|c| c / len);
        let cell = GuideCell::new(unit, false);
        assert!(!cell.is_goal());
        for (got, want) in cell.guide().into_iter().zip(unit) {
            assert!(
                (got - want).abs() <= 0.5 / 127.0 + 1e-6,
                "{unit:?} -> {got}"
            );
        }
    }
    assert_eq!(
        GuideCell::new([1.0, -1.0, 0.5], false).guide()[..2],
        [1.0, -1.0]
    );
}

/// `warm` reads inside the grid for any point: outside it on every side, non-finite, huge.
#[test]
fn warm_takes_any_point() {
    let (grid, _, field) = spheres().build();
    let hi = grid.max();
    let odd = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1e30, 1e30, 0.0];
    for x in odd.iter().chain(&[grid.min[0], hi[0]]) {
        for y in odd.iter().chain(&[hi[1]]) {
            std::hint::black_box(field.warm([*x, *y, hi[2] + 1.0]));
        }
    }
    for p in random_points(&grid, 12, 2_000) {
        std::hint::black_box(field.warm(p));
    }
}
