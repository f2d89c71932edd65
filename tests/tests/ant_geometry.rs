//! Foraging on geometries the built-in scenarios do not have (xiang2018 §4-5 and the rules of
//! ours listed in docs/models.md), each over 10 seeds: ants get round a wall and out of a cup,
//! the nearer of two food sources wins, a small colony still forms a trail, laden ants find
//! their nest, and colonies sharing a food source each keep their own trail.

use std::collections::HashMap;

use swarm_core::Scalar;
use swarm_core::ant::Label;
use swarm_sim::ants::{AntEvent, AntSim, AnyAntGroup};
use swarm_sim::scenario::{self, Scenario};

const SEEDS: std::ops::RangeInclusive<u32> = 1..=10;

/// One ant as the tests see it.
#[derive(Clone, Copy)]
struct Ant {
    pos: [f32; 2],
    label: Label,
}

fn ants(sim: &AntSim) -> HashMap<u32, Ant> {
    let mut out = HashMap::new();
    for g in &sim.groups {
        match g {
            AnyAntGroup::F32(g) => out.extend(g.ids.iter().zip(&g.states).map(|(&i, s)| {
                let pos = [s.pos.x, s.pos.y];
                (
                    i,
                    Ant {
                        pos,
                        label: s.label,
                    },
                )
            })),
            AnyAntGroup::Fixed(g) => out.extend(g.ids.iter().zip(&g.states).map(|(&i, s)| {
                let pos = [s.pos.x.to_f32(), s.pos.y.to_f32()];
                (
                    i,
                    Ant {
                        pos,
                        label: s.label,
                    },
                )
            })),
        }
    }
    out
}

/// Runs `sc` with `seed` for its steps, calling `each(step, ants, events)` after every tick.
fn run(sc: &Scenario, seed: u32, mut each: impl FnMut(u32, &HashMap<u32, Ant>, &[AntEvent])) {
    let mut sim = AntSim::from_scenario(sc, seed).expect("builds");
    while sim.step < sc.steps {
        let step = sim.step;
        for e in sc.events.iter().filter(|e| e.step == step) {
            sim.apply(sc.object_id(e.action.object()).unwrap(), &e.action);
        }
        let events = sim.step().expect("tick");
        each(step + 1, &ants(&sim), &events);
    }
}

/// A 200 × 120 arena with one colony of `count` ants around nest (50, 60) and `objects` (TOML).
fn colony(count: u32, steps: u32, objects: &str) -> Scenario {
    let toml = format!(
        "name = \"geometry\"\nseed = 1\nsteps = {steps}\n\
         world = {{ dim = 2, min = [0, 0], max = [200, 120] }}\n\
         [[groups]]\nname = \"colony\"\nmodel = \"ant\"\ncount = {count}\nnest = \"nest\"\n\
         spawn = {{ at = \"nest\", radius = 8 }}\n\
         [[objects]]\nname = \"nest\"\nkind = \"nest\"\ncenter = [50, 60]\nradius = 5\n{objects}"
    );
    Scenario::from_str(&toml, "geometry test").unwrap_or_else(|e| panic!("{e}"))
}

const FOOD_AT_150: &str =
    "[[objects]]\nname = \"food\"\nkind = \"food\"\ncenter = [150, 60]\nradius = 5\n";

/// The laden trips (collect → drop) completed after tick `from`, as path lengths.
fn laden_trips(sc: &Scenario, seed: u32, from: u32) -> Vec<f32> {
    let mut trip: HashMap<u32, f32> = HashMap::new();
    let mut last: HashMap<u32, Ant> = HashMap::new();
    let mut trips = Vec::new();
    run(sc, seed, |step, now, events| {
        for (id, len) in trip.iter_mut() {
            let (a, b) = (last[id].pos, now[id].pos);
            *len += (b[0] - a[0]).hypot(b[1] - a[1]);
        }
        for e in events {
            match *e {
                AntEvent::Collected { agent, .. } => {
                    trip.insert(agent, 0.0);
                }
                AntEvent::Delivered { agent, .. } => {
                    if let Some(len) = trip.remove(&agent).filter(|_| step > from) {
                        trips.push(len);
                    }
                }
            }
        }
        last = now.clone();
    });
    trips
}

fn median(mut v: Vec<f32>) -> f32 {
    assert!(!v.is_empty(), "no samples");
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[v.len() / 2]
}

