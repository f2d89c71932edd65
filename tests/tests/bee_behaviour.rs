//! The bee behaviours of chen §IV-V (issue 3), on the built-in scenarios with their fixed
//! seeds, through the whole simulator (scenario → engine → controller). The numbers quoted in
//! the comments were measured with these seeds.

use std::collections::HashMap;

use swarm_sim::bees::{AnyBeeGroup, BeeSim};
use swarm_sim::scenario::{self, ObjectKind, Scenario};

fn load(name: &str) -> (Scenario, BeeSim) {
    let sc = scenario::builtin(name).expect("built-in scenario");
    let sim = BeeSim::from_scenario(&sc, swarm_tests::seed(sc.seed)).expect("builds");
    (sc, sim)
}

fn norm(v: &[f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// Every bee's position by id, from the sensed world.
fn positions_by_id(sim: &BeeSim) -> HashMap<u32, [f64; 3]> {
    let s = &sim.world.sensed;
    s.id.iter().copied().zip(s.pos.iter().copied()).collect()
}

/// The bees whose nearest neighbour is closer than `d` (a body overlap for d = 2r), by a
/// uniform grid of cell `d`.
fn overlapping(pos: &[[f64; 3]], d: f64) -> usize {
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let key = |p: &[f64; 3]| [0, 1, 2].map(|k| (p[k] / d).floor() as i64);
    for (i, p) in pos.iter().enumerate() {
        grid.entry(key(p)).or_default().push(i);
    }
    let close = |i: usize, p: &[f64; 3]| {
        let k = key(p);
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz])
                        .is_some_and(|v| {
                            v.iter().any(|&j| {
                                j != i
                                    && (0..3).map(|c| (p[c] - pos[j][c]).powi(2)).sum::<f64>()
                                        < d * d
                            })
                        })
                })
            })
        })
    };
    pos.iter().enumerate().filter(|&(i, p)| close(i, p)).count()
}

/// Counts body overlaps (a neighbour closer than 2r) over the bee-steps of a run.
#[derive(Default)]
struct Overlaps {
    overlapping: usize,
    bee_steps: usize,
}

impl Overlaps {
    fn sample(&mut self, sim: &BeeSim, two_r: f64) {
        self.overlapping += overlapping(&sim.world.sensed.pos, two_r);
        self.bee_steps += sim.agents();
    }

    fn fraction(&self) -> f64 {
        self.overlapping as f64 / self.bee_steps.max(1) as f64
    }

    /// Checks that bodies overlapped in under 1 % of the bee-steps.
    #[track_caller]
    fn assert_rare(&self) {
        let f = self.fraction();
        assert!(f < 0.01, "body overlap in {f} of the bee-steps");
    }
}

/// One avoiding bee-step seen from outside the controller (chen eq. 6-7): whether the shaft
/// nearest to where the bee was lies on its left of the forward axis o the step chose, the
/// roll set-point (rad), and eq. 6's magnitude at the distance to that shaft's surface.
struct AvoidingRoll {
    shaft_on_left: bool,
    roll: f64,
    eq6: f64,
}

