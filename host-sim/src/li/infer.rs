//! Indirect inference of the segment process behind tracked trajectories (ours; li2015 §3.1
//! only segments the data and tabulates what it finds).
//!
//! Segmenting sampled, noisy tracks does not return the segments that were flown: at 100
//! frames/s half of the paper's segments span fewer than five samples, a third less than two,
//! and segments shorter than the noise merge with their neighbours (docs/models.md measures
//! the bias). Indirect inference (Gouriéroux, Monfort and Renault 1993) lets the bias cancel:
//!
//! 1. the data give a vector of **auxiliary statistics** ([`statistics`]): what a
//!    segmentation finds (segments per sample, the mean and quantiles of their lengths, the
//!    quantiles of their turning angles), how much the path bends between successive windows
//!    of 1 to 48 samples (the mean of 1 − cos and quantiles of the angle), the median step and
//!    the noise estimate;
//! 2. a **generating process** ([`Process`]) with a few parameters: a flight at constant speed
//!    along a polyline whose segment lengths follow a generalised gamma and whose turns a
//!    half-normal cone angle (the model's own turn: [`direction`] at a uniform azimuth),
//!    sampled every `dt` with Gaussian noise per coordinate;
//! 3. the parameters (the process's four, the speed and the noise) are those whose simulated
//!    tracks, cut into runs as long as the data's and segmented the same way, give the same
//!    statistics: weighted least squares (each statistic divided by its spread over
//!    data-sized replicates, at least 1 %), by Levenberg-Marquardt on the logarithms of a, c,
//!    the mean length, the turn sd, the speed and the noise (the mean rather than the scale:
//!    the criterion's valley then runs along the shape coordinates), from three starting
//!    shapes, the best of them polished once more.
//!
//! The simulations draw the same random numbers for every candidate (common random numbers:
//! one stream for the polyline, one for the noise), so the criterion is a deterministic
//! function of the parameters and the fit is reproducible bit for bit, on any thread count.
//!
//! What it cannot do: the data hardly tell apart shapes that differ only below the sampling
//! resolution (two vertices within one frame interval look like one bigger turn), so the
//! median length, which lies there, is the least certain estimate, and with noise large
//! against a step (0.4 mm at 1.5 mm a step) it comes out high (docs/models.md gives the
//! measured errors).

use rayon::prelude::*;
use swarm_core::Vec3;
use swarm_core::li::waypoint::direction;
use swarm_core::rand::rand;

use super::segment::{Segmentation, noise_sd, step_lengths};
use crate::error::{Result, SimError};

/// The windows (samples) between which the bending of the path is measured.
const BEND_LAGS: [usize; 11] = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48];
/// The windows whose bend angles' quantiles are statistics too.
const BEND_QUANTILE_LAGS: [usize; 4] = [1, 2, 3, 5];
/// The quantiles of those angles.
const BEND_QUANTILES: [f64; 4] = [0.5, 0.75, 0.9, 0.97];
/// The quantiles of the segment lengths.
const LENGTH_QUANTILES: [f64; 7] = [0.1, 0.25, 0.5, 0.75, 0.9, 0.97, 0.99];
/// The quantiles of the turning angles.
const TURN_QUANTILES: [f64; 3] = [0.25, 0.5, 0.75];
/// The smallest spread a statistic is weighted with (1 % on its log scale): no statistic is
/// trusted to better than a process that is only a model of the data.
const SPREAD_FLOOR: f64 = 0.01;
/// Data-sized replicates that measure each statistic's spread.
const REPLICATES: u32 = 8;
/// The starting shapes (a, c) of the generalised gamma, from a heavy short end to a Weibull-
/// like one; the fit keeps the best of the three.
const STARTS: [(f64, f64); 3] = [(0.3, 1.3), (0.6, 1.0), (1.2, 0.8)];
/// Forward-difference step of the Jacobian (on the log parameters).
const JACOBIAN_STEP: f64 = 0.05;
/// Levenberg-Marquardt iterations per start.
const ITERATIONS: usize = 30;

