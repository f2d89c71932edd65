//! Piecewise-linear segmentation of a trajectory (li2015 §3.1: "piecewise linear regression
//! … with goodness of fit R² = 0.9"; the algorithm is ours, spec §2.5): top-down, a window of
//! samples is one segment when a straight line explains at least `r2_min` of its scatter, else
//! it is split at the sample farthest from its chord and both halves are examined again.

/// The paper's goodness of fit.
pub const R2_MIN: f64 = 0.9;

/// The shortest window that is split (a shorter one is a segment whatever its fit).
pub const MIN_SPLIT: usize = 6;

/// The shortest segment a split leaves (samples, endpoints shared with the neighbours).
pub const MIN_SEGMENT: usize = 3;

/// R² of the best 3D line through `points` (orthogonal regression, i.e. PCA): the share of
/// the scatter about the centroid along the principal axis, λ₁ / trace of the covariance.
/// 1 for fewer than two distinct points.
pub fn r_squared(points: &[[f64; 3]]) -> f64 {
    let n = points.len() as f64;
    if points.len() < 2 {
        return 1.0;
    }
    let mut mean = [0.0; 3];
    for p in points {
        for k in 0..3 {
            mean[k] += p[k] / n;
        }
    }
    let mut c = [[0.0; 3]; 3];
    for p in points {
        let d = [p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += d[i] * d[j];
            }
        }
    }
    let trace = c[0][0] + c[1][1] + c[2][2];
    if trace <= 0.0 {
        return 1.0;
    }
    // λ₁ by power iteration from the axis of the largest variance (the covariance is
    // symmetric positive semi-definite; 64 iterations settle far below the 1e-9 that matters).
    let start = (0..3)
        .max_by(|&a, &b| c[a][a].total_cmp(&c[b][b]))
        .unwrap_or(0);
    let mut v = [0.0; 3];
    v[start] = 1.0;
    let mut lambda = 0.0;
    for _ in 0..64 {
        let w = [0, 1, 2].map(|i| c[i][0] * v[0] + c[i][1] * v[1] + c[i][2] * v[2]);
        let norm = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        if norm == 0.0 {
            break;
        }
        lambda = norm;
        v = w.map(|x| x / norm);
    }
    (lambda / trace).clamp(0.0, 1.0)
}

/// The distance from `p` to the line through `a` and `b` (to `a` when they coincide).
fn distance_to_chord(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let cross = [
        ab[1] * ap[2] - ab[2] * ap[1],
        ab[2] * ap[0] - ab[0] * ap[2],
        ab[0] * ap[1] - ab[1] * ap[0],
    ];
    let len = (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]).sqrt();
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if len > 0.0 {
        norm(cross) / len
    } else {
        norm(ap)
    }
}

/// The sample of `points` in `range` farthest from the chord of samples `a` and `b`, with
/// that distance (the first one on a tie); `None` for an empty range.
fn farthest(
    points: &[[f64; 3]],
    a: usize,
    b: usize,
    range: std::ops::RangeInclusive<usize>,
) -> Option<(f64, usize)> {
    range
        .map(|k| (distance_to_chord(points[k], points[a], points[b]), k))
        .max_by(|x, y| x.0.total_cmp(&y.0).then(y.1.cmp(&x.1)))
}

/// Top-down splitting of `len` samples: `split(a, b)` names the sample to cut the window
/// `[a, b]` at, or `None` to keep it as one segment. The segments come as inclusive index
/// ranges, in order, each sharing its first sample with the previous one's last; fewer than
/// two samples have none.
fn top_down(len: usize, split: impl Fn(usize, usize) -> Option<usize>) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    if len < 2 {
        return out;
    }
    let mut todo = vec![(0, len - 1)];
    while let Some((a, b)) = todo.pop() {
        match split(a, b) {
            // Right half first: the stack hands the left half out next, so segments come
            // in order.
            Some(k) => {
                todo.push((k, b));
                todo.push((a, k));
            }
            None => out.push((a, b)),
        }
    }
    out
}

/// The segments of one track (consecutive samples), split top down: a window of
/// at least [`MIN_SPLIT`] samples whose [`r_squared`] is below `r2_min` is split at its
/// sample farthest from its chord (keeping [`MIN_SEGMENT`] samples on each side).
pub fn segment(points: &[[f64; 3]], r2_min: f64) -> Vec<(usize, usize)> {
    top_down(points.len(), |a, b| {
        if b - a + 1 < MIN_SPLIT || r_squared(&points[a..=b]) >= r2_min {
            return None;
        }
        let range = a + MIN_SEGMENT - 1..=b + 1 - MIN_SEGMENT;
        farthest(points, a, b, range).map(|(_, k)| k)
    })
}