/// The avoiding bee-steps of the last step; `before` holds the positions the step started from
/// and `shafts` the vertical shafts as (x, z, radius).
fn avoiding_rolls(
    sim: &BeeSim,
    before: &HashMap<u32, [f64; 3]>,
    shafts: &[(f64, f64, f64)],
    d0: f64,
) -> Vec<AvoidingRoll> {
    use swarm_core::Scalar;
    let mut out = Vec::new();
    for g in &sim.groups {
        let steps: Vec<(u32, [f64; 3], bool, f64)> = match g {
            AnyBeeGroup::F32(g) => g
                .by_id()
                .into_iter()
                .map(|(id, s, d)| {
                    let o = [s.forward.x, s.forward.y, s.forward.z].map(f64::from);
                    (id, o, d.avoiding, f64::from(d.roll))
                })
                .collect(),
            AnyBeeGroup::Fixed(g) => g
                .by_id()
                .into_iter()
                .map(|(id, s, d)| {
                    let o = [s.forward.x, s.forward.y, s.forward.z].map(|c| f64::from(c.to_f32()));
                    (id, o, d.avoiding, f64::from(d.roll.to_f32()))
                })
                .collect(),
        };
        for (id, o, avoiding, roll) in steps {
            if !avoiding {
                continue;
            }
            let p = before[&id];
            let (gap, x, z) = shafts
                .iter()
                .map(|&(x, z, r)| ((p[0] - x).hypot(p[2] - z) - r, x, z))
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .expect("shafts");
            // Eq. 7: y = [0, 1, 0] · (o × r_e), r_e horizontal toward the shaft's axis.
            let side = o[2] * (x - p[0]) - o[0] * (z - p[2]);
            out.push(AvoidingRoll {
                shaft_on_left: side > 0.0,
                roll,
                eq6: (-(d0 - gap).powi(2) / 2.0).exp() * 45f64.to_radians(),
            });
        }
    }
    out
}

