//! The seven time-varying metrics of ren2016 (Materials and Methods, "Evaluation"; spec §2.6):
//! speed v, acceleration a, angular velocity ω, angular acceleration α, Cartesian jerk μ,
//! shortest distance d and velocity difference η, sampled from positions by forward
//! differences at the frame interval Δt_s, for measured and simulated tracks alike.

use std::collections::BTreeMap;

use rayon::prelude::*;

use super::tracks::Tracks;

/// The metrics, in the paper's order Φ = {v, a, ω, α, μ, d, η}.
pub const METRICS: [&str; 7] = ["v", "a", "omega", "alpha", "mu", "d", "eta"];

/// Every sample of every metric, by [`METRICS`] index.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Samples(pub [Vec<f64>; 7]);

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: V3) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// ω between consecutive velocities: arccos of their cosine (clamped to [−1, 1]) over Δt;
/// `None` when either velocity is zero.
fn omega(a: V3, b: V3, dt: f64) -> Option<f64> {
    let (na, nb) = (norm(a), norm(b));
    if na == 0.0 || nb == 0.0 {
        return None;
    }
    let c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (na * nb);
    Some(c.clamp(-1.0, 1.0).acos() / dt)
}

/// The samples of `tracks` (spec §2.6):
///
/// * v_t = (p_{t+1} − p_t)/Δt, v = ‖v_t‖;
/// * a = ‖v_{t+1} − v_t‖/Δt;
/// * ω = arccos(v̂_t·v̂_{t+1})/Δt (skipped where a speed is zero);
/// * α = (ω_{t+1} − ω_t)/Δt (signed, as printed);
/// * μ = ‖(v_{t+2} − v_{t+1}) − (v_{t+1} − v_t)‖/Δt²;
/// * d = min_{k≠m} ‖p_k − p_m‖ per frame with at least two insects;
/// * η = |‖v_nei‖ − ‖v‖|/d_i per insect and frame, v_nei the velocity of its nearest
///   neighbour (among those with a velocity in that frame) and d_i the distance to it.
///
/// Differences need consecutive frames of one track; a gap starts a new run.
pub fn samples(tracks: &Tracks) -> Samples {
    let dt = tracks.dt;
    let mut out = Samples::default();
    // Per frame: (position, velocity) of every insect with a velocity there.
    let mut frames: BTreeMap<i64, Vec<(V3, Option<V3>)>> = BTreeMap::new();
    for (_, first, run) in tracks.runs() {
        let vel: Vec<V3> = run
            .windows(2)
            .map(|w| scale(sub(w[1], w[0]), 1.0 / dt))
            .collect();
        let om: Vec<Option<f64>> = vel.windows(2).map(|w| omega(w[0], w[1], dt)).collect();
        out.0[0].extend(vel.iter().map(|&v| norm(v)));
        out.0[1].extend(vel.windows(2).map(|w| norm(sub(w[1], w[0])) / dt));
        out.0[2].extend(om.iter().flatten());
        out.0[3].extend(om.windows(2).filter_map(|w| Some((w[1]? - w[0]?) / dt)));
        out.0[4].extend(vel.windows(3).map(|w| {
            let j = sub(sub(w[2], w[1]), sub(w[1], w[0]));
            norm(j) / (dt * dt)
        }));
        for (i, &p) in run.iter().enumerate() {
            frames
                .entry(first + i as i64)
                .or_default()
                .push((p, vel.get(i).copied()));
        }
    }
    let per_frame: Vec<(Option<f64>, Vec<f64>)> = frames
        .into_par_iter()
        .map(|(_, insects)| frame_samples(&insects))
        .collect();
    for (d, eta) in per_frame {
        out.0[5].extend(d);
        out.0[6].extend(eta);
    }
    out
}

/// d and the η samples of one frame (all pairs: tracking data has hundreds of insects).
fn frame_samples(insects: &[(V3, Option<V3>)]) -> (Option<f64>, Vec<f64>) {
    let mut shortest: Option<f64> = None;
    let mut eta = Vec::new();
    for (i, (p, v)) in insects.iter().enumerate() {
        let mut nearest: Option<(f64, V3)> = None;
        for (j, (q, w)) in insects.iter().enumerate() {
            if i == j {
                continue;
            }
            let r = norm(sub(*q, *p));
            if j > i {
                shortest = Some(shortest.map_or(r, |s| s.min(r)));
            }
            if let Some(w) = w
                && nearest.is_none_or(|(best, _)| r < best)
            {
                nearest = Some((r, *w));
            }
        }
        if let (Some(v), Some((r, w))) = (v, nearest)
            && r > 0.0
        {
            eta.push((norm(w) - norm(*v)).abs() / r);
        }
    }
    (shortest, eta)
}
