//! Bee swarm audit (issue 12): per seed, the lateral drift with no obstacle, the share of bees
//! through the Fig. 14 shaft field, body overlap (< 2r) per bee-step, and the grassland's
//! wall share (the issue-12 figures of `docs/models.md`). Parameter overrides from the
//! environment: BEE_K (stiffness), BEE_RHO0, BEE_H, BEE_KAPPA2, BEE_DT.
//!
//! ```sh
//! cargo run --release -p swarm-tests --example bee_audit -- <scene> <seed-from> <seed-to> [steps]
//! ```
//!
//! with `<scene>` one of `drift` (Fig. 14 without its shafts), `fig14`, `fig15`, `grass`, or
//! `curl` (samples the largest curl-noise force of two Table I columns).

use swarm_core::model::ParamValue;
use swarm_sim::bees::{BeeParamsOverride, BeeSim};
use swarm_sim::scenario::{self, ObjectKind, Scenario};

fn env(name: &str) -> Option<f32> {
    std::env::var(name).ok().map(|s| s.parse().unwrap())
}

fn tune(sc: &mut Scenario) {
    let knobs = [
        ("BEE_K", "stiffness"),
        ("BEE_RHO0", "rest_density"),
        ("BEE_H", "h"),
        ("BEE_KAPPA2", "kappa2"),
        ("BEE_DT", "dt"),
    ];
    for g in &mut sc.groups {
        let mut o: BeeParamsOverride = g.params_as().expect("bee parameters");
        for (var, param) in knobs {
            if let Some(v) = env(var) {
                assert!(o.overrides.set(param, ParamValue::Real(v)), "{param}");
            }
        }
        g.set_params(&o).expect("a table");
    }
}