/// chen Fig. 14: 100 bees fly through a field of seven vertical shafts to a goal beyond them,
/// 2000 steps (the observation window).
///
/// * (c) The controller avoids the shafts by itself: no bee ever ends a step inside a shaft,
///   and the world never had to put a bee back out of a shaft (`contacts.obstacle`, 0 over
///   seeds 1-40; before the forward axis followed the velocity and eq. 5 tuned every approach:
///   104 in 600 steps; closest approach to a shaft now 0.25) nor, more than a handful of times,
///   back into the bounds (`contacts.bounds` ≤ 5; 0 over seeds 1-40 since the world reaches 20
///   units past the goal and 10 beyond the sides: with the far wall 8 units behind the goal,
///   bees overshooting it met the wall 1-7 times for seeds 1, 7 and 12, and one bee of seed 16
///   drifted to a side wall). The swarm gets past the shafts (x > 40: observed 100 of 100).
/// * (d) Roll-to-avoid, checked from outside the controller: for every avoiding bee-step, the
///   shaft nearest to where the bee was is on its left or its right of the forward axis o
///   (eq. 7); the bee rolls away from it, positive (sway right) for a shaft on its left and
///   negative on its right, with eq. 6's magnitude e^{−(d0−d)²/2}·45° at the distance d to the
///   shaft's surface (to 1e-4 rad). Observed: 140 bee-steps with the shaft on the left, 80 on
///   the right, all 220 away and at eq. 6; over seeds 1-40, 46-172 on each side, all of them.
/// * (a) The bees hover on average: the mean altitude stays within 2 units of its start
///   (observed 13.88 → 14.21, worst drift 0.70) and no bee is within a unit of the ceiling at
///   the end (was 73 of 100, with 25-60 ceiling clamps a step).
/// * (b) The drag keeps the speed below the limit: mean speed under 0.6 × max_speed (observed
///   1.33 of 4) and under 1 % of the bee-steps at the limit (observed 0.01 %; was nearly
///   all).
#[test]
fn fig14_bees_avoid_the_shafts_by_themselves_hover_and_fly_below_the_speed_limit() {
    let (sc, mut sim) = load("bees-fig14-shafts");
    let shafts: Vec<(f64, f64, f64)> = sc
        .objects
        .iter()
        .filter_map(|o| match o.kind {
            ObjectKind::Shaft { center, radius, .. } => Some((
                f64::from(center[0]),
                f64::from(center[1]),
                f64::from(radius),
            )),
            _ => None,
        })
        .collect();
    assert_eq!(shafts.len(), 7);
    let max_speed = f64::from(
        swarm_sim::bees::bee_params(&sc.groups[0])
            .unwrap()
            .max_speed,
    );
    let ceiling = f64::from(sc.world.max()[1]);
    let n = sim.agents() as f64;
    let altitude = |sim: &BeeSim| sim.world.sensed.pos.iter().map(|p| p[1]).sum::<f64>() / n;
    let start_altitude = altitude(&sim);
    let (mut speed_sum, mut at_limit, mut worst_drift) = (0.0, 0usize, 0.0f64);
    let d0 = f64::from(swarm_sim::bees::bee_params(&sc.groups[0]).unwrap().d0);
    let two_r = 2.0 * f64::from(swarm_sim::bees::bee_params(&sc.groups[0]).unwrap().radius);
    let mut rolls = Vec::new();
    let mut min_gap = f64::INFINITY;
    // The shaft field: between the first and last rows of shafts (x) and the outer shafts (z).
    let (mut x_lo, mut x_hi, mut z_lo, mut z_hi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, z, _) in &shafts {
        if x < x_lo {
            x_lo = x;
        }
        if x > x_hi {
            x_hi = x;
        }
        if z < z_lo {
            z_lo = z;
        }
        if z > z_hi {
            z_hi = z;
        }
    }
    let mut through = vec![false; sim.agents()];
    let mut overlaps = Overlaps::default();
    for _ in 0..2000 {
        let before = positions_by_id(&sim);
        sim.step().expect("step");
        rolls.extend(avoiding_rolls(&sim, &before, &shafts, d0));
        overlaps.sample(&sim, two_r);
        for (id, p) in sim.world.sensed.id.iter().zip(&sim.world.sensed.pos) {
            if (x_lo..=x_hi).contains(&p[0]) && (z_lo..=z_hi).contains(&p[2]) {
                through[*id as usize] = true;
            }
        }
        for p in &sim.world.sensed.pos {
            for &(x, z, r) in &shafts {
                let gap = (p[0] - x).hypot(p[2] - z) - r;
                assert!(
                    gap > 0.0,
                    "a bee inside a shaft at step {}: {p:?}",
                    sim.step
                );
                min_gap = min_gap.min(gap);
            }
        }
        for v in &sim.world.sensed.vel {
            let s = norm(v);
            speed_sum += s;
            at_limit += usize::from(s > 0.999 * max_speed);
        }
        worst_drift = worst_drift.max((altitude(&sim) - start_altitude).abs());
    }
    let bee_steps = n * 2000.0;
    let mean_speed = speed_sum / bee_steps;
    let at_limit = at_limit as f64 / bee_steps;
    let near_ceiling = sim
        .world
        .sensed
        .pos
        .iter()
        .filter(|p| p[1] > ceiling - 1.0)
        .count();
    let past = sim.world.sensed.pos.iter().filter(|p| p[0] > 40.0).count();
    let through = through.iter().filter(|&&t| t).count() as f64 / n;
    // Eq. 6-7 from outside: shaft on the left → positive roll (sway right, away from it), on
    // the right → negative, with eq. 6's magnitude at the distance to it.
    let on_left = rolls.iter().filter(|r| r.shaft_on_left).count();
    let on_right = rolls.len() - on_left;
    let away = rolls
        .iter()
        .filter(|r| r.shaft_on_left == (r.roll > 0.0))
        .count();
    let eq6 = rolls
        .iter()
        .filter(|r| (r.roll.abs() - r.eq6).abs() < 1e-4)
        .count();
    println!(
        "fig14, 2000 steps, {n} bees: world corrections {:?}; closest approach to a shaft \
         {min_gap:.3}; avoiding bee-steps with the shaft on the left {on_left}, on the right \
         {on_right}, rolling away {away}, eq. 6 magnitude {eq6}; {past} bees past \
         the shafts; mean altitude {start_altitude:.2} -> {:.2} (worst drift {worst_drift:.2}), \
         {near_ceiling} within 1 of the ceiling; mean speed {mean_speed:.2} (limit \
         {max_speed}), fraction of bee-steps at the limit {at_limit:.4}; share of bees through \
         the shaft field {through:.2}; body overlap in {:.5} of the bee-steps",
        sim.contacts,
        altitude(&sim),
        overlaps.fraction(),
    );
    assert!(
        through >= 0.5,
        "only {through} of the bees flew through the shaft field"
    );
    overlaps.assert_rare();
    assert_eq!(
        sim.contacts.obstacle, 0,
        "the world had to put bees back out of a shaft: {:?}",
        sim.contacts
    );
    assert!(
        sim.contacts.bounds <= 5,
        "the world had to put bees back into the bounds: {:?}",
        sim.contacts
    );
    assert!(
        on_left >= 20 && on_right >= 20,
        "shafts passed: {on_left} on the left, {on_right} on the right"
    );
    assert_eq!(away, rolls.len(), "bee-steps rolling toward the shaft");
    assert_eq!(eq6, rolls.len(), "bee-steps off eq. 6's roll magnitude");
    assert!(past >= 90, "only {past} bees got past the shafts");
    assert!(worst_drift < 2.0, "mean altitude drifted by {worst_drift}");
    assert_eq!(near_ceiling, 0, "bees at the ceiling");
    assert!(mean_speed < 0.6 * max_speed, "mean speed {mean_speed}");
    assert!(
        at_limit < 0.01,
        "{at_limit} of the bee-steps at the speed limit"
    );
}

