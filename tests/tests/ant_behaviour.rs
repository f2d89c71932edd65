//! The colony behaviours of xiang2018 §5, on the built-in scenarios with their fixed seeds,
//! through the whole simulator (scenario → engine → controller).

use std::collections::HashMap;

use swarm_core::Scalar;
use swarm_sim::ants::{AntEvent, AntSim, AnyAntGroup};
use swarm_sim::scenario::{self, Event, Scenario};

fn load(name: &str) -> (Scenario, AntSim) {
    let sc = scenario::builtin(name).expect("built-in scenario");
    let sim = AntSim::from_scenario(&sc, swarm_tests::seed(sc.seed)).expect("builds");
    (sc, sim)
}

/// Runs the scenario's events and ticks up to `until`, calling `each` after every tick.
fn run_until(
    sc: &Scenario,
    sim: &mut AntSim,
    until: u32,
    mut each: impl FnMut(&AntSim, &[AntEvent]),
) {
    while sim.step < until {
        let step = sim.step;
        for e in sc.events.iter().filter(|e| e.step == step) {
            let id = sc.object_id(e.action.object()).expect("event object");
            sim.apply(id, &e.action);
        }
        let events = sim.step().expect("tick");
        each(sim, &events);
    }
}

/// Positions of every ant, by id.
fn positions(sim: &AntSim) -> HashMap<u32, [f32; 2]> {
    let mut out = HashMap::new();
    for g in &sim.groups {
        match g {
            AnyAntGroup::F32(g) => out.extend(
                g.states_by_id()
                    .into_iter()
                    .map(|(id, s)| (id, [s.pos.x, s.pos.y])),
            ),
            AnyAntGroup::Fixed(g) => out.extend(
                g.states_by_id()
                    .into_iter()
                    .map(|(id, s)| (id, [s.pos.x.to_f32(), s.pos.y.to_f32()])),
            ),
        }
    }
    out
}

fn center(sc: &Scenario, name: &str) -> [f32; 2] {
    let c = sc
        .object(name)
        .and_then(|o| o.kind.center())
        .expect("object with a centre");
    [c[0], c[1]]
}

#[test]
fn fig7a_a_trail_forms_deliveries_grow_steadily_and_trips_are_direct() {
    let (sc, mut sim) = load("ants-fig7a-single-colony");
    let (nest, food) = (center(&sc, "nest"), center(&sc, "food"));
    // Edge to edge: an ant collects inside the food circle and drops inside the nest circle.
    let radius = |n: &str| sc.object(n).and_then(|o| o.kind.radius()).unwrap();
    let straight = (food[0] - nest[0]).hypot(food[1] - nest[1]) - radius("nest") - radius("food");
    let mut per_window = vec![0u32; 8]; // deliveries per 500 ticks
    let mut trip: HashMap<u32, f32> = HashMap::new();
    let mut trips = Vec::new();
    let mut last = positions(&sim);
    run_until(&sc, &mut sim, 4000, |sim, events| {
        let now = positions(sim);
        for (id, len) in trip.iter_mut() {
            let (a, b) = (last[id], now[id]);
            *len += (b[0] - a[0]).hypot(b[1] - a[1]);
        }
        for e in events {
            match *e {
                AntEvent::Collected { agent, .. } => {
                    trip.insert(agent, 0.0);
                }
                AntEvent::Delivered { agent, .. } => {
                    per_window[(sim.step as usize - 1) / 500] += 1;
                    if let Some(len) = trip.remove(&agent) {
                        // Trips completed once the trail exists (second half of the run).
                        if sim.step > 2000 {
                            trips.push(len);
                        }
                    }
                }
            }
        }
        last = now;
    });
    println!("deliveries per 500 ticks: {per_window:?}");
    assert!(
        per_window.iter().sum::<u32>() > 300,
        "food reaches the nest"
    );
    // Once the trail exists (second half), every window delivers, none collapses.
    let late = &per_window[4..];
    let mean = late.iter().sum::<u32>() as f32 / late.len() as f32;
    assert!(
        late.iter().all(|&d| d as f32 > 0.5 * mean),
        "steady deliveries: {late:?}"
    );
    // Directness: the straight nest-food distance (edge to edge) over the median length of the
    // laden trips (collect → drop) completed in the second half of the run.
    trips.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let median = trips[trips.len() / 2];
    let directness = straight / median;
    println!(
        "{} trips, median {median:.1} for a straight distance of {straight:.1}: directness {directness:.2}",
        trips.len()
    );
    // Measured 0.35 with seed 7 (median laden trip 257 for 90 straight), 0.28-0.38 over seeds
    // 1-30 (median trips 239-318): ants wiggle ±30° per tick (θ = π/6) and re-aim only on
    // contact. A regression guard, not a target.
    assert!(directness > 0.25, "trail directness {directness:.2}");
}