/// The generating process of the fit: segment lengths `scale·G^{1/c}`, G ~ Gamma(a, 1) (a
/// generalised gamma: a Weibull for a = 1, a gamma for c = 1; the spec's fixture is one), and
/// turning angles |N(0, turn_sd²)| (radians; the cone angle of [`direction`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Process {
    /// Shape a of the gamma variate.
    pub a: f64,
    /// Power c.
    pub c: f64,
    /// Scale (the tracks' unit).
    pub scale: f64,
    /// The sd of the normal whose magnitude is the turning angle (radians).
    pub turn_sd: f64,
}

impl Process {
    /// The length below which a share `u` of the segments lie.
    pub fn length_quantile(&self, u: f64) -> f64 {
        self.scale * inv_gamma_p(self.a, u).powf(1.0 / self.c)
    }

    /// The share of the segments shorter than `x`.
    pub fn length_cdf(&self, x: f64) -> f64 {
        if x <= 0.0 {
            return 0.0;
        }
        gamma_p(self.a, (x / self.scale).powf(self.c))
    }

    /// The mean length.
    pub fn length_mean(&self) -> f64 {
        self.scale * (ln_gamma(self.a + 1.0 / self.c) - ln_gamma(self.a)).exp()
    }

    /// The median length.
    pub fn length_median(&self) -> f64 {
        self.length_quantile(0.5)
    }

    /// The standard deviation of the length.
    pub fn length_sd(&self) -> f64 {
        let m2 = self.scale.powi(2) * (ln_gamma(self.a + 2.0 / self.c) - ln_gamma(self.a)).exp();
        (m2 - self.length_mean().powi(2)).max(0.0).sqrt()
    }

    /// The share of the turning angles below `x` (radians).
    pub fn turn_cdf(&self, x: f64) -> f64 {
        if x <= 0.0 {
            return 0.0;
        }
        // |N(0, σ²)| < x  ⇔  N(0,1)²/2 < x²/(2σ²): P(1/2, ·).
        gamma_p(0.5, x * x / (2.0 * self.turn_sd * self.turn_sd))
    }

    /// The median turning angle.
    pub fn turn_median(&self) -> f64 {
        self.turn_sd * (2.0 * inv_gamma_p(0.5, 0.5)).sqrt()
    }

    /// The mean turning angle.
    pub fn turn_mean(&self) -> f64 {
        self.turn_sd * (2.0 / std::f64::consts::PI).sqrt()
    }

    /// The standard deviation of the turning angle.
    pub fn turn_sd_moment(&self) -> f64 {
        self.turn_sd * (1.0 - 2.0 / std::f64::consts::PI).sqrt()
    }

    /// The process of the fit's coordinates: ln a, ln c, ln (mean length), ln turn_sd (the
    /// mean rather than the scale, so that a change of shape keeps the number of vertices:
    /// the criterion's valley runs along the coordinates).
    fn from_x(x: &[f64]) -> Process {
        let (a, c) = (x[0].exp(), x[1].exp());
        Process {
            a,
            c,
            scale: (x[2] + ln_gamma(a) - ln_gamma(a + 1.0 / c)).exp(),
            turn_sd: x[3].exp(),
        }
    }
}

/// What the fit found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fitted {
    /// The generating process.
    pub process: Process,
    /// The flight speed (units per second).
    pub speed: f64,
    /// The measurement noise (sd per coordinate, units).
    pub noise: f64,
    /// The weighted squared distance of its statistics from the data's.
    pub cost: f64,
    /// Simulations run.
    pub evals: usize,
}

/// A uniform number in (0, 1) of stream `stream`, run `run`, draw `n`.
fn uniform(seed: u32, run: usize, n: u32, stream: u32) -> f64 {
    (f64::from(rand(seed, run as u32, n, stream)) + 0.5) / 4_294_967_296.0
}