/// Local extrema of `xs` whose swing to the next extremum is at least `min_swing` (a zig-zag
/// filter: noise of smaller amplitude does not count), as (index, value).
fn turning_points(xs: &[f64], min_swing: f64) -> Vec<(usize, f64)> {
    let mut out: Vec<(usize, f64)> = Vec::new();
    let (mut hi, mut lo) = ((0usize, xs[0]), (0usize, xs[0]));
    let mut dir = 0i8;
    for (i, &x) in xs.iter().enumerate() {
        if x > hi.1 {
            hi = (i, x);
        }
        if x < lo.1 {
            lo = (i, x);
        }
        match dir {
            0 if hi.1 - lo.1 >= min_swing => dir = if hi.0 > lo.0 { 1 } else { -1 },
            1 if hi.1 - x >= min_swing => {
                out.push(hi);
                dir = -1;
                lo = (i, x);
            }
            -1 if x - lo.1 >= min_swing => {
                out.push(lo);
                dir = 1;
                hi = (i, x);
            }
            _ => {}
        }
    }
    out
}

/// Pearson correlation of two series of equal length.
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let va: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
    let vb: f64 = b.iter().map(|y| (y - mb).powi(2)).sum();
    cov / (va * vb).sqrt()
}

/// chen Fig. 15 and the issue's acceptance line: "around the nest the distance to the nest
/// oscillates (approach and push-back) instead of collapsing onto it". 350 bees, 5000 steps
/// (250 s, longer than the scenario's default 2000); the bees arrive around the nest by step
/// 1000 (the swarm-mean distance to the nest centre falls from 27.9 to about 8.3).
///
/// The measure, after the arrival (steps 1000-5000), on d = the distance of a bee to the nest
/// centre:
///
/// 1. Each bee: approach and push-back. Its d, run through a zig-zag filter with a swing of 1
///    unit, makes repeated cycles (a minimum, then a push-back of at least 1 unit): at least 12
///    for the median bee and 8 for the 10th percentile (observed 17 and 13, fewest 9).
/// 2. At every moment a part of the swarm is being pushed back: in every 0.5 s window at least
///    10 % of the bees move away from the nest by 0.25 or more (observed at least 19 %).
/// 3. No collapse: no bee ever comes within 2.5 + r of the centre (it would overlap the
///    particle sphere; observed closest 4.9), and the mean d stays above 4.5 (observed lowest
///    8.2); body overlap (a neighbour closer than 2r) in under 1 % of the bee-steps (observed
///    0 with the nest column's stiffness 60).
///
/// Issue 12 removed a swarm-level check: with one shared clock the whole swarm closed in and
/// was pushed back with eq. 3's thrust (the mean d oscillated between 5.2 and 5.8, correlation
/// with θ_pitch −0.96). Each bee now runs eq. 3-4 on its own clock, so the zig-zags of the
/// bees are independent and the swarm-mean distance is flat (8.2-8.5), as the paper's
/// low-aligned swarm should be.
#[test]
fn fig15_the_distance_to_the_nest_oscillates_instead_of_collapsing() {
    let (sc, mut sim) = load("bees-fig15-nest");
    let (c, r) = match sc.object("nest").map(|o| &o.kind) {
        Some(&ObjectKind::Target { center, radius, .. }) => {
            (center.map(f64::from), f64::from(radius))
        }
        _ => panic!("no nest"),
    };
    let params = swarm_sim::bees::bee_params(&sc.groups[0]).unwrap();
    let (bee_radius, dt) = (f64::from(params.radius), f64::from(params.dt));
    let n = sim.agents();
    let (arrival, steps) = (1000usize, 5000usize);
    let mut mean = Vec::with_capacity(steps);
    let mut per_bee = vec![Vec::with_capacity(steps); n];
    let mut closest = f64::INFINITY;
    let mut pushed_back = Vec::new();
    let mut window_start: Vec<f64> = Vec::new();
    let mut overlaps = Overlaps::default();
    for step in 0..steps {
        sim.step().expect("step");
        overlaps.sample(&sim, 2.0 * bee_radius);
        let d: Vec<f64> = sim
            .positions_by_id()
            .iter()
            .map(|p| norm(&[p[0] - c[0], p[1] - c[1], p[2] - c[2]]))
            .collect();
        closest = d.iter().copied().fold(closest, f64::min);
        mean.push(d.iter().sum::<f64>() / n as f64);
        for (s, &x) in per_bee.iter_mut().zip(&d) {
            s.push(x);
        }
        if step >= arrival && step % 10 == 0 {
            if !window_start.is_empty() {
                let away = d
                    .iter()
                    .zip(&window_start)
                    .filter(|(now, then)| *now - *then >= 0.25)
                    .count();
                pushed_back.push(away as f64 / n as f64);
            }
            window_start = d;
        }
    }
    let mut cycles: Vec<usize> = per_bee
        .iter()
        .map(|s| turning_points(&s[arrival..], 1.0).len() / 2)
        .collect();
    cycles.sort_unstable();
    let turns: Vec<(usize, f64)> = turning_points(&mean[arrival..], 0.25)
        .into_iter()
        .map(|(i, m)| (i + arrival + 1, m))
        .collect();
    let pitch: Vec<f64> = (arrival..steps)
        .map(|s| {
            let t = (s + 1) as f64 * dt;
            16.429 + 3.5 * (std::f64::consts::PI * (t + 2.986) / 35.972).sin()
        })
        .collect();
    let corr = correlation(&mean[arrival..], &pitch);
    let least_pushed = pushed_back.iter().copied().fold(1.0, f64::min);
    let lowest_mean = mean[arrival..]
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let sample: Vec<String> = mean
        .iter()
        .step_by(250)
        .map(|m| format!("{m:.2}"))
        .collect();
    println!(
        "fig15: mean distance to the nest centre every 250 steps: [{}]; turning points of the \
         mean after step {arrival} (swing 0.25): {turns:.2?}; correlation with the pitch \
         {corr:.3}; approach/push-back cycles per bee (swing 1): median {}, 10th percentile {}, \
         min {}; least fraction pushed back in 0.5 s {least_pushed:.3}; closest bee \
         {closest:.3}, lowest mean {lowest_mean:.3} (nest radius {r}); world corrections {:?}; body overlap in {:.5} of the bee-steps",
        sample.join(", "),
        cycles[n / 2],
        cycles[n / 10],
        cycles[0],
        sim.contacts,
        overlaps.fraction(),
    );
    assert!(
        cycles[n / 2] >= 12 && cycles[n / 10] >= 8,
        "bees do not approach repeatedly: median {}, 10th percentile {}",
        cycles[n / 2],
        cycles[n / 10]
    );
    assert!(
        least_pushed >= 0.1,
        "at some moment almost no bee was pushed back: {least_pushed}"
    );
    assert!(
        closest > r + bee_radius,
        "a bee reached the nest's particle sphere: {closest}"
    );
    overlaps.assert_rare();
    assert!(
        lowest_mean > 4.5,
        "the swarm collapsed onto the nest: {lowest_mean}"
    );
}