#[test]
fn fig8a_an_ant_only_ever_delivers_to_its_own_nest() {
    let (sc, mut sim) = load("ants-fig8a-hybrid");
    let home: HashMap<u32, u16> = sim
        .groups
        .iter()
        .flat_map(|g| match g {
            AnyAntGroup::F32(g) => g
                .states_by_id()
                .into_iter()
                .map(|(id, s)| (id, s.nest))
                .collect::<Vec<_>>(),
            AnyAntGroup::Fixed(g) => g
                .states_by_id()
                .into_iter()
                .map(|(id, s)| (id, s.nest))
                .collect(),
        })
        .collect();
    let mut delivered = 0;
    run_until(&sc, &mut sim, 3000, |_, events| {
        for e in events {
            if let AntEvent::Delivered { agent, nest } = *e {
                assert_eq!(
                    nest, home[&agent],
                    "ant {agent} delivered to another colony's nest"
                );
                delivered += 1;
            }
        }
    });
    assert!(delivered > 50, "{delivered} deliveries");
}

/// xiang2018 Fig. 12: the food source is moved at tick 2000. Every delivery is tagged with the
/// place its food was collected (the nearer of the old and the new centre) and the test follows
/// the two flows: the old trail's deliveries stop, the new source's start and reach the rate of
/// the old trail.
///
/// Deliveries in total do not stop: 500 ants wandering a 200 × 120 arena are everywhere, and
/// one of them is inside the moved food within 1-6 ticks of the move (seeds 1-12), while the
/// ants already laden drain the old trail over the next 200-600 ticks (a few lost ones for
/// longer). Over seeds 1-40, per 500 ticks: 184-257 old-trail deliveries before the move, 2-23
/// from 800 ticks after it (at most 12 % of before; the test allows 20 %), and 221-309
/// new-source deliveries at the end (at least 0.94 × the old trail's; the test asks 0.75 ×).
#[test]
fn fig12_deliveries_from_the_old_place_stop_after_the_food_moves_then_resume_from_the_new() {
    let (sc, mut sim) = load("ants-fig12-moved-food");
    let (moved, to) = sc
        .events
        .iter()
        .find_map(|e| match &e.action {
            scenario::Action::Move { to, .. } => Some((e.step, [to[0], to[1]])),
            _ => None,
        })
        .expect("a move");
    let from = center(&sc, "food");
    // An ant that stopped to collect before the move finishes collecting (§4.1).
    let last_old_collect = moved
        + u32::from(
            swarm_sim::ants::ant_params(&sc.groups[0])
                .unwrap()
                .collect_ticks,
        );
    let near_old =
        |p: [f32; 2]| (p[0] - from[0]).hypot(p[1] - from[1]) < (p[0] - to[0]).hypot(p[1] - to[1]);
    // Where each laden ant collected its food (nearer the old centre), and every delivery as
    // (tick, from the old place).
    let mut laden: HashMap<u32, bool> = HashMap::new();
    let mut delivered: Vec<(u32, bool)> = Vec::new();
    run_until(&sc, &mut sim, sc.steps, |sim, events| {
        let mut at = None;
        for e in events {
            match *e {
                AntEvent::Collected { agent, .. } => {
                    let p = at.get_or_insert_with(|| positions(sim))[&agent];
                    assert!(
                        sim.step <= last_old_collect || !near_old(p),
                        "ant {agent} collected at the old place {p:?} at tick {} (moved at {moved})",
                        sim.step
                    );
                    laden.insert(agent, near_old(p));
                }
                AntEvent::Delivered { agent, .. } => {
                    let old = laden
                        .remove(&agent)
                        .expect("a delivery without a collection");
                    delivered.push((sim.step, old));
                }
            }
        }
    });
    let count = |from_old: bool, t: std::ops::Range<u32>| {
        delivered
            .iter()
            .filter(|&&(s, o)| o == from_old && t.contains(&s))
            .count()
    };
    let before = count(true, moved - 500..moved);
    let drained = count(true, moved + 800..moved + 1300);
    let resumed = count(false, sc.steps - 500..sc.steps + 1);
    println!(
        "deliveries per 500 ticks: old trail {before} before the move, {drained} from 800 \
         ticks after it; new source {resumed} at the end"
    );
    assert!(before > 100, "no trail before the move: {before}");
    assert!(
        (drained as f32) < 0.2 * before as f32,
        "the old trail still delivers: {before} → {drained}"
    );
    assert!(
        resumed as f32 > 0.75 * before as f32,
        "deliveries do not resume at the new source: {resumed} (old trail {before})"
    );
}