/// A standard normal from two uniforms (Box-Muller).
fn normal(u: f64, v: f64) -> f64 {
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// The random numbers of a set of simulated runs, the same for every candidate process.
struct Draws {
    /// Samples per run.
    lens: Vec<usize>,
    /// Per run: a standard normal per sample and coordinate.
    noise: Vec<Vec<[f64; 3]>>,
    /// Per run: the first direction's height and azimuth.
    start: Vec<(f64, f64)>,
    /// Per run: per vertex, the length's uniform, |N(0, 1)| of the turn, the azimuth.
    vertices: Vec<Vec<(f64, f64, f64)>>,
    seed: u32,
}

impl Draws {
    const NOISE: u32 = 0x4E5A;
    const START: u32 = 0x5354;
    const VERTEX: u32 = 0x5345;

    fn new(lens: Vec<usize>, seed: u32) -> Draws {
        let noise = lens
            .par_iter()
            .enumerate()
            .map(|(r, &n)| {
                (0..n as u32)
                    .map(|k| {
                        [0, 1, 2].map(|i| {
                            let at = 6 * k + 2 * i;
                            normal(
                                uniform(seed, r, at + 1, Self::NOISE),
                                uniform(seed, r, at + 2, Self::NOISE),
                            )
                        })
                    })
                    .collect()
            })
            .collect();
        let start = (0..lens.len())
            .map(|r| {
                (
                    uniform(seed, r, 1, Self::START) * 2.0 - 1.0,
                    (uniform(seed, r, 2, Self::START) * 2.0 - 1.0) * std::f64::consts::PI,
                )
            })
            .collect();
        Draws {
            vertices: vec![Vec::new(); lens.len()],
            lens,
            noise,
            start,
            seed,
        }
    }

    /// Makes sure every run has its first `n` vertices drawn.
    fn reserve(&mut self, run: usize, n: usize) {
        let v = &mut self.vertices[run];
        while v.len() < n {
            let k = 4 * v.len() as u32;
            let u = |j| uniform(self.seed, run, k + j, Self::VERTEX);
            v.push((
                u(1),
                normal(u(2), u(3)).abs(),
                (u(4) * 2.0 - 1.0) * std::f64::consts::PI,
            ));
        }
    }

    /// The runs of `p` at `speed` and `noise`, sampled every `dt`.
    fn tracks(&mut self, p: &Process, speed: f64, noise: f64, dt: f64) -> Vec<Vec<[f64; 3]>> {
        let mut out: Vec<Option<Vec<[f64; 3]>>> = vec![None; self.lens.len()];
        let mut first = true;
        loop {
            // A run whose polyline ends before its last sample gets twice the vertices and is
            // flown again (sequentially drawn, so the draws never depend on the thread count).
            let todo: Vec<usize> = (0..out.len()).filter(|&r| out[r].is_none()).collect();
            if todo.is_empty() {
                break;
            }
            for &r in &todo {
                let n = if first {
                    self.vertices[r].len().max(16)
                } else {
                    2 * self.vertices[r].len()
                };
                self.reserve(r, n);
            }
            first = false;
            let this = &*self;
            let flown: Vec<(usize, Option<Vec<[f64; 3]>>)> = todo
                .into_par_iter()
                .map(|r| (r, this.run(r, p, speed, noise, dt)))
                .collect();
            for (r, run) in flown {
                out[r] = run;
            }
        }
        out.into_iter().flatten().collect()
    }

    /// Run `r`, or `None` when its vertices end before its last sample.
    fn run(&self, r: usize, p: &Process, speed: f64, noise: f64, dt: f64) -> Option<Vec<[f64; 3]>> {
        let step = speed * dt;
        let (z, phi) = self.start[r];
        let mut heading = direction(Vec3::<f32>::zero(), 0.0, phi as f32, z as f32);
        let mut pos = [0.0; 3];
        let mut vertices = self.vertices[r].iter();
        let mut left = p.length_quantile(vertices.next()?.0);
        let mut out = Vec::with_capacity(self.lens[r]);
        for e in &self.noise[r] {
            out.push([0, 1, 2].map(|i| pos[i] + noise * e[i]));
            let mut go = step;
            while go > left {
                pos = advance(pos, heading, left);
                go -= left;
                let &(u, z, phi) = vertices.next()?;
                heading = direction(heading, (p.turn_sd * z) as f32, phi as f32, 0.0);
                left = p.length_quantile(u);
            }
            pos = advance(pos, heading, go);
            left -= go;
        }
        Some(out)
    }
}

fn advance(pos: [f64; 3], heading: Vec3<f32>, by: f64) -> [f64; 3] {
    let h = [heading.x, heading.y, heading.z];
    [0, 1, 2].map(|i| pos[i] + by * f64::from(h[i]))
}

/// The linearly interpolated quantile `q` of `x` (reordered in place); 0 for none.
fn quantile(x: &mut [f64], q: f64) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let pos = q * (x.len() - 1) as f64;
    let i = pos.floor() as usize;
    let frac = pos - i as f64;
    let (_, below, above) = x.select_nth_unstable_by(i, f64::total_cmp);
    let lo = *below;
    match above.iter().copied().min_by(f64::total_cmp) {
        Some(hi) if frac > 0.0 => lo + frac * (hi - lo),
        _ => lo,
    }
}