/// The swarm's mean lateral drift (units/s) flying to a goal with no obstacle: the velocity
/// component along the horizontal perpendicular of the direction from the swarm's start
/// centroid to the goal, averaged over the bees farther than 8 units from the goal (the
/// approach) and over `steps` steps.
fn lateral_drift(mut sc: Scenario, seed: u32, steps: usize) -> (f64, f64) {
    sc.objects
        .retain(|o| !matches!(o.kind, ObjectKind::Shaft { .. }));
    let goal = match sc.object("goal").map(|o| &o.kind) {
        Some(&ObjectKind::Target { center, .. }) => center.map(f64::from),
        _ => panic!("no goal"),
    };
    let two_r = 2.0 * f64::from(swarm_sim::bees::bee_params(&sc.groups[0]).unwrap().radius);
    let mut sim = BeeSim::from_scenario(&sc, seed).expect("builds");
    let n = sim.agents() as f64;
    let start = sim.world.sensed.pos.iter().fold([0.0; 3], |a, p| {
        [a[0] + p[0] / n, a[1] + p[1] / n, a[2] + p[2] / n]
    });
    let (dx, dz) = (goal[0] - start[0], goal[2] - start[2]);
    let len = dx.hypot(dz);
    let perp = [dz / len, -dx / len];
    let (mut sum, mut count) = (0.0, 0usize);
    let mut overlaps = Overlaps::default();
    for _ in 0..steps {
        sim.step().expect("step");
        overlaps.sample(&sim, two_r);
        let s = &sim.world.sensed;
        for (p, v) in s.pos.iter().zip(&s.vel) {
            if (goal[0] - p[0]).hypot(goal[2] - p[2]) > 8.0 {
                sum += v[0] * perp[0] + v[2] * perp[1];
                count += 1;
            }
        }
    }
    (sum / count.max(1) as f64, overlaps.fraction())
}

