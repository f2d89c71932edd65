use swarm_core::Vec3;

use super::*;

/// Runs `steps` steps of the random cube on `threads` threads; the bodies by id.
fn run_cube(n: usize, steps: u32, threads: usize, reorder: u32) -> Vec<Body<f32>> {
    let cube = random_cube(n, 7, 8.0);
    let mut crowd = OrcaCrowd::new(&cube.positions, CrowdParams::rvo2_cube()).unwrap();
    crowd.set_reorder_every(reorder);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        for _ in 0..steps {
            crowd
                .step(|id, p| toward(cube.goals[id as usize], p))
                .unwrap();
        }
    });
    crowd.bodies()
}

/// Bit patterns, so that `-0.0 != 0.0` and NaN compare equal to themselves.
fn bits(b: &[Body<f32>]) -> Vec<[u32; 6]> {
    b.iter()
        .map(|b| [b.pos.x, b.pos.y, b.pos.z, b.vel.x, b.vel.y, b.vel.z].map(f32::to_bits))
        .collect()
}

#[test]
fn orca_crowd_is_deterministic_across_threads_and_slot_orders() {
    let want = bits(&run_cube(600, 12, 1, 0));
    for (threads, reorder) in [(2, 0), (3, 1), (4, 5), (2, 8)] {
        assert_eq!(
            bits(&run_cube(600, 12, threads, reorder)),
            want,
            "{threads} threads, reorder every {reorder}"
        );
    }
}

#[test]
fn orca_cube_at_spacing_8_has_no_overlaps() {
    let cube = random_cube(343, 3, 8.0);
    let mut crowd = OrcaCrowd::new(&cube.positions, CrowdParams::rvo2_cube()).unwrap();
    assert_eq!(crowd.overlaps(), 0);
    for s in 0..60 {
        crowd
            .step(|id, p| toward(cube.goals[id as usize], p))
            .unwrap();
        assert_eq!(crowd.overlaps(), 0, "step {s}");
    }
}

#[test]
fn orca_agents_reach_their_goals() {
    // 64 agents swap places on a small jittered lattice (every path crosses others), with
    // the benchmark's parameters.
    let cube = random_cube(64, 11, 5.0);
    let mut crowd = OrcaCrowd::new(&cube.positions, CrowdParams::rvo2_cube()).unwrap();
    let mut steps = 0;
    while steps < 2000 && dist_to_goals(&crowd, &cube.goals) > 0.01 {
        crowd
            .step(|id, p| toward(cube.goals[id as usize], p))
            .unwrap();
        steps += 1;
    }
    assert!(
        dist_to_goals(&crowd, &cube.goals) <= 0.01,
        "after {steps} steps"
    );
}

/// The largest distance of an agent from its goal.
fn dist_to_goals(crowd: &OrcaCrowd, goals: &[Vec3<f32>]) -> f32 {
    crowd
        .positions()
        .iter()
        .zip(goals)
        .map(|(p, g)| (*p - *g).length())
        .fold(0.0, f32::max)
}

#[test]
fn orca_bad_input_is_a_typed_error() {
    let mut p = CrowdParams::rvo2_cube();
    p.orca.max_neighbors = MAX_NEIGHBORS as u16 + 1;
    let at = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(5.0, 0.0, 0.0)];
    assert!(matches!(
        OrcaCrowd::new(&at, p),
        Err(SimError::GroupParams {
            source: Error::BadParam {
                field: "max_neighbors"
            },
            ..
        })
    ));
    p = CrowdParams::rvo2_cube();
    p.neighbor_dist = f32::NAN;
    assert!(OrcaCrowd::new(&at, p).is_err());
    p = CrowdParams::rvo2_cube();
    p.orca.dt = 0.0;
    assert!(OrcaCrowd::new(&at, p).is_err());
    let nan = [Vec3::new(f32::NAN, 0.0, 0.0)];
    assert!(OrcaCrowd::new(&nan, CrowdParams::rvo2_cube()).is_err());

    // A preferred velocity that is not finite: the lowest failing agent is named, and the
    // crowd is left as it was.
    let mut crowd = OrcaCrowd::new(&at, CrowdParams::rvo2_cube()).unwrap();
    let before = crowd.bodies();
    let e = crowd
        .step(|_, _| Vec3::new(f32::INFINITY, 0.0, 0.0))
        .unwrap_err();
    assert!(
        matches!(
            e,
            SimError::Controller {
                phase: "orca",
                step: 0,
                agent: 0,
                ..
            }
        ),
        "{e}"
    );
    assert_eq!(crowd.bodies(), before);
    assert_eq!(crowd.steps(), 0);
}

