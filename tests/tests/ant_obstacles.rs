//! Obstacles are a hard constraint for ants, on any geometry: random arenas of convex and
//! concave polygons, thin walls, cups, boxes and circles, with random nest and food placement,
//! in `f32` and fixed point; no ant ends any tick inside an obstacle (exact geometry), and an
//! obstacle that appears on top of ants moves them out.

use std::fmt::Write as _;

use swarm_core::Scalar;
use swarm_sim::ants::{AntObjectDef, AntObjectKind, AntSim, AnyAntGroup};
use swarm_sim::scenario::Scenario;

/// A small counter-based generator (splitmix64): the arenas are the same on every machine.
struct Gen(u64);

impl Gen {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn f(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

const W: f32 = 160.0;
const H: f32 = 100.0;

fn rotate(points: &[[f32; 2]], c: [f32; 2], angle: f32) -> Vec<[f32; 2]> {
    let (s, k) = angle.sin_cos();
    points
        .iter()
        .map(|p| [c[0] + p[0] * k - p[1] * s, c[1] + p[0] * s + p[1] * k])
        .collect()
}

/// One random obstacle around `c`, as a TOML object body (after `kind = `); `None` if it does
/// not fit in the world.
fn obstacle(g: &mut Gen, c: [f32; 2]) -> Option<String> {
    let a = g.f(0.0, std::f32::consts::TAU);
    let poly = |pts: Vec<[f32; 2]>| {
        let list: Vec<String> = pts
            .iter()
            .map(|p| format!("[{:.3}, {:.3}]", p[0], p[1]))
            .collect();
        let inside = pts
            .iter()
            .all(|p| (0.0..=W).contains(&p[0]) && (0.0..=H).contains(&p[1]));
        inside.then(|| format!("\"polygon\"\npoints = [{}]", list.join(", ")))
    };
    match g.below(6) {
        0 => Some(format!(
            "\"rock\"\ncenter = [{:.3}, {:.3}]\nradius = {:.3}",
            c[0],
            c[1],
            g.f(1.0, 8.0)
        )),
        // A box.
        1 => {
            let (w, h) = (g.f(2.0, 16.0), g.f(2.0, 16.0));
            poly(rotate(
                &[[-w, -h], [w, -h], [w, h], [-w, h]].map(|p| [p[0] / 2.0, p[1] / 2.0]),
                c,
                a,
            ))
        }
        // A thin wall (0.3 to 6 wide, up to 40 long).
        2 => {
            let (w, l) = (g.f(0.3, 6.0), g.f(8.0, 40.0));
            poly(rotate(
                &[[-w, -l], [w, -l], [w, l], [-w, l]].map(|p| [p[0] / 2.0, p[1] / 2.0]),
                c,
                a,
            ))
        }
        // A cup (U shape) with walls 1-4 thick.
        3 => {
            let (w, d, t) = (g.f(8.0, 24.0), g.f(6.0, 20.0), g.f(1.0, 4.0));
            let (x0, x1, y0, y1) = (-d / 2.0, d / 2.0, -w / 2.0, w / 2.0);
            poly(rotate(
                &[
                    [x0, y0],
                    [x1, y0],
                    [x1, y1],
                    [x0, y1],
                    [x0, y1 - t],
                    [x1 - t, y1 - t],
                    [x1 - t, y0 + t],
                    [x0, y0 + t],
                ],
                c,
                a,
            ))
        }
        // A convex polygon: points on a circle at increasing angles.
        4 => {
            let (n, r) = (3 + g.below(6) as usize, g.f(2.0, 10.0));
            let mut angles: Vec<f32> = (0..n).map(|_| g.f(0.0, std::f32::consts::TAU)).collect();
            angles.sort_by(|x, y| x.partial_cmp(y).unwrap());
            angles.dedup_by(|x, y| (*x - *y).abs() < 0.2);
            if angles.len() < 3 {
                angles = vec![0.0, 2.1, 4.2];
            }
            poly(
                angles
                    .iter()
                    .map(|t| [c[0] + r * t.cos(), c[1] + r * t.sin()])
                    .collect(),
            )
        }
        // A concave star: alternating radii.
        _ => {
            let n = 4 + g.below(5) as usize;
            let (ro, ri) = (g.f(5.0, 14.0), g.f(1.0, 4.0));
            poly(
                (0..2 * n)
                    .map(|k| {
                        let t = a + k as f32 * std::f32::consts::PI / n as f32;
                        let r = if k % 2 == 0 { ro } else { ri };
                        [c[0] + r * t.cos(), c[1] + r * t.sin()]
                    })
                    .collect(),
            )
        }
    }
}

/// A random arena: obstacles, then a nest and a food source where no obstacle is, 150 ants
/// of scalar type `scalar`; one more obstacle, inactive, is added at step 100 where ants are.
fn arena(seed: u64, scalar: &str) -> Scenario {
    let mut g = Gen(seed);
    let mut toml = format!(
        "name = \"random-arena-{seed}\"\nseed = {seed}\nsteps = 600\n\
         world = {{ dim = 2, min = [0, 0], max = [{W}, {H}] }}\n"
    );
    let nest = [g.f(15.0, 40.0), g.f(15.0, H - 15.0)];
    let food = [g.f(W - 40.0, W - 15.0), g.f(15.0, H - 15.0)];
    let mut objects = String::new();
    let count = 6 + g.below(6);
    let mut placed = 0;
    while placed < count {
        let c = [g.f(5.0, W - 5.0), g.f(5.0, H - 5.0)];
        // Keep the nest and the food clear (the scenario would be refused or warned about).
        if (c[0] - nest[0]).hypot(c[1] - nest[1]) < 25.0
            || (c[0] - food[0]).hypot(c[1] - food[1]) < 25.0
        {
            continue;
        }
        let Some(body) = obstacle(&mut g, c) else {
            continue;
        };
        let _ = write!(
            objects,
            "\n[[objects]]\nname = \"o{placed}\"\nkind = {body}\n"
        );
        placed += 1;
    }
    // The late rock lands on the trail, half way.
    let mid = [(nest[0] + food[0]) / 2.0, (nest[1] + food[1]) / 2.0];
    let _ = write!(
        objects,
        "\n[[objects]]\nname = \"late\"\nkind = \"rock\"\ncenter = [{:.3}, {:.3}]\nradius = 6\nactive = false\n",
        mid[0], mid[1]
    );
    let _ = write!(
        toml,
        "\n[[groups]]\nname = \"colony\"\nmodel = \"ant\"\ncount = 150\nnest = \"nest\"\n\
         scalar = \"{scalar}\"\nspawn = {{ at = \"nest\", radius = 4 }}\n\
         \n[[objects]]\nname = \"nest\"\nkind = \"nest\"\ncenter = [{:.3}, {:.3}]\nradius = 4\n\
         \n[[objects]]\nname = \"food\"\nkind = \"food\"\ncenter = [{:.3}, {:.3}]\nradius = 4\n\
         {objects}\n[[events]]\nstep = 100\nadd = \"late\"\n",
        nest[0], nest[1], food[0], food[1]
    );
    Scenario::from_str(&toml, "random arena").unwrap_or_else(|e| panic!("{e}\n{toml}"))
}

/// Every ant: its id, its position, and whether it is inside obstacle `o`, in its own scalar
/// (as it senses the obstacle).
fn insides(sim: &AntSim, o: &AntObjectDef) -> Vec<(u32, [f32; 2], bool)> {
    let mut out = Vec::new();
    for g in &sim.groups {
        match g {
            AnyAntGroup::F32(g) => out.extend(
                g.ids
                    .iter()
                    .zip(&g.states)
                    .map(|(&i, s)| (i, [s.pos.x, s.pos.y], o.closest(s.pos).1)),
            ),
            AnyAntGroup::Fixed(g) => out.extend(
                g.ids
                    .iter()
                    .zip(&g.states)
                    .map(|(&i, s)| (i, [s.pos.x.to_f32(), s.pos.y.to_f32()], o.closest(s.pos).1)),
            ),
        }
    }
    out
}

/// Runs arena `seed` and checks every ant after every tick against every active obstacle.
fn no_ant_inside_any_obstacle(seed: u64, scalar: &str) {
    let sc = arena(seed, scalar);
    let mut sim = AntSim::from_scenario(&sc, seed as u32).expect("builds");
    let mut trapped_by_event = 0;
    let mut delivered = 0;
    while sim.step < sc.steps {
        let step = sim.step;
        for e in sc.events.iter().filter(|e| e.step == step) {
            let before = sim.moved_out;
            sim.apply(sc.object_id(e.action.object()).unwrap(), &e.action);
            trapped_by_event += sim.moved_out - before;
        }
        for e in sim.step().expect("tick") {
            delivered += matches!(e, swarm_sim::ants::AntEvent::Delivered { .. }) as u32;
        }
        for o in sim.world.objects.iter().filter(|o| o.active) {
            if o.kind == AntObjectKind::Obstacle {
                for (id, p, inside) in insides(&sim, o) {
                    assert!(
                        !inside,
                        "arena {seed} ({scalar}): ant {id} ends tick {step} inside obstacle `{}` at {p:?}",
                        o.name
                    );
                }
            }
        }
    }
    println!(
        "arena {seed} ({scalar}): {trapped_by_event} ants moved out by the late rock, {delivered} deliveries"
    );
}

#[test]
fn no_ant_ends_a_tick_inside_an_obstacle_f32() {
    for seed in 1..=24 {
        no_ant_inside_any_obstacle(seed, "f32");
    }
}

#[test]
fn no_ant_ends_a_tick_inside_an_obstacle_fixed() {
    for seed in 1..=24 {
        no_ant_inside_any_obstacle(seed, "fixed");
    }
}
