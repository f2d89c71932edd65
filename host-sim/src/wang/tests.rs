//! The wang2014 engine: the same bits on any thread count and slot order, in both scalars;
//! the boundary of eq. 2 the world hands an insect; the rules of a wang group.

use swarm_core::{Fx, Scalar, Vec3};

use super::*;
use crate::by_scalar;
use crate::scalar::a3;
use crate::scenario::{self, ScalarType};

/// Fig. 8's scenario with the first group in `scalar` and a second, fixed-point group, the
/// ball moved at step 30 (a re-solve).
fn chase(scalar: ScalarType) -> scenario::Scenario {
    let mut sc = scenario::builtin("wang-fig8-chasing").unwrap();
    sc.groups[0].scalar = scalar;
    sc.groups[0].count = 150;
    let mut second = sc.groups[0].clone();
    second.name = "fixed".into();
    second.scalar = ScalarType::Fixed;
    sc.groups.push(second);
    sc.events[0].step = 30;
    // A larger MDE distance, so that minimum distance enforcement acts in a short run.
    for g in &mut sc.groups {
        if let Some(t) = g.params.as_mut() {
            t.insert("d_min".into(), toml::Value::Float(0.5));
        }
    }
    sc.set_steps(60);
    sc.validate().unwrap();
    sc
}

/// Hash of every insect's state bits in id order, and the counts.
fn hash(sim: &WangSim) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut mix = |x: u64| h = (h ^ x).wrapping_mul(0x100_0000_01b3);
    for g in &sim.groups {
        by_scalar!(g, g => for (id, s) in g.by_id() {
            mix(u64::from(id));
            for c in a3(s.pos).into_iter().chain(a3(s.vel)) {
                mix(c.to_bits());
            }
        });
    }
    mix(sim.total.pushed);
    mix(sim.total.obstacle + sim.total.bounds);
    h
}

fn run(threads: usize, reorder: u32, scalar: ScalarType) -> u64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let sc = chase(scalar);
        let mut sim = WangSim::from_scenario(&sc, 3).unwrap();
        sim.reorder_every = reorder;
        for _ in 0..sc.steps {
            crate::engine::apply_due_events(&mut sim, &sc);
            sim.tick().unwrap();
        }
        assert!(sim.total.pushed > 0, "MDE acted");
        hash(&sim)
    })
}

#[test]
fn bit_identical_for_any_thread_count_and_slot_order() {
    for scalar in [ScalarType::F32, ScalarType::Fixed] {
        let base = run(1, 0, scalar);
        assert_eq!(base, run(2, 0, scalar), "{scalar:?}");
        assert_eq!(base, run(2, 7, scalar), "{scalar:?}");
    }
}

#[test]
fn a_moved_goal_is_solved_again_and_reported() {
    let sc = chase(ScalarType::F32);
    let mut sim = WangSim::from_scenario(&sc, 1).unwrap();
    assert_eq!(
        crate::engine::Engine::notes(&mut sim).len(),
        1,
        "the first solve"
    );
    let ball = sc.object_id("ball").unwrap();
    // Between the ball's first place (z 30) and its second (z 50).
    let at = Vec3::new(46.0f32, 20.0, 40.0);
    let before = sim.world.field(ball).unwrap().guide_at(at);
    sim.apply(ball, &sc.events[0].action);
    sim.tick().unwrap();
    let notes = crate::engine::Engine::notes(&mut sim);
    assert!(notes.len() == 1 && notes[0].contains("cells"), "{notes:?}");
    let after = sim.world.field(ball).unwrap().guide_at(at);
    assert!(before.z < -0.5, "toward the ball at z 30: {before:?}");
    assert!(after.z > 0.5, "toward the ball at z 50: {after:?}");
}