/// What one run contributes to the statistics.
#[derive(Default)]
struct RunStats {
    lengths: Vec<f64>,
    turns: Vec<f64>,
    bend_sum: [f64; BEND_LAGS.len()],
    bend_n: [usize; BEND_LAGS.len()],
    bend_angles: [Vec<f64>; BEND_QUANTILE_LAGS.len()],
    steps: Vec<f64>,
    noise: Option<f64>,
}

fn unit(d: [f64; 3]) -> Option<[f64; 3]> {
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    (n > 0.0).then(|| d.map(|v| v / n))
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0)
}

fn run_stats(run: &[[f64; 3]], seg: &Segmentation) -> RunStats {
    let mut s = RunStats {
        noise: noise_sd(run),
        ..RunStats::default()
    };
    let mut previous = None;
    for (a, b) in seg.split(run) {
        let d = [0, 1, 2].map(|k| run[b][k] - run[a][k]);
        s.lengths
            .push((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
        let Some(d) = unit(d) else { continue };
        if let Some(p) = previous {
            s.turns.push(dot(p, d).acos());
        }
        previous = Some(d);
    }
    let window = |k: usize, w: usize| unit([0, 1, 2].map(|i| run[k + w][i] - run[k][i]));
    for (j, &w) in BEND_LAGS.iter().enumerate() {
        for k in 0..run.len().saturating_sub(2 * w) {
            if let (Some(a), Some(b)) = (window(k, w), window(k + w, w)) {
                s.bend_sum[j] += 1.0 - dot(a, b);
                s.bend_n[j] += 1;
            }
        }
    }
    for (j, &w) in BEND_QUANTILE_LAGS.iter().enumerate() {
        for k in 0..run.len().saturating_sub(2 * w) {
            if let (Some(a), Some(b)) = (window(k, w), window(k + w, w)) {
                s.bend_angles[j].push(dot(a, b).acos());
            }
        }
    }
    s.steps = step_lengths(run);
    s
}

/// The auxiliary statistics of `runs` (logarithms, so that each is relative): segments per
/// sample; the mean and the 10, 25, 50, 75, 90, 97 and 99 % quantiles of the segment lengths;
/// the 25, 50 and 75 % quantiles of the turning angles; the mean of 1 − cos of the angle
/// between successive windows of w samples for w = 1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48; the
/// 50, 75, 90 and 97 % quantiles of that angle for w = 1, 2, 3, 5; the median step; the
/// median over runs of the noise estimate. Also the number of segments and turns found.
pub fn statistics(runs: &[Vec<[f64; 3]>], seg: &Segmentation) -> (Vec<f64>, usize, usize) {
    let parts: Vec<RunStats> = runs.par_iter().map(|r| run_stats(r, seg)).collect();
    let samples: usize = runs.iter().map(Vec::len).sum();
    let mut lengths: Vec<f64> = parts
        .iter()
        .flat_map(|p| p.lengths.iter().copied())
        .collect();
    let mut turns: Vec<f64> = parts.iter().flat_map(|p| p.turns.iter().copied()).collect();
    let (segments, turn_count) = (lengths.len(), turns.len());
    let ln = |v: f64| v.max(1e-300).ln();
    let mut out = vec![
        ln(segments as f64 / samples.max(1) as f64),
        ln(lengths.iter().sum::<f64>() / segments.max(1) as f64),
    ];
    out.extend(
        LENGTH_QUANTILES
            .iter()
            .map(|&q| ln(quantile(&mut lengths, q))),
    );
    out.extend(TURN_QUANTILES.iter().map(|&q| ln(quantile(&mut turns, q))));
    for j in 0..BEND_LAGS.len() {
        let sum: f64 = parts.iter().map(|p| p.bend_sum[j]).sum();
        let n: usize = parts.iter().map(|p| p.bend_n[j]).sum();
        out.push(ln(sum / n.max(1) as f64));
    }
    for j in 0..BEND_QUANTILE_LAGS.len() {
        let mut angles: Vec<f64> = parts
            .iter()
            .flat_map(|p| p.bend_angles[j].iter().copied())
            .collect();
        out.extend(BEND_QUANTILES.iter().map(|&q| ln(quantile(&mut angles, q))));
    }
    let mut steps: Vec<f64> = parts.iter().flat_map(|p| p.steps.iter().copied()).collect();
    out.push(ln(quantile(&mut steps, 0.5)));
    let mut noise: Vec<f64> = parts.iter().filter_map(|p| p.noise).collect();
    out.push(ln(quantile(&mut noise, 0.5)));
    (out, segments, turn_count)
}

/// How the fit runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InferOptions {
    /// The segmentation the statistics use (on the data and on the simulations alike).
    pub segmentation: Segmentation,
    /// At least this many samples are simulated per candidate (the data's runs, repeated).
    pub sim_samples: usize,
    /// The seed of the simulations.
    pub seed: u32,
}

impl Default for InferOptions {
    /// The noise-following tolerance at c = 3.5, 100,000 simulated samples, seed 1.
    fn default() -> Self {
        InferOptions {
            segmentation: Segmentation::default(),
            sim_samples: 100_000,
            seed: 1,
        }
    }
}

/// The smallest data the fit accepts: segments and turns the segmentation finds.
pub const MIN_SEGMENTS: usize = 10;

/// Fits the generating process to `runs` (runs of consecutive samples every `dt` seconds).
///
/// # Errors
///
/// [`SimError::LiTooFewSegments`] when the segmentation finds fewer than [`MIN_SEGMENTS`]
/// segments or turns in the data.
pub fn infer(runs: &[Vec<[f64; 3]>], dt: f64, opts: &InferOptions) -> Result<Fitted> {
    let seg = &opts.segmentation;
    let (target, segments, turns) = statistics(runs, seg);
    if segments < MIN_SEGMENTS || turns < MIN_SEGMENTS {
        return Err(SimError::LiTooFewSegments {
            segments,
            turns,
            needed: MIN_SEGMENTS,
        });
    }
    let m = target.len();
    let lens: Vec<usize> = runs.iter().map(Vec::len).collect();
    let samples: usize = lens.iter().sum();
    let copies = opts.sim_samples.div_ceil(samples.max(1)).max(1);
    let sim_lens: Vec<usize> = (0..copies).flat_map(|_| lens.iter().copied()).collect();
    let mut draws = Draws::new(sim_lens, opts.seed);

    // The start: the direct estimates (the segments' mean length and median turn, the median
    // step, the noise estimate).
    let n_step = m - 2;
    let mean_length = target[1].exp();
    let turn_sd = target[2 + LENGTH_QUANTILES.len() + 1].exp() / 0.674_489_750_196_081_7;
    let (speed, noise) = (target[n_step].exp() / dt, target[n_step + 1].exp());
    let at = |a: f64, c: f64| {
        vec![
            a.ln(),
            c.ln(),
            mean_length.ln(),
            turn_sd.clamp(0.01, 3.0).ln(),
            speed.ln(),
            noise.ln(),
        ]
    };

    // Each statistic's spread over data-sized replicates of the middle start.
    let x0 = at(STARTS[1].0, STARTS[1].1);
    let replicates: Vec<Vec<f64>> = (0..REPLICATES)
        .map(|i| {
            let mut d = Draws::new(lens.clone(), opts.seed.wrapping_add(1000 + i));
            let p = Process::from_x(&x0);
            statistics(&d.tracks(&p, x0[4].exp(), x0[5].exp(), dt), seg).0
        })
        .collect();
    let spread: Vec<f64> = (0..m)
        .map(|i| {
            let r = f64::from(REPLICATES);
            let mean = replicates.iter().map(|x| x[i]).sum::<f64>() / r;
            let var = replicates
                .iter()
                .map(|x| (x[i] - mean).powi(2))
                .sum::<f64>()
                / (r - 1.0);
            var.sqrt().max(SPREAD_FLOOR)
        })
        .collect();

    let mut evals = 0;
    let mut residuals = |x: &[f64]| -> Vec<f64> {
        evals += 1;
        let p = Process::from_x(x);
        // Segments far below a step would need millions of vertices per run: not a
        // candidate (a cost far above any fit's).
        let mean = p.length_mean();
        if mean.is_nan() || mean < 0.01 * x[4].exp() * dt {
            return vec![1e3; m];
        }
        let (s, _, _) = statistics(&draws.tracks(&p, x[4].exp(), x[5].exp(), dt), seg);
        s.iter()
            .zip(&target)
            .zip(&spread)
            .map(|((s, t), w)| (s - t) / w)
            .collect()
    };
    let limits = [
        (0.05f64.ln(), 20f64.ln()),
        (0.2f64.ln(), 10f64.ln()),
        ((mean_length * 0.1).ln(), (mean_length * 10.0).ln()),
        (1e-3f64.ln(), 3f64.ln()),
        (f64::NEG_INFINITY, f64::INFINITY),
        (f64::NEG_INFINITY, f64::INFINITY),
    ];
    let mut best: Option<(Vec<f64>, f64)> = None;
    for (a, c) in STARTS {
        let (x, cost) = levenberg_marquardt(&mut residuals, at(a, c), &limits);
        if best.as_ref().is_none_or(|b| cost < b.1) {
            best = Some((x, cost));
        }
    }
    // The best once more from where it stopped (a fresh damping: the valley is long).
    let (x, _) = best.expect("three starts");
    let (x, cost) = levenberg_marquardt(&mut residuals, x, &limits);
    Ok(Fitted {
        process: Process::from_x(&x),
        speed: x[4].exp(),
        noise: x[5].exp(),
        cost,
        evals,
    })
}

/// Minimises Σ r(x)² from `x` by Levenberg-Marquardt with a forward-difference Jacobian,
/// each coordinate kept within `limits`; the point and its cost.
fn levenberg_marquardt(
    r: &mut dyn FnMut(&[f64]) -> Vec<f64>,
    mut x: Vec<f64>,
    limits: &[(f64, f64)],
) -> (Vec<f64>, f64) {
    let n = x.len();
    let clamp = |x: &mut Vec<f64>| {
        for (v, (lo, hi)) in x.iter_mut().zip(limits) {
            *v = v.clamp(*lo, *hi);
        }
    };
    clamp(&mut x);
    let mut rv = r(&x);
    let mut cost: f64 = rv.iter().map(|v| v * v).sum();
    let mut lambda = 1e-2;
    for _ in 0..ITERATIONS {
        let jac: Vec<Vec<f64>> = (0..n)
            .map(|j| {
                let mut xp = x.clone();
                xp[j] += JACOBIAN_STEP;
                r(&xp)
                    .iter()
                    .zip(&rv)
                    .map(|(a, b)| (a - b) / JACOBIAN_STEP)
                    .collect()
            })
            .collect();
        let jtj: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|k| dot_n(&jac[i], &jac[k])).collect())
            .collect();
        let g: Vec<f64> = (0..n).map(|i| -dot_n(&jac[i], &rv)).collect();
        let mut improved = None;
        for _ in 0..8 {
            let mut a = jtj.clone();
            for (i, row) in a.iter_mut().enumerate() {
                row[i] += lambda * (jtj[i][i] + 1e-6);
            }
            let Some(dx) = solve(a, g.clone()) else {
                lambda *= 10.0;
                continue;
            };
            let mut xn: Vec<f64> = x
                .iter()
                .zip(&dx)
                .map(|(v, d)| v + d.clamp(-0.5, 0.5))
                .collect();
            clamp(&mut xn);
            let rn = r(&xn);
            let cn: f64 = rn.iter().map(|v| v * v).sum();
            if cn < cost {
                let small = cost - cn < 1e-4 * cost || dx.iter().all(|d| d.abs() < 1e-3);
                improved = Some(small);
                x = xn;
                rv = rn;
                cost = cn;
                lambda = (lambda / 3.0).max(1e-6);
                break;
            }
            lambda *= 4.0;
        }
        match improved {
            Some(false) => {}
            _ => break,
        }
    }
    (x, cost)
}