/// Fraction of bees whose nearest neighbour is closer than `d`.
fn overlapping(pos: &[[f64; 3]], d: f64) -> usize {
    let cell = d.max(0.5);
    let mut grid: std::collections::HashMap<[i64; 3], Vec<usize>> = Default::default();
    let key = |p: &[f64; 3]| [0, 1, 2].map(|k| (p[k] / cell).floor() as i64);
    for (i, p) in pos.iter().enumerate() {
        grid.entry(key(p)).or_default().push(i);
    }
    let mut n = 0;
    for (i, p) in pos.iter().enumerate() {
        let k = key(p);
        let mut hit = false;
        'o: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(v) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for &j in v {
                            if j != i {
                                let q = pos[j];
                                let d2 = (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f64>();
                                if d2 < d * d {
                                    hit = true;
                                    break 'o;
                                }
                            }
                        }
                    }
                }
            }
        }
        n += usize::from(hit);
    }
    n
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene = args[1].as_str();
    if scene == "curl" {
        for (l, e) in [(2.7f32, 1.7f32), (2.2, 2.0)] {
            let (mut mx, mut sum, mut n) = (0.0f32, 0.0f32, 0);
            for i in 0..200_000u32 {
                let r = |k| swarm_core::rand::rand(1, i, 0, k) as f32 / 4.295e9 * 50.0;
                let f = swarm_core::bee::curl::curl_force(
                    swarm_core::Vec3::new(r(0), r(1), r(2)),
                    l,
                    e,
                );
                let m = f.length();
                mx = mx.max(m);
                sum += m;
                n += 1;
            }
            println!(
                "L {l} eps {e}: max |curl| {mx:.3}, mean {:.3}",
                sum / n as f32
            );
        }
        return;
    }
    let (a, b): (u32, u32) = (args[2].parse().unwrap(), args[3].parse().unwrap());
    let steps_arg: Option<usize> = args.get(4).map(|s| s.parse().unwrap());
    for seed in a..=b {
        let name = match scene {
            "drift" | "fig14" => "bees-fig14-shafts",
            "fig15" => "bees-fig15-nest",
            _ => "bees-fig11-grassland",
        };
        let mut sc = scenario::builtin(name).unwrap();
        if scene == "drift" {
            sc.objects
                .retain(|o| !matches!(o.kind, ObjectKind::Shaft { .. }));
            if let Some(n) = env("BEE_COUNT") {
                sc.groups[0].count = n as u32;
            }
            if let Some(z) = env("BEE_GOAL_Z") {
                for o in &mut sc.objects {
                    if let ObjectKind::Target { center, .. } = &mut o.kind {
                        *center = [8.0, 14.0, z];
                    }
                }
            }
        }
        tune(&mut sc);
        let p = swarm_sim::bees::bee_params(&sc.groups[0]).unwrap();
        let two_r = 2.0 * f64::from(p.radius);
        let goal = sc.objects.iter().find_map(|o| match o.kind {
            ObjectKind::Target { center, .. } => Some(center.map(f64::from)),
            _ => None,
        });
        let mut sim = BeeSim::from_scenario(&sc, seed).unwrap();
        let n = sim.agents();
        let perp = {
            let c = sim
                .positions_by_id()
                .iter()
                .fold([0.0; 3], |a, p| [a[0] + p[0], a[1] + p[1], a[2] + p[2]]);
            let g = goal.unwrap_or([0.0; 3]);
            let (dx, dz) = (g[0] - c[0] / n as f64, g[2] - c[2] / n as f64);
            let d = dx.hypot(dz).max(1e-9);
            [dz / d, -dx / d]
        };
        let steps = steps_arg.unwrap_or(sc.steps as usize);
        let (mut overl, mut samples) = (0usize, 0usize);
        let (mut lat_sum, mut lat_n) = (0.0f64, 0usize);
        let mut through = vec![false; n];
        let (min, max) = (sc.world.min(), sc.world.max());
        let mut near_wall_worst = 0.0f64;
        let mut near_wall_sum = 0.0f64;
        let mut wall_samples = 0usize;
        let t0 = std::time::Instant::now();
        let every = if n > 500 { 5 } else { 1 };
        for step in 0..steps {
            sim.step().unwrap();
            if step % every == 0 {
                let pos = sim.positions_by_id();
                overl += overlapping(&pos, two_r);
                samples += n;
            }
            let s = &sim.world.sensed;
            for (k, (p, v)) in s.pos.iter().zip(&s.vel).enumerate() {
                if let Some(g) = goal {
                    let (dx, dz) = (g[0] - p[0], g[2] - p[2]);
                    let d = dx.hypot(dz);
                    if d > 8.0 && scene == "drift" {
                        // horizontal perpendicular of the start direction: (c.z, -c.x)
                        lat_sum += v[0] * perp[0] + v[2] * perp[1];
                        lat_n += 1;
                    }
                    let _ = (dx, dz);
                }
                if (24.0..=36.0).contains(&p[0]) && (18.0..=42.0).contains(&p[2]) {
                    through[s.id[k] as usize] = true;
                }
            }
            if scene == "grass" && step >= steps / 3 {
                let near = s
                    .pos
                    .iter()
                    .filter(|p| {
                        (0..3).any(|c| {
                            (c != 1 && p[c] - f64::from(min[c]) < 1.0)
                                || p[c] > f64::from(max[c]) - 1.0
                        })
                    })
                    .count() as f64
                    / n as f64;
                near_wall_worst = near_wall_worst.max(near);
                near_wall_sum += near;
                wall_samples += 1;
            }
        }
        let thr = through.iter().filter(|&&t| t).count();
        println!(
            "{scene} seed {seed}: n {n} steps {steps} overlap {:.4} lateral {:.4} through {:.2} \
             near-wall mean {:.3} worst {:.3} contacts {:?} ({:.0} s)",
            overl as f64 / samples as f64,
            lat_sum / lat_n.max(1) as f64,
            thr as f64 / n as f64,
            near_wall_sum / wall_samples.max(1) as f64,
            near_wall_worst,
            sim.contacts,
            t0.elapsed().as_secs_f64()
        );
    }
}
