//! Scoring trajectories against data (ren2016 "Evaluation", Eq. 6-9; spec §2.6), for any
//! model: the seven metrics of [`metrics`], their z-scored PDFs compared by L1 and weighted
//! by entropy ([`score`]), the swarm's polarisation, and li2015's measures of where it is
//! ([`spread`]: the distance to the centroid, the accumulated density). Measured tracks come as CSV
//! (`id,time,x,y,z`, [`Tracks::read_csv`]), a run's from its trajectories.
//!
//! ```
//! use swarm_sim::eval::{Scaling, Tracks, evaluate};
//!
//! // Two insects on straight lines, and a candidate that zigzags.
//! let line = |id: u64, y: f64| (0..50).map(move |k| (id, k, [k as f64 * 0.1, y, 0.0]));
//! let zig = |id: u64, y: f64| (0..50).map(move |k| (id, k, [k as f64 * 0.1, y + 0.05 * (k % 2) as f64, 0.0]));
//! let reference = Tracks::from_samples(0.1, line(0, 0.0).chain(line(1, 1.0)));
//! let straight = Tracks::from_samples(0.1, line(0, 0.5).chain(line(1, 2.0)));
//! let zigzag = Tracks::from_samples(0.1, zig(0, 0.0).chain(zig(1, 1.0)));
//! let e = evaluate(&reference, &[&straight, &zigzag], Scaling::Separate);
//! assert!(e.weighting.scores[0] > e.weighting.scores[1]);
//! ```

pub mod metrics;
pub mod score;
pub mod spread;
mod tracks;

#[cfg(test)]
mod tests;

pub use metrics::{METRICS, Samples, samples};
pub use score::{Scaling, Weighting, energy, entropy_weights};
pub use spread::{DENSITY_CELLS, centroid_distance, density_tv};
pub use tracks::{TRACKS_HEADER, Tracks};

/// Candidates scored against a reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation {
    /// E_φ (Eq. 7) of each candidate and metric ([`METRICS`] order); a metric with no sample
    /// on either side counts as the worst energy of that metric among the candidates (or 0).
    pub energies: Vec<[f64; 7]>,
    /// The entropy weighting and the scores E (Eq. 6, 8, 9) over the candidates.
    pub weighting: Weighting,
    /// The mean polarisation ‖mean of the unit velocities‖ over the frames, of the reference
    /// and of each candidate.
    pub polarisation: (f64, Vec<f64>),
    /// The mean distance to the centroid over the frames (li2015 Fig. 8), of the reference
    /// and of each candidate.
    pub centroid_distance: (f64, Vec<f64>),
    /// The total variation between each candidate's accumulated density and the reference's
    /// on a grid of [`DENSITY_CELLS`]³ cells over both (li2015 Figs. 4, 9); `None` for an
    /// empty set.
    pub density_tv: Vec<Option<f64>>,
    /// How each metric's sets were z-scored.
    pub scaling: Scaling,
}

/// Scores `candidates` against `reference` (spec §2.6 steps 1-4 for fixed parameters; the
/// parameter estimation of step 2 is the caller's), each metric's sets z-scored by `scaling`.
pub fn evaluate(reference: &Tracks, candidates: &[&Tracks], scaling: Scaling) -> Evaluation {
    let real = samples(reference);
    let raw: Vec<[Option<f64>; 7]> = candidates
        .iter()
        .map(|c| {
            let sim = samples(c);
            std::array::from_fn(|k| energy(&real.0[k], &sim.0[k], scaling))
        })
        .collect();
    let energies: Vec<[f64; 7]> = raw
        .iter()
        .map(|row| {
            std::array::from_fn(|k| {
                row[k].unwrap_or_else(|| raw.iter().filter_map(|r| r[k]).fold(0.0, f64::max))
            })
        })
        .collect();
    let matrix: Vec<Vec<f64>> = energies.iter().map(|r| r.to_vec()).collect();
    Evaluation {
        weighting: entropy_weights(&matrix),
        energies,
        scaling,
        polarisation: (
            polarisation(reference),
            candidates.iter().map(|c| polarisation(c)).collect(),
        ),
        centroid_distance: (
            centroid_distance(reference),
            candidates.iter().map(|c| centroid_distance(c)).collect(),
        ),
        density_tv: candidates
            .iter()
            .map(|c| density_tv(reference, c, DENSITY_CELLS))
            .collect(),
    }
}