fn dot_n(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The solution of the small dense system `a·x = b` (Gaussian elimination with partial
/// pivoting); `None` when `a` is singular.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for i in 0..n {
        let p = (i..n).max_by(|&x, &y| a[x][i].abs().total_cmp(&a[y][i].abs()))?;
        if a[p][i].abs() < 1e-300 {
            return None;
        }
        a.swap(i, p);
        b.swap(i, p);
        let pivot = a[i].clone();
        for j in i + 1..n {
            let f = a[j][i] / pivot[i];
            for (x, y) in a[j][i..n].iter_mut().zip(&pivot[i..n]) {
                *x -= f * y;
            }
            b[j] -= f * b[i];
        }
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        x[i] = (b[i] - (i + 1..n).map(|k| a[i][k] * x[k]).sum::<f64>()) / a[i][i];
    }
    Some(x)
}

/// ln Γ(x) for x > 0 (Lanczos, g = 7, 9 terms: relative error below 1e-13).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let t = x + 7.5;
    let sum = C
        .iter()
        .enumerate()
        .skip(1)
        .fold(C[0], |s, (i, &c)| s + c / (x + i as f64));
    0.5 * std::f64::consts::TAU.ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// The regularised lower incomplete gamma function P(a, x) (series below a + 1, continued
/// fraction above; Numerical Recipes §6.2).
pub fn gamma_p(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let front = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut ap, mut del) = (a, 1.0 / a);
        let mut sum = del;
        for _ in 0..1000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        (sum * front).min(1.0)
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (1.0 - front * h).max(0.0)
    }
}