#[test]
fn orca_empty_and_lonely_crowds_step() {
    let mut crowd = OrcaCrowd::new(&[], CrowdParams::rvo2_cube()).unwrap();
    assert!(crowd.is_empty());
    crowd.step(|_, _| Vec3::new(1.0, 0.0, 0.0)).unwrap();
    assert_eq!(crowd.overlaps(), 0);

    // One agent, far from anyone: it flies at its preferred velocity, capped at max_speed.
    let mut crowd = OrcaCrowd::new(&[Vec3::new(5.0, 5.0, 5.0)], CrowdParams::rvo2_cube()).unwrap();
    crowd.step(|_, _| Vec3::new(3.0, 0.0, 0.0)).unwrap();
    crowd.step(|_, _| Vec3::new(0.0, 1.0, 0.0)).unwrap();
    let b = crowd.bodies()[0];
    assert_eq!(b.vel, Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(b.pos, Vec3::new(5.25, 5.125, 5.0));
    assert_eq!((crowd.len(), crowd.steps()), (1, 2));
}

#[test]
fn orca_overlaps_counts_pairs_closer_than_two_radii() {
    let p = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.9, 0.0, 0.0),
        Vec3::new(6.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0),
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::new(100.0, 0.0, 0.0),
    ];
    // (0, 1) and (0, 3) are closer than 3; (0, 4) is exactly 3 apart, (1, 2) 3.1.
    assert_eq!(overlaps(&p, 1.5), 2);
    assert_eq!(overlaps(&p[..1], 1.5), 0);
    assert_eq!(overlaps(&[], 1.5), 0);
}

#[test]
fn orca_random_cube_matches_the_cpp_driver() {
    // Printed by a probe built from scripts/rvo2/random_cube.cc's `mix32`, `unit`, lattice and
    // permutation code (g++ 12, -O3, x86-64): n = 1000, seed 42, spacing 8.
    assert_eq!(
        [cube::mix32(0), cube::mix32(1), cube::mix32(0xdead_beef)],
        [0, 0x6889_90c0, 0xe628_c683]
    );
    let c = random_cube(1000, 42, 8.0);
    let want: [(usize, [u32; 3], usize); 4] = [
        (0, [0x3e07_6aa0, 0x3f74_78a6, 0x3e79_a4c0], 892),
        (1, [0x4109_7102, 0xbd81_04a0, 0xbf03_19c2], 633),
        (37, [0x425c_4e0a, 0x41c0_76e4, 0x3f10_2274], 282),
        (999, [0x428e_31b2, 0x428e_b411, 0x4291_db14], 795),
    ];
    for (i, pos, goal) in want {
        let p = c.positions[i];
        assert_eq!([p.x, p.y, p.z].map(f32::to_bits), pos, "agent {i}");
        assert_eq!(c.goals[i], c.positions[goal], "goal of agent {i}");
    }
    // A permutation: every lattice point is somebody's goal.
    let mut g: Vec<[u32; 3]> = c
        .goals
        .iter()
        .map(|p| [p.x, p.y, p.z].map(f32::to_bits))
        .collect();
    g.sort();
    g.dedup();
    assert_eq!(g.len(), 1000);
}