#[test]
fn the_boundary_is_the_nearest_surface_with_its_curvature() {
    let mut w = WangWorld::new([0.0; 3], [20.0; 3], 1.0, 1.0, 0.05).unwrap();
    w.obstacles.push(crate::space::BeeObstacle::new(
        0,
        "ball",
        crate::space::Shape3::Sphere {
            center: [10.0; 3],
            radius: 2.0,
        },
        true,
    ));
    w.obstacles.push(crate::space::BeeObstacle::new(
        1,
        "shaft",
        crate::space::Shape3::Shaft {
            center: [5.0, 5.0],
            radius: 1.0,
            y_min: 0.0,
            y_max: 20.0,
        },
        true,
    ));
    // Beside the ball: curvature 1/|p − c|, no axis.
    let b = w.boundary(Vec3::new(12.5f32, 10.0, 10.0), 1.0).unwrap();
    assert_eq!(
        (b.normal, b.curvature),
        (Vec3::new(1.0, 0.0, 0.0), 1.0 / 2.5)
    );
    assert_eq!(b.axis, Vec3::zero());
    // Beside the shaft's side: 1/ρ about the vertical axis.
    let b = w.boundary(Vec3::new(6.5f32, 10.0, 5.0), 1.0).unwrap();
    assert_eq!((b.curvature, b.axis), (1.0 / 1.5, Vec3::new(0.0, 1.0, 0.0)));
    // Near a wall: its inward normal, planar.
    let b = w.boundary(Vec3::new(0.25f32, 10.0, 15.0), 1.0).unwrap();
    assert_eq!((b.normal, b.curvature), (Vec3::new(1.0, 0.0, 0.0), 0.0));
    assert_eq!(b.point, Vec3::new(0.0, 10.0, 15.0));
    // Farther than d0 from everything: none.
    assert!(w.boundary(Vec3::new(15.0f32, 15.0, 15.0), 1.0).is_none());
    // The same in fixed point.
    let b = w
        .boundary(Vec3::<Fx>::from_f32(12.5, 10.0, 10.0), Fx::ONE)
        .unwrap();
    assert!((b.curvature.to_f32() - 0.4).abs() < 1e-4);
}

#[test]
fn insects_never_end_a_step_inside_an_obstacle_and_the_bench_world_runs() {
    for scalar in [ScalarType::F32, ScalarType::Fixed] {
        let mut sim = bench_wang_world(2000, 5, scalar);
        for _ in 0..50 {
            sim.tick().unwrap();
        }
        let w = &sim.world;
        for p in sim.positions_by_id() {
            let p = crate::scalar::v3::<f32>(p);
            assert!(
                !w.obstacles
                    .iter()
                    .any(|o| o.shape.surface(p, w.min, w.max).inside),
                "{p:?}"
            );
        }
    }
}

#[test]
fn the_shaped_bench_world_refines_the_grid_and_copies_obstacles_clear_of_the_goal() {
    let base = bench_wang_world(4000, 5, ScalarType::F32);
    let shape = WangBenchShape {
        grid_refine: 2,
        obstacle_copies: 4,
    };
    let mut sim = bench_wang_world_shaped(4000, 5, ScalarType::F32, shape);
    let w = &sim.world;
    assert_eq!(w.grid.dims, base.world.grid.dims.map(|d| 2 * d));
    assert_eq!(w.obstacles.len(), 16);
    assert_eq!(&w.obstacles[..4], &base.world.obstacles[..]);
    let Some(GoalArea::Ball { center, radius }) = w.goals.first().map(|g| &g.area) else {
        panic!("a ball goal");
    };
    for o in &w.obstacles {
        let (lo, hi) = o.shape.aabb();
        let d2: f32 = (0..3)
            .map(|k| (center[k] - center[k].clamp(lo[k], hi[k])).powi(2))
            .sum();
        assert!(d2.sqrt() > *radius, "{o:?}");
    }
    for _ in 0..5 {
        sim.tick().unwrap();
    }
}

#[test]
fn a_goal_of_the_wrong_kind_or_none_is_refused_by_name() {
    let text = scenario::builtin("wang-fig9-aggregation")
        .unwrap()
        .to_toml()
        .unwrap();
    let no_goal = text.replace("goal = \"home\"\n", "");
    let e = scenario::Scenario::from_str(&no_goal, "test.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("groups[0].goal") && e.contains("missing field `goal`"),
        "{e}"
    );
    let bad = text
        .replace(
            "spawn = { at = \"home\", radius = 3.0 }",
            "spawn = { min = [5, 5, 5], max = [15, 15, 15] }",
        )
        .replace("kind = \"zone\"", "kind = \"target\"\nparticles = 10");
    let e = scenario::Scenario::from_str(&bad, "test.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("expected a goal area"), "{e}");
    // A zone and a region survive a round trip through TOML.
    for name in ["wang-fig9-aggregation", "wang-fig6-two-blocks"] {
        let sc = scenario::builtin(name).unwrap();
        let again = scenario::Scenario::from_str(&sc.to_toml().unwrap(), "again.toml").unwrap();
        assert_eq!(again.objects, sc.objects, "{name}");
    }
}