/// Moves the centre of the target `name` of `sc` to `center`.
fn move_target(sc: &mut Scenario, name: &str, center: [f32; 3]) {
    match sc
        .objects
        .iter_mut()
        .find(|o| o.name == name)
        .map(|o| &mut o.kind)
    {
        Some(ObjectKind::Target { center: c, .. }) => *c = center,
        _ => panic!("no target `{name}`"),
    }
}

/// Issue 12: with no obstacle and a goal straight ahead the swarm does not sway as one. Each
/// bee runs eq. 3-4 on its own clock (`bee_time`) and its sway is the roll's deviation from
/// its period mean, so the swarm's mean lateral drift during the approach (600 steps, 30 s) is
/// under 0.1 units/s (it was about 1.2 with the shared clock, 94-95 % of the bees drifting the
/// same way). Checked on the Fig. 14 scene without its shafts (100 bees flying +x) and on
/// two variants the scenario does not have: 30 bees to a goal in +z, and 250 fixed-point bees
/// to a goal in −x. Observed: |drift| ≤ 0.045 for 100 bees (seeds 1-20), ≤ 0.067 for 30 bees
/// and ≤ 0.024 for 250 (seeds 1-12 and 14); no body overlap. (30 bees spawned beside the
/// x = 0 wall drifted +0.04 to +0.14 away from it, with or without the curl noise: the crowd's
/// pressure spreads a swarm away from a wall, which is not sway.)
#[test]
fn with_no_obstacle_the_swarm_does_not_drift_sideways() {
    use swarm_sim::scenario::{ScalarType, SpawnRegion};
    let (sc, sim) = load("bees-fig14-shafts");
    let seed = sim.seed;
    let mut variants = vec![("100 bees, +x", sc.clone())];
    let mut side = sc.clone();
    side.groups[0].count = 30;
    move_target(&mut side, "goal", [36.0, 14.0, 60.0]);
    // Spawned in the middle of the world's width, so that the crowd's pressure spreads it
    // evenly (a swarm spawned beside a wall spreads away from it: a drift that is not sway).
    side.groups[0].spawn.region = SpawnRegion::Box {
        min: vec![31.0, 8.0, 0.0],
        max: vec![41.0, 20.0, 12.0],
    };
    variants.push(("30 bees, +z", side));
    let mut back = sc;
    back.groups[0].count = 250;
    back.groups[0].scalar = ScalarType::Fixed;
    // Start near the far end and fly back toward x = 8.
    move_target(&mut back, "goal", [8.0, 14.0, 30.0]);
    back.groups[0].spawn.region = SpawnRegion::Box {
        min: vec![52.0, 8.0, 18.0],
        max: vec![66.0, 20.0, 42.0],
    };
    variants.push(("250 fixed-point bees, -x", back));
    for (what, sc) in variants {
        let (drift, overlap) = lateral_drift(sc, seed, 600);
        println!(
            "no obstacle, {what}: mean lateral drift {drift:.4} units/s, overlap {overlap:.5}"
        );
        assert!(
            drift.abs() < 0.1,
            "{what}: the swarm drifts sideways at {drift} units/s"
        );
        assert!(
            overlap < 0.01,
            "{what}: body overlap in {overlap} of the bee-steps"
        );
    }
}