/// The polarisation of one frame, Φ = ‖mean of the unit velocities‖ (0: no common heading,
/// 1: all aligned); insects at rest count as zero vectors.
pub fn frame_polarisation(vel: &[[f64; 3]]) -> f64 {
    if vel.is_empty() {
        return 0.0;
    }
    let mut sum = [0.0f64; 3];
    for v in vel {
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if len > 0.0 {
            for k in 0..3 {
                sum[k] += v[k] / len;
            }
        }
    }
    let n = vel.len() as f64;
    (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt() / n
}

/// The milling order of one frame about `center` (spec R-T23, Fig. 9): ‖Σ ρ_i × v_i‖ /
/// Σ ‖ρ_i‖‖v_i‖ with ρ_i = r_i − c, the swarm's rotation about whatever axis it turns round;
/// about a given `axis` â (the cave's), |Σ (ρ_i × v_i)·â| / Σ ‖ρ_i‖‖v_i‖ with ρ_i the offset
/// from the axis (perpendicular to it). 1 when every insect circles the same way, about 0 for
/// a swarm at random or moving along one heading; 0 without motion or with a zero axis.
pub fn frame_milling(
    pos: &[[f64; 3]],
    vel: &[[f64; 3]],
    center: [f64; 3],
    axis: Option<[f64; 3]>,
) -> f64 {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let norm = |a: [f64; 3]| dot(a, a).sqrt();
    let unit = match axis {
        Some(a) if norm(a) == 0.0 => return 0.0,
        Some(a) => Some(a.map(|c| c / norm(a))),
        None => None,
    };
    let (mut turn, mut scale) = ([0.0; 3], 0.0);
    for (p, v) in pos.iter().zip(vel) {
        let mut rho: [f64; 3] = std::array::from_fn(|k| p[k] - center[k]);
        if let Some(a) = unit {
            let along = dot(rho, a);
            rho = std::array::from_fn(|k| rho[k] - along * a[k]);
        }
        turn[0] += rho[1] * v[2] - rho[2] * v[1];
        turn[1] += rho[2] * v[0] - rho[0] * v[2];
        turn[2] += rho[0] * v[1] - rho[1] * v[0];
        scale += norm(rho) * norm(*v);
    }
    let turn = unit.map_or(norm(turn), |a| dot(turn, a).abs());
    if scale > 0.0 { turn / scale } else { 0.0 }
}

/// The mean over frames of ‖(1/N) Σ v̂_i‖, velocities by forward differences (frames where
/// no insect moves are skipped).
pub fn polarisation(tracks: &Tracks) -> f64 {
    let mut frames: std::collections::BTreeMap<i64, ([f64; 3], usize)> = Default::default();
    for (_, first, run) in tracks.runs() {
        for (i, w) in run.windows(2).enumerate() {
            let d = [w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]];
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if n > 0.0 {
                let e = frames.entry(first + i as i64).or_default();
                for (sum, c) in e.0.iter_mut().zip(d) {
                    *sum += c / n;
                }
                e.1 += 1;
            }
        }
    }
    let values: Vec<f64> = frames
        .values()
        .map(|(s, n)| (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt() / *n as f64)
        .collect();
    if values.is_empty() {
        0.0
    } else {
        values.iter().sum::<f64>() / values.len() as f64
    }
}

/// The evaluation as JSON: per candidate its path, energies by metric, score, polarisation,
/// distance to the centroid and density total variation; the weights and entropies by metric;
/// the reference's polarisation and distance to the centroid.
pub fn report(
    reference: &std::path::Path,
    candidates: &[std::path::PathBuf],
    e: &Evaluation,
) -> serde_json::Value {
    let by_metric = |v: &[f64]| -> serde_json::Map<String, serde_json::Value> {
        METRICS
            .iter()
            .zip(v)
            .map(|(m, x)| ((*m).to_string(), (*x).into()))
            .collect()
    };
    let rows: Vec<serde_json::Value> = (0..candidates.len())
        .map(|i| {
            serde_json::json!({
                "path": candidates[i].display().to_string(),
                "energies": by_metric(&e.energies[i]),
                "score": e.weighting.scores[i],
                "polarisation": e.polarisation.1[i],
                "centroid_distance": e.centroid_distance.1[i],
                "density_tv": e.density_tv[i],
            })
        })
        .collect();
    serde_json::json!({
        "reference": reference.display().to_string(),
        "reference_polarisation": e.polarisation.0,
        "reference_centroid_distance": e.centroid_distance.0,
        "density_cells": DENSITY_CELLS,
        "scaling": e.scaling,
        "weights": by_metric(&e.weighting.weights),
        "entropy": by_metric(&e.weighting.entropy),
        "candidates": rows,
    })
}

/// The evaluation as a text table: one row per candidate (energies, score, polarisation,
/// distance to the centroid, density total variation), then the weights.
pub fn table(candidates: &[std::path::PathBuf], e: &Evaluation) -> String {
    use std::fmt::Write as _;
    let mut out = format!("{:<32}", "candidate");
    for m in METRICS {
        let _ = write!(out, " {m:>7}");
    }
    out.push_str("   score  polar. centroid densTV\n");
    for (i, path) in candidates.iter().enumerate() {
        let name = path.display().to_string();
        let _ = write!(out, "{name:<32}");
        for x in &e.energies[i] {
            let _ = write!(out, " {x:>7.3}");
        }
        let tv = e.density_tv[i].map_or("-".into(), |v| format!("{v:.3}"));
        let _ = writeln!(
            out,
            " {:>7.3} {:>7.3} {:>8.3} {tv:>6}",
            e.weighting.scores[i], e.polarisation.1[i], e.centroid_distance.1[i]
        );
    }
    let _ = write!(out, "{:<32}", "weights");
    for w in &e.weighting.weights {
        let _ = write!(out, " {w:>7.3}");
    }
    let _ = write!(
        out,
        "\nreference polarisation {:.3}, distance to the centroid {:.3}",
        e.polarisation.0, e.centroid_distance.0
    );
    out
}