/// The scenario's first event whose action is `verb` (`"start"`, `"stop"`, ...).
fn first_event<'a>(sc: &'a Scenario, verb: &str) -> &'a Event {
    sc.events
        .iter()
        .find(|e| e.action.verb() == verb)
        .unwrap_or_else(|| panic!("no `{verb}` event"))
}

#[test]
fn fig13_no_ant_lingers_inside_an_active_disturbance() {
    let (sc, mut sim) = load("ants-fig13-disturbance");
    let start = first_event(&sc, "start");
    let stop = first_event(&sc, "stop").step;
    let d = sc.object(start.action.object()).unwrap();
    let start = start.step;
    let (c, r) = (d.kind.center().unwrap().to_vec(), d.kind.radius().unwrap());
    let mut inside_since: HashMap<u32, u32> = HashMap::new();
    let mut longest = 0;
    run_until(&sc, &mut sim, stop, |sim, _| {
        if sim.step <= start {
            return;
        }
        for (id, p) in positions(sim) {
            if (p[0] - c[0]).hypot(p[1] - c[1]) < r {
                let since = *inside_since.entry(id).or_insert(sim.step);
                longest = longest.max(sim.step - since);
            } else {
                inside_since.remove(&id);
            }
        }
    });
    // Ants caught by the disturbance run straight out: at speed 1 that takes at most the
    // radius in ticks (plus a stop already under way).
    println!("longest stay inside the disturbance: {longest} ticks (radius {r})");
    assert!(
        (longest as f32) <= r + 12.0,
        "an ant lingered {longest} ticks"
    );
}

