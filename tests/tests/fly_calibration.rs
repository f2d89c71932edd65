//! R-T15 (spec §2.6, ours): the genetic algorithm recovers a model from its own trajectories.
//! The midges of Fig. 1 (Table 1's Midge column), three runs pooled (500 frames after a
//! burn-in of 200), are the reference; the GA ([`Ga::default`]: 20 individuals × 100
//! generations, chen §VI's budget) searches the seven parameters ren2016 estimates over the
//! spec's ranges from random starts (γ, scale and r_rep, which span decades, in their
//! logarithms), every individual one run with another seed (common random numbers), scored by
//! E of Eq. 6 with Step 1's weights ([`fit::score`], the reference's moments); it must reach
//! the true parameters' E within 0.02. Measured: seed 1, truth 0.383, the GA 0.449 (past
//! 0.363 at generation 70). With chen's 10 individuals the GA stalls far below (docs/models.md). The
//! search stops at the first generation that reaches the bound.

use rayon::prelude::*;
use swarm_sim::eval::{Scaling, samples};
use swarm_sim::fit::{self, Ga, Param, Sampling, Search};
use swarm_sim::fly::fly_params;
use swarm_sim::scenario::{self, Scenario};

/// `sc` with the seven estimated parameters `[γ, scale, gain, χ_rep, r_rep, χ_att, r_att*]`
/// (Table 1's terms: r_rep carries the alignment zone along, r_att* = r_att − r_ali), and the
/// speed limit that keeps the friction step stable (γ·max_speed·Δt ≤ ½); `None` when the
/// model refuses them.
fn with_genes(sc: &Scenario, genes: &[f64]) -> Option<Scenario> {
    let p = fly_params(&sc.groups[0]).expect("fly parameters");
    let r_ali = genes[4] + f64::from(p.r_ali - p.r_rep);
    let dt = f64::from(p.dt);
    fit::with_params(
        sc,
        &[
            ("gamma", genes[0]),
            (
                "max_speed",
                f64::from(p.max_speed).min(0.5 / (genes[0] * dt)),
            ),
            ("scale", genes[1]),
            ("gain", genes[2]),
            ("chi_rep", genes[3]),
            ("r_rep", genes[4]),
            ("r_ali", r_ali),
            ("chi_att", genes[5]),
            ("r_att", r_ali + genes[6]),
        ],
    )
    .ok()
}

#[test]
fn the_ga_recovers_the_midges() {
    let sc = scenario::builtin("fly-fig1-midges").expect("built-in");
    let p = fly_params(&sc.groups[0]).expect("fly parameters");
    let dt = f64::from(p.dt);
    let seed = swarm_tests::seed(sc.seed);
    let sampling = |seeds: Vec<u32>| Sampling {
        burn_in: 200,
        frames: 500,
        every: 1,
        seeds,
    };
    let reference =
        fit::simulate(&sc, dt, &sampling((0..3).map(|k| seed + k).collect())).expect("reference");
    let real = samples(&reference);
    let runs = sampling(vec![seed + 1000]);
    // Spec §2.6's ranges, in Table 1's terms (r_att* = r_att − r_ali).
    let params: Vec<Param> = [
        "gamma=0.1:20:log",
        "scale=0.1:5:log",
        "gain=0:6",
        "chi_rep=0:30",
        "r_rep=0.01:10:log",
        "chi_att=0:40",
        "r_att*=0:20",
    ]
    .iter()
    .map(|s| s.parse().expect("a range"))
    .collect();
    let score = |genes: &[f64]| {
        let values: Vec<f64> = params.iter().zip(genes).map(|(p, &g)| p.value(g)).collect();
        match with_genes(&sc, &values) {
            Some(s) => fit::score(
                &real,
                &fit::simulate(&s, dt, &runs).expect("runs"),
                Scaling::Reference,
            ),
            None => f64::NAN,
        }
    };
    let truth = [
        p.gamma,
        p.scale,
        p.gain,
        p.chi_rep,
        p.r_rep,
        p.chi_att,
        p.r_att - p.r_ali,
    ];
    let truth: Vec<f64> = params
        .iter()
        .zip(truth)
        .map(|(p, v)| p.gene(f64::from(v)))
        .collect();
    let e_truth = score(&truth);
    let ranges: Vec<(f64, f64)> = params.iter().map(Param::gene_range).collect();
    // The GA of `Ga::maximise`, a generation at a time, stopped once it reaches the truth's E
    // within 0.02 (what is asked; later generations only improve on it).
    let target = e_truth - 0.02;
    let mut search = Search::new(
        Ga {
            seed,
            ..Ga::default()
        },
        &ranges,
    );
    while !search.done() && search.history().last().is_none_or(|&b| b < target) {
        let scores: Vec<f64> = search.ask().par_iter().map(|g| score(g)).collect();
        search.tell(&scores);
        let g = search.history().len();
        if g.is_multiple_of(10) {
            eprintln!(
                "generation {g}: best E {:.4} (truth {e_truth:.4})",
                search.history()[g - 1]
            );
        }
    }
    let fit = search.outcome();
    let best: Vec<String> = params
        .iter()
        .zip(&fit.best)
        .map(|(p, &g)| format!("{} {:.3}", p.name, p.value(g)))
        .collect();
    eprintln!(
        "truth E {e_truth:.4}; the GA's best E {:.4}: {best:?}",
        fit.score
    );
    assert!(
        fit.score >= target,
        "the GA reached E {:.4}, the truth scores {e_truth:.4}: {best:?}",
        fit.score
    );
}