fn dist(a: [f32; 2], b: [f32; 2]) -> f32 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Distance from `p` to the segment `a`-`b`.
fn to_segment(p: [f32; 2], a: [f32; 2], b: [f32; 2]) -> f32 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let t = (((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / (ab[0] * ab[0] + ab[1] * ab[1]))
        .clamp(0.0, 1.0);
    dist(p, [a[0] + t * ab[0], a[1] + t * ab[1]])
}

/// The median laden trip round a 6 × 60 wall half way between nest and food (x 97-103, y
/// 30-90), over the shortest way round (edge to edge), for each of the 10 seeds.
fn wall_detours(count: u32, limit: f32) {
    let wall = "[[objects]]\nname = \"wall\"\nkind = \"polygon\"\n\
                points = [[97, 30], [103, 30], [103, 90], [97, 90]]\n";
    let sc = colony(count, 3000, &format!("{FOOD_AT_150}{wall}"));
    // The shortest way round, edge to edge: nest → a corner → the other corner → food.
    let (nest, food) = ([50.0, 60.0], [150.0, 60.0]);
    let shortest = dist(nest, [97.0, 30.0]) + 6.0 + dist([103.0, 30.0], food) - 10.0;
    for seed in SEEDS {
        let trips = laden_trips(&sc, seed, 1500);
        let n = trips.len();
        let ratio = median(trips) / shortest;
        println!(
            "{count} ants, seed {seed}: {n} laden trips, median {ratio:.2} × the shortest way round"
        );
        assert!(n as u32 >= count / 2, "seed {seed}: only {n} laden trips");
        assert!(
            ratio <= limit,
            "seed {seed}: median laden trip {ratio:.2} × the shortest"
        );
    }
}

#[test]
fn a_wall_across_the_nest_food_line_is_circumvented() {
    // 100 ants: measured 1.30-1.31 × (the wiggle of the random turn is 5 % of it).
    wall_detours(100, 1.5);
}

/// The same with 500 ants (issue 12's colony size): measured 1.36-1.37 ×. The crowd on the
/// trail lengthens every trip through the pushes of eq. 2-4; before R_d was limited to unit
/// length (docs/models.md) they outweighed O* and the median was 2.0-2.5 ×.
#[test]
fn a_wall_is_circumvented_by_500_ants_within_1_5_times_the_shortest_way() {
    wall_detours(500, 1.5);
}

#[test]
fn ants_leave_a_cup_opening_toward_the_nest() {
    // A U open toward the nest (west): inside x 90-110, y 49-71; walls 4 thick.
    let cup = "[[objects]]\nname = \"cup\"\nkind = \"polygon\"\n\
               points = [[90, 45], [114, 45], [114, 75], [90, 75], [90, 71], [110, 71], [110, 49], [90, 49]]\n";
    let sc = colony(500, 3000, &format!("{FOOD_AT_150}{cup}"));
    let in_cup = |p: [f32; 2]| (90.0..110.0).contains(&p[0]) && (49.0..71.0).contains(&p[1]);
    for seed in SEEDS {
        let mut stay: HashMap<u32, u32> = HashMap::new();
        let mut longest = 0;
        let (mut inside, mut samples) = (0u64, 0u64);
        let mut delivered = 0;
        run(&sc, seed, |step, now, events| {
            delivered += events
                .iter()
                .filter(|e| matches!(e, AntEvent::Delivered { .. }))
                .count();
            for (&id, a) in now {
                if in_cup(a.pos) {
                    let s = stay.entry(id).or_default();
                    *s += 1;
                    longest = longest.max(*s);
                } else {
                    stay.remove(&id);
                }
                if step > 1500 {
                    samples += 1;
                    inside += in_cup(a.pos) as u64;
                }
            }
        });
        let share = inside as f64 / samples as f64;
        println!(
            "seed {seed}: longest stay in the cup {longest} ticks, {:.2} % of ants in it, {delivered} deliveries",
            100.0 * share
        );
        // Every ant that goes in comes out (before: ants were trapped for good, staying to the
        // end of the run). The cup is on the way to the food, so outbound ants walk in and
        // round: 11-14 % of the ants are in it at any time with 500 ants (the crowd going
        // round), 1.8 % for a uniform spread; the longest stays measure 160-310 ticks.
        assert!(
            longest <= 400,
            "seed {seed}: an ant stayed {longest} ticks in the cup"
        );
        assert!(
            share < 0.2,
            "seed {seed}: {:.1} % of ants in the cup",
            100.0 * share
        );
        assert!(
            delivered >= 200,
            "seed {seed}: {delivered} deliveries round the cup"
        );
    }
}

#[test]
fn the_nearer_of_two_equal_food_sources_wins() {
    // Nest (50, 80); "near" 53 units south, "far" 133 units east; the same size.
    let toml = "name = \"two-foods\"\nseed = 1\nsteps = 3000\n\
         world = { dim = 2, min = [0, 0], max = [200, 160] }\n\
         [[groups]]\nname = \"colony\"\nmodel = \"ant\"\ncount = 500\nnest = \"nest\"\n\
         spawn = { at = \"nest\", radius = 8 }\n\
         [[objects]]\nname = \"nest\"\nkind = \"nest\"\ncenter = [50, 80]\nradius = 5\n\
         [[objects]]\nname = \"near\"\nkind = \"food\"\ncenter = [50, 27]\nradius = 5\n\
         [[objects]]\nname = \"far\"\nkind = \"food\"\ncenter = [183, 80]\nradius = 5\n";
    let sc = Scenario::from_str(toml, "two foods").unwrap();
    let (near, far) = (sc.object_id("near").unwrap(), sc.object_id("far").unwrap());
    let mut wins = 0;
    for seed in SEEDS {
        let (mut n, mut f) = (0, 0);
        run(&sc, seed, |step, _, events| {
            for e in events {
                if let AntEvent::Collected { food, .. } = *e
                    && step > 2500
                {
                    n += (food == near) as u32;
                    f += (food == far) as u32;
                }
            }
        });
        println!("seed {seed}: pickups in the last 500 ticks: near {n}, far {f}");
        wins += (n > f) as u32;
    }
    assert!(wins >= 8, "the nearer source won in {wins} of 10 seeds");
}

/// Laden ants on the nest-food corridor (within 10 of the segment between the centres),
/// relative to a uniform spread over the arena, over the second half of the run.
fn corridor_concentration(sc: &Scenario, seed: u32) -> (f64, u64) {
    let (nest, food) = ([50.0, 60.0], [150.0, 60.0]);
    let (mut on, mut laden) = (0u64, 0u64);
    run(sc, seed, |step, now, _| {
        if step <= sc.steps / 2 {
            return;
        }
        for a in now.values().filter(|a| a.label == Label::Food) {
            laden += 1;
            on += (to_segment(a.pos, nest, food) <= 10.0) as u64;
        }
    });
    // The corridor: a 100 × 20 rectangle and two half discs, of the 200 × 120 arena.
    let uniform = (100.0 * 20.0 + std::f64::consts::PI * 100.0) / (200.0 * 120.0);
    (on as f64 / laden.max(1) as f64 / uniform, laden)
}

#[test]
fn fifty_ants_still_form_a_trail() {
    let sc = colony(50, 4000, FOOD_AT_150);
    for seed in SEEDS {
        let (c, laden) = corridor_concentration(&sc, seed);
        println!(
            "seed {seed}: laden ants on the corridor at {c:.1} × a uniform spread ({laden} samples)"
        );
        assert!(
            laden > 1000,
            "seed {seed}: hardly any ant is laden ({laden} samples)"
        );
        assert!(
            c >= 2.0,
            "seed {seed}: laden ants at {c:.2} × a uniform spread"
        );
    }
}

#[test]
fn fig7a_laden_ants_are_on_the_trail_not_lost() {
    let sc = scenario::builtin("ants-fig7a-single-colony").unwrap();
    let (nest, food) = ([50.0, 60.0], [150.0, 60.0]);
    let center = |n: &str| {
        sc.object(n)
            .and_then(|o| o.kind.center())
            .map(|c| [c[0], c[1]])
    };
    assert_eq!(
        (center("nest"), center("food")),
        (Some(nest), Some(food)),
        "the test's geometry is the scenario's"
    );
    for seed in SEEDS {
        let mut last = HashMap::new();
        run(&sc, seed, |_, now, _| last = now.clone());
        let lost = last
            .values()
            .filter(|a| a.label == Label::Food && to_segment(a.pos, nest, food) > 10.0)
            .count();
        let share = lost as f64 / last.len() as f64;
        println!(
            "seed {seed}: {:.1} % of the ants are laden and off the trail",
            100.0 * share
        );
        assert!(
            share <= 0.15,
            "seed {seed}: {:.1} % laden and lost",
            100.0 * share
        );
    }
}

/// Deliveries per nest over the second half of a run.
fn deliveries(sc: &Scenario, seed: u32) -> HashMap<u16, u32> {
    let mut out = HashMap::new();
    run(sc, seed, |step, _, events| {
        for e in events {
            if let AntEvent::Delivered { nest, .. } = *e
                && step > sc.steps / 2
            {
                *out.entry(nest).or_default() += 1;
            }
        }
    });
    out
}

#[test]
fn colonies_sharing_a_food_source_each_keep_their_trail() {
    let nests = [("north", [50.0, 90.0]), ("south", [50.0, 30.0])];
    let scenario = |with: &[&str]| {
        let mut toml = String::from(
            "name = \"shared-food\"\nseed = 1\nsteps = 3000\n\
             world = { dim = 2, min = [0, 0], max = [200, 120] }\n",
        );
        for (name, c) in nests.iter().filter(|(n, _)| with.contains(n)) {
            toml += &format!(
                "[[groups]]\nname = \"{name}\"\nmodel = \"ant\"\ncount = 250\nnest = \"{name}\"\n\
                 spawn = {{ at = \"{name}\", radius = 8 }}\n\
                 [[objects]]\nname = \"{name}\"\nkind = \"nest\"\ncenter = [{}, {}]\nradius = 5\n",
                c[0], c[1]
            );
        }
        toml += FOOD_AT_150;
        Scenario::from_str(&toml, "shared food").unwrap()
    };
    let both = scenario(&["north", "south"]);
    for seed in SEEDS {
        let shared = deliveries(&both, seed);
        for (name, _) in nests {
            let alone_sc = scenario(&[name]);
            let alone = deliveries(&alone_sc, seed)[&alone_sc.object_id(name).unwrap()];
            let with = shared
                .get(&both.object_id(name).unwrap())
                .copied()
                .unwrap_or(0);
            let ratio = with as f64 / alone as f64;
            println!("seed {seed}: {name} delivers {with} sharing, {alone} alone ({ratio:.2})");
            assert!(
                ratio >= 0.3,
                "seed {seed}: {name} delivers {ratio:.2} of its rate alone"
            );
        }
    }
}