/// The segments of one track by the largest distance to the chord (Douglas-Peucker,
/// ours): a window is split at its sample farthest from its chord while that distance
/// exceeds `tolerance`. Same output as [`segment`].
pub fn segment_by_tolerance(points: &[[f64; 3]], tolerance: f64) -> Vec<(usize, usize)> {
    top_down(points.len(), |a, b| {
        let (d, k) = farthest(points, a, b, a + 1..=b.checked_sub(1)?)?;
        (d > tolerance).then_some(k)
    })
}

/// The measurement noise of a track (sd per coordinate), estimated from its second
/// differences `p[k+1] − 2p[k] + p[k−1]`, whose variance is 6σ² for white noise on a straight
/// path at constant speed: the median absolute value over every coordinate, /0.6745 (the
/// median of |N(0, 1)|) and /√6. Turns are rare among the samples, so the median ignores
/// them. `None` for fewer than 3 samples.
pub fn noise_sd(points: &[[f64; 3]]) -> Option<f64> {
    let mut d: Vec<f64> = points
        .windows(3)
        .flat_map(|w| (0..3).map(move |k| (w[2][k] - 2.0 * w[1][k] + w[0][k]).abs()))
        .collect();
    if d.is_empty() {
        return None;
    }
    let mid = d.len() / 2;
    let (_, median, _) = d.select_nth_unstable_by(mid, f64::total_cmp);
    Some(*median / 0.6745 / 6f64.sqrt())
}

/// The default of the noise-following tolerance: c = 3.5 (docs/models.md: the value whose
/// segments come closest to the synthetic process's at the spec's condition).
pub const TOLERANCE_C: f64 = 3.5;

/// How a track is cut into segments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segmentation {
    /// The paper's rule ([`segment`]): a window is one segment when a line explains at least
    /// `r2` of its scatter.
    R2 {
        /// The goodness of fit (the paper's 0.9).
        r2: f64,
    },
    /// A tolerance that follows the noise ([`segment_by_tolerance`] at `c`·σ̂, σ̂ each
    /// track's [`noise_sd`]).
    Tolerance {
        /// The multiple of the noise.
        c: f64,
    },
}

impl Default for Segmentation {
    /// [`Segmentation::Tolerance`] at [`TOLERANCE_C`].
    fn default() -> Self {
        Segmentation::Tolerance { c: TOLERANCE_C }
    }
}

impl Segmentation {
    /// The segments of one run of consecutive samples (as [`segment`]). With a tolerance, a
    /// run of fewer than 3 samples (no noise estimate) is one segment, and the noise estimate
    /// is at least 10⁻⁹ of the median step (a noise-free track is cut at its bends, not at
    /// rounding errors).
    pub fn split(&self, points: &[[f64; 3]]) -> Vec<(usize, usize)> {
        match *self {
            Segmentation::R2 { r2 } => segment(points, r2),
            Segmentation::Tolerance { c } => {
                let Some(sigma) = noise_sd(points) else {
                    return segment_by_tolerance(points, f64::INFINITY);
                };
                let mut steps = step_lengths(points);
                let mid = steps.len() / 2;
                let step = *steps.select_nth_unstable_by(mid, f64::total_cmp).1;
                segment_by_tolerance(points, c * sigma.max(1e-9 * step))
            }
        }
    }

    /// The method's name in a model file and on the command line (`r2`, `tolerance`).
    pub fn method(&self) -> &'static str {
        match self {
            Segmentation::R2 { .. } => "r2",
            Segmentation::Tolerance { .. } => "tolerance",
        }
    }

    /// Its parameter (R² or c).
    pub fn parameter(&self) -> f64 {
        match *self {
            Segmentation::R2 { r2 } => r2,
            Segmentation::Tolerance { c } => c,
        }
    }
}

/// The distance between each pair of consecutive points.
pub(crate) fn step_lengths(points: &[[f64; 3]]) -> Vec<f64> {
    points
        .windows(2)
        .map(|w| {
            (0..3)
                .map(|k| (w[1][k] - w[0][k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect()
}