#[test]
fn fig11_the_trail_returns_toward_the_original_line_after_the_rocks_go() {
    let (sc, mut sim) = load("ants-fig11-dynamic-obstacles");
    let (nest, food) = (center(&sc, "nest"), center(&sc, "food"));
    let drop = sc.events.iter().map(|e| e.step).min().unwrap();
    let first_removal = sc
        .events
        .iter()
        .map(|e| e.step)
        .filter(|&t| t > drop)
        .min()
        .unwrap();
    // The measure: among the laden ants heading home on the middle half of the way (where the
    // rocks lie), the share within 2.5 units (half a rock's radius) of the straight nest-food
    // line; over the 500 ticks before the rocks come, the 500 ticks before the first one goes
    // (all three in place) and the last 500 ticks of the run (all gone for 1500 ticks).
    //
    // A share, not a mean or median distance: the trail keeps broadening for thousands of ticks
    // with or without rocks (without them, the median distance grows from about 6 to 8 over
    // this run), which would mask the return; the share on the line does not (0.22 before,
    // 0.18-0.20 at the end without rocks, over seeds 1-12).
    let on_line = |sim: &AntSim, tally: &mut [usize; 2]| {
        let (dx, dy) = (food[0] - nest[0], food[1] - nest[1]);
        let len = dx.hypot(dy);
        for g in &sim.groups {
            if let AnyAntGroup::F32(g) = g {
                for s in &g.states {
                    let (px, py) = (s.pos.x - nest[0], s.pos.y - nest[1]);
                    let t = (px * dx + py * dy) / (len * len);
                    // Heading home: on the trail, not a lost ant wandering.
                    let homeward = -(s.heading.x * dx + s.heading.y * dy) / len > 0.9;
                    if s.label == swarm_core::ant::Label::Food
                        && homeward
                        && (0.25..0.75).contains(&t)
                    {
                        tally[0] += usize::from((px * dy - py * dx).abs() / len < 2.5);
                        tally[1] += 1;
                    }
                }
            }
        }
    };
    let window = |end: u32| end - 500..end;
    let windows = [window(drop), window(first_removal), window(sc.steps)];
    let mut tallies = [[0usize; 2]; 3];
    run_until(&sc, &mut sim, sc.steps, |sim, _| {
        for (w, tally) in windows.iter().zip(&mut tallies) {
            if w.contains(&sim.step) {
                on_line(sim, tally);
            }
        }
    });
    assert!(
        tallies.iter().all(|t| t[1] > 5000),
        "too few ants measured: {tallies:?}"
    );
    let [before, during, after] = tallies.map(|[on, all]| on as f32 / all as f32);
    println!(
        "share of homeward laden ants on the nest-food line: before {before:.3}, with the rocks \
         {during:.3}, after {after:.3}"
    );
    // Over seeds 1-12: before 0.21-0.26, with rocks 0.017-0.031, after 0.15-0.22.
    assert!(
        during < 0.25 * before,
        "the rocks do not push the trail aside: {before:.3} → {during:.3}"
    );
    assert!(
        after > 0.5 * before,
        "the trail does not come back: {before:.3} → {during:.3} → {after:.3}"
    );
}

#[test]
fn fig14_ants_take_the_way_points_in_order_and_every_leg_is_foraged() {
    let (sc, mut sim) = load("ants-fig14-waypoints");
    let id = |n: &str| sc.object_id(n).unwrap();
    let route = [
        id("nest"),
        id("waypoint-1"),
        id("waypoint-2"),
        id("waypoint-3"),
        id("food"),
    ];
    assert_eq!(sim.world.route, route[1..4]);
    let homes = |sim: &AntSim| -> HashMap<u32, u16> {
        let s = &sim.world.sensed;
        s.id.iter().copied().zip(s.nest.iter().copied()).collect()
    };
    let mut before = homes(&sim);
    let (mut collected, mut delivered) = (HashMap::new(), HashMap::new());
    let mut first_reached: HashMap<u16, u32> = HashMap::new();
    run_until(&sc, &mut sim, 5000, |sim, events| {
        for e in events {
            match *e {
                AntEvent::Collected { agent, food } => {
                    // Only ever the destination of the ant's own leg.
                    let home = before[&agent];
                    let leg = route.iter().position(|&r| r == home).unwrap();
                    assert_eq!(food, route[leg + 1], "ant {agent} on leg {leg}");
                    *collected.entry(food).or_insert(0u32) += 1;
                    first_reached.entry(food).or_insert(sim.step);
                }
                AntEvent::Delivered { agent, nest } => {
                    assert_eq!(nest, before[&agent], "ant {agent}");
                    *delivered.entry(nest).or_insert(0u32) += 1;
                }
            }
        }
        before = homes(sim);
    });
    // The colony stretches along the route: way points are reached in order, every leg ends up
    // foraged (news carried back to its start), and the food is reached through all of them.
    let reached: Vec<u32> = route[1..].iter().map(|r| first_reached[r]).collect();
    assert!(
        reached.windows(2).all(|w| w[0] < w[1]),
        "first arrivals {reached:?}"
    );
    for leg in 0..4 {
        let (start, end) = (route[leg], route[leg + 1]);
        let (c, d) = (collected[&end], delivered.get(&start).copied().unwrap_or(0));
        assert!(c >= 10 && d >= 5, "leg {leg}: {c} arrivals, {d} returns");
    }
    let mut legs: HashMap<u16, u32> = HashMap::new();
    for n in before.values() {
        *legs.entry(*n).or_default() += 1;
    }
    assert!(
        route[..4]
            .iter()
            .all(|r| legs.get(r).copied().unwrap_or(0) >= 25),
        "ants per leg {legs:?}"
    );
}
