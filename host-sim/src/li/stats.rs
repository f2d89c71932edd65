//! The statistics li2015 §3.1 takes from tracked trajectories: the lengths of the linear
//! segments and the turning angles between successive ones (the two distributions of
//! Algorithm 1), and the visiting frequency of each cell of the space (§4.3).

use super::segment::Segmentation;
use crate::eval::Tracks;

/// The segments of a set of tracks.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Segments {
    /// Each segment's chord length ‖p_end − p_start‖ (the tracks' unit).
    pub lengths: Vec<f64>,
    /// The angle between each two successive segments of one track (radians, in [−π, π]),
    /// signed by the turn about +y (spec §2.5: sign((d₁ × d₂)·ŷ)).
    pub turns: Vec<f64>,
}

/// The segments of every run of consecutive frames of `tracks` ([`Tracks::runs`]: a gap
/// starts a new run, and no turn is measured across it), by the paper's rule
/// ([`segment`](super::segment::segment)) with `r2_min`.
pub fn segments(tracks: &Tracks, r2_min: f64) -> Segments {
    segments_by(tracks, &Segmentation::R2 { r2: r2_min })
}

/// The segments of every run of consecutive frames of `tracks`, by `method`.
pub fn segments_by(tracks: &Tracks, method: &Segmentation) -> Segments {
    let mut out = Segments::default();
    for (_, _, run) in tracks.runs() {
        let mut previous: Option<[f64; 3]> = None;
        for (a, b) in method.split(&run) {
            let d = [0, 1, 2].map(|k| run[b][k] - run[a][k]);
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            out.lengths.push(len);
            if len == 0.0 {
                continue;
            }
            let d = d.map(|x| x / len);
            if let Some(p) = previous {
                let cos = (p[0] * d[0] + p[1] * d[1] + p[2] * d[2]).clamp(-1.0, 1.0);
                // (p × d)·ŷ
                let up = p[2] * d[0] - p[0] * d[2];
                out.turns
                    .push(if up < 0.0 { -cos.acos() } else { cos.acos() });
            }
            previous = Some(d);
        }
    }
    out
}

/// Count, mean, median and standard deviation (population) of a sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Moments {
    /// Number of values.
    pub n: usize,
    /// Mean.
    pub mean: f64,
    /// Median (the mean of the middle two for an even count).
    pub median: f64,
    /// Standard deviation.
    pub sd: f64,
}

/// The [`Moments`] of `x` (all zero when it is empty).
pub fn moments(x: &[f64]) -> Moments {
    if x.is_empty() {
        return Moments::default();
    }
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n as f64;
    let sd = (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
    let mut sorted = x.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    };
    Moments {
        n,
        mean,
        median,
        sd,
    }
}

/// Counts of `x` in `bins` equal bins over `[lo, hi]` (values outside go to the end bins).
pub fn histogram(x: &[f64], lo: f64, hi: f64, bins: usize) -> Vec<u32> {
    let mut counts = vec![0u32; bins];
    if bins == 0 || hi <= lo {
        return counts;
    }
    for &v in x {
        let k = ((v - lo) / (hi - lo) * bins as f64).floor();
        let k = if k.is_nan() {
            0.0
        } else {
            k.clamp(0.0, (bins - 1) as f64)
        };
        counts[k as usize] += 1;
    }
    counts
}

/// The visiting-frequency grid of §4.3: every sample of `tracks` counted in its cell of the
/// `dims` grid of cubic cells of side `cell` from `origin` (x fastest; samples outside are
/// not counted), scaled so the most visited cell is 255, and a visited cell at least 1
/// (a cell never visited stays 0: Metropolis-Hastings never proposes into it).
pub fn visit_density(tracks: &Tracks, origin: [f64; 3], cell: f64, dims: [usize; 3]) -> Vec<u8> {
    let mut counts = vec![0u64; dims[0] * dims[1] * dims[2]];
    for samples in tracks.by_id.values() {
        for (_, p) in samples {
            let mut idx = [0usize; 3];
            let inside = (0..3).all(|k| {
                let q = ((p[k] - origin[k]) / cell).floor();
                idx[k] = q.max(0.0) as usize;
                q >= 0.0 && idx[k] < dims[k]
            });
            if inside {
                counts[idx[0] + dims[0] * (idx[1] + dims[1] * idx[2])] += 1;
            }
        }
    }
    let max = counts.iter().copied().max().unwrap_or(0).max(1) as f64;
    counts
        .iter()
        .map(|&c| match c {
            0 => 0,
            c => ((c as f64 / max * 255.0).round() as u8).max(1),
        })
        .collect()
}