/// chen Fig. 11, issue 12: the grassland swarm gathers (the scene's loose `gathering` target
/// over the middle of the grass) instead of spreading over the box and pressing on its walls
/// (tens of thousands of bounds corrections before), and its bees do not overlap. 1000 bees,
/// 1500 steps: at every step at least 90 % of the bees are more than a unit from every side
/// wall and the ceiling (observed at least 99.7 %), and under 1 % of the bee-steps have a
/// neighbour closer than 2r (observed 0 with the grassland stiffness 200; 9 % with 20).
#[test]
fn fig11_the_grassland_swarm_gathers_off_the_walls_without_overlapping() {
    let (sc, mut sim) = load("bees-fig11-grassland");
    let bound = |v: &[f32]| [0, 1, 2].map(|k| f64::from(v[k]));
    let (min, max) = (bound(sc.world.min()), bound(sc.world.max()));
    let two_r = 2.0 * f64::from(swarm_sim::bees::bee_params(&sc.groups[0]).unwrap().radius);
    let n = sim.agents() as f64;
    let mut worst_off = 1.0f64;
    let mut overlaps = Overlaps::default();
    let steps = sc.steps as usize;
    for _ in 0..steps {
        sim.step().expect("step");
        overlaps.sample(&sim, two_r);
        let off = sim
            .world
            .sensed
            .pos
            .iter()
            .filter(|p| (0..3).all(|k| (k == 1 || p[k] - min[k] > 1.0) && max[k] - p[k] > 1.0))
            .count() as f64
            / n;
        worst_off = worst_off.min(off);
    }
    println!(
        "fig11, {steps} steps, {n} bees: least share of bees off the walls {worst_off:.4}; body \
         overlap in {:.5} of the bee-steps; world corrections {:?}",
        overlaps.fraction(),
        sim.contacts
    );
    assert!(
        worst_off >= 0.9,
        "only {worst_off} of the bees off the walls"
    );
    overlaps.assert_rare();
}