/// The x with P(a, x) = p, p in (0, 1) (Halley's method from Numerical Recipes' start,
/// §6.2.1).
pub fn inv_gamma_p(a: f64, p: f64) -> f64 {
    if p <= 0.0 {
        return 0.0;
    }
    let a1 = a - 1.0;
    let gln = ln_gamma(a);
    let (lna1, afac) = if a > 1.0 {
        (a1.ln(), (a1 * (a1.ln() - 1.0) - gln).exp())
    } else {
        (0.0, 0.0)
    };
    let mut x = if a > 1.0 {
        let pp = if p < 0.5 { p } else { 1.0 - p };
        let t = (-2.0 * pp.ln()).sqrt();
        let mut z = (2.30753 + t * 0.27061) / (1.0 + t * (0.99229 + t * 0.04481)) - t;
        if p < 0.5 {
            z = -z;
        }
        (a * (1.0 - 1.0 / (9.0 * a) - z / (3.0 * a.sqrt())).powi(3)).max(1e-3)
    } else {
        let t = 1.0 - a * (0.253 + a * 0.12);
        if p < t {
            (p / t).powf(1.0 / a)
        } else {
            1.0 - (1.0 - (p - t) / (1.0 - t)).ln()
        }
    };
    for _ in 0..100 {
        if x <= 0.0 {
            return 0.0;
        }
        let err = gamma_p(a, x) - p;
        let t = if a > 1.0 {
            afac * (-(x - a1) + a1 * (x.ln() - lna1)).exp()
        } else {
            (-x + a1 * x.ln() - gln).exp()
        };
        let u = err / t;
        let step = u / (1.0 - 0.5 * (u * (a1 / x - 1.0)).min(1.0));
        x -= step;
        if x <= 0.0 {
            x = 0.5 * (x + step);
        }
        if step.abs() < 1e-12 * x {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gamma_functions() {
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
        assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
        // P(1, x) = 1 − e^{−x}.
        for x in [0.1, 1.0, 3.0, 10.0] {
            assert!((gamma_p(1.0, x) - (1.0 - (-x).exp())).abs() < 1e-12);
        }
        for a in [0.3, 0.369292, 1.0, 2.5, 9.0] {
            for p in [1e-6, 0.01, 0.3, 0.5, 0.9, 0.999_999] {
                let x = inv_gamma_p(a, p);
                assert!((gamma_p(a, x) / p - 1.0).abs() < 1e-9, "a {a} p {p}: {x}");
            }
        }
    }

    /// The spec's fixture (§2.1) as a process: its mean, median and sd are the paper's, its
    /// turns' median that of |N(0, 40.02°)|.
    #[test]
    fn the_fixtures_process_has_the_papers_moments() {
        let p = Process {
            a: 0.369292,
            c: 1.276084,
            scale: 37.6463,
            turn_sd: 40.02f64.to_radians(),
        };
        let close = |got: f64, want: f64, tol: f64| {
            assert!((got / want - 1.0).abs() < tol, "{got} vs {want}");
        };
        close(p.length_mean(), 14.57, 2e-3);
        close(p.length_median(), 7.22, 2e-3);
        close(p.length_sd(), 19.01, 2e-3);
        close(p.length_cdf(p.length_median()), 0.5, 1e-9);
        close(p.turn_median().to_degrees(), 0.674_489_75 * 40.02, 1e-9);
        close(p.turn_cdf(p.turn_median()), 0.5, 1e-9);
    }

    #[test]
    fn quantiles_interpolate() {
        let mut x = vec![4.0, 1.0, 3.0, 2.0];
        assert_eq!(quantile(&mut x, 0.5), 2.5);
        assert_eq!(quantile(&mut x, 0.0), 1.0);
        assert_eq!(quantile(&mut x, 1.0), 4.0);
        assert_eq!(quantile(&mut [], 0.5), 0.0);
    }

    #[test]
    fn the_solver_solves() {
        let x = solve(vec![vec![2.0, 1.0], vec![1.0, 3.0]], vec![3.0, 5.0]).unwrap();
        assert!((x[0] - 0.8).abs() < 1e-12 && (x[1] - 1.4).abs() < 1e-12);
        assert!(solve(vec![vec![1.0, 2.0], vec![2.0, 4.0]], vec![1.0, 2.0]).is_none());
    }
}
