//! The offline data pipeline of li2015 §3.1 (spec §2.5): tracked trajectories in, a model
//! file out (`swarm li fit`), and the synthetic tracks that stand in for the paper's data
//! (`swarm li synth`).
//!
//! [`fit`]: the tracks' runs of consecutive frames are segmented ([`Segmentation`]); the
//! segment-length and turning-angle tables are either the segments' own histograms
//! ([`Estimate::Direct`], the paper's method) or the distributions of the process whose
//! segmented tracks reproduce the data's statistics ([`Estimate::Indirect`], the default:
//! [`infer`](super::infer)); the visiting-frequency grid counts every sample in its cell of a
//! grid over the data's box. The result is a [`LiModel`], with its provenance.

use std::fmt::Write as _;

use super::data::GridShape;
use super::fixture::{Fixture, synthetic_tracks};
use super::infer::{InferOptions, MIN_SEGMENTS, infer};
use super::model::{
    Estimate, FORMAT, FittedProcess, LengthsTurns, LiModel, Method, ModelGrid, ModelTable,
    Provenance, VERSION,
};
use super::segment::Segmentation;
use super::stats::{moments, segments_by, visit_density};
use crate::error::{Result, SimError};
use crate::eval::{TRACKS_HEADER, Tracks};

/// How [`fit`] reads the tracks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// The segmentation (default: the noise-following tolerance at c = 3.5).
    pub segmentation: Segmentation,
    /// Direct or indirect (default).
    pub estimate: Estimate,
    /// Density cells along the longest side of the data's box (default 16).
    pub cells: u16,
    /// The seed of the indirect fit's simulations (default 1).
    pub seed: u32,
    /// The least samples the indirect fit simulates per candidate (default 100,000).
    pub sim_samples: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            segmentation: Segmentation::default(),
            estimate: Estimate::Indirect,
            cells: 16,
            seed: 1,
            sim_samples: InferOptions::default().sim_samples,
        }
    }
}

/// The share of the fitted length distribution its table covers (the rest goes to the last
/// bin): the 99.9 % quantile keeps the 64 bins narrow where the lengths are.
const LENGTH_COVER: f64 = 0.999;

/// The margin added on every side of the data's box before it is cut into cells, as a share
/// of its longest side (every sample then lies inside a cell, the extreme ones included).
const BOX_MARGIN: f32 = 0.005;

/// The model of `tracks` (read from a file called `source`).
///
/// # Errors
///
/// [`SimError::LiTooFewSegments`] when the segmentation finds fewer than
/// [`MIN_SEGMENTS`] segments or turns; [`SimError::LiSamples`] when they cannot be tabulated
/// (all equal); [`SimError::LiGrid`] for more density cells than a device holds.
pub fn fit(tracks: &Tracks, source: &str, opts: &FitOptions) -> Result<LiModel> {
    let runs: Vec<Vec<[f64; 3]>> = tracks.runs().into_iter().map(|r| r.2).collect();
    let samples: usize = runs.iter().map(Vec::len).sum();
    let segs = segments_by(tracks, &opts.segmentation);
    let turns: Vec<f64> = segs.turns.iter().map(|t| t.abs()).collect();
    if segs.lengths.len() < MIN_SEGMENTS || turns.len() < MIN_SEGMENTS {
        return Err(SimError::LiTooFewSegments {
            segments: segs.lengths.len(),
            turns: turns.len(),
            needed: MIN_SEGMENTS,
        });
    }
    let segmented = LengthsTurns {
        length: moments(&segs.lengths).into(),
        turn: moments(&turns).into(),
    };
    let (lengths, turn_table, fitted) = match opts.estimate {
        Estimate::Direct => (
            ModelTable::of_samples("segment lengths", &segs.lengths)?,
            ModelTable::of_samples("turning angles", &turns)?,
            None,
        ),
        Estimate::Indirect => {
            let infer_opts = InferOptions {
                segmentation: opts.segmentation,
                sim_samples: opts.sim_samples,
                seed: opts.seed,
            };
            let f = infer(&runs, tracks.dt, &infer_opts)?;
            let p = f.process;
            let hi = p.length_quantile(LENGTH_COVER) as f32;
            let lengths = ModelTable::of_cdf(0.0, hi, |x| p.length_cdf(x));
            let turns = ModelTable::of_cdf(0.0, std::f32::consts::PI, |x| p.turn_cdf(x));
            let fitted = FittedProcess {
                a: p.a,
                c: p.c,
                scale: p.scale,
                turn_sd: p.turn_sd,
                speed: f.speed,
                noise: f.noise,
                cost: f.cost,
                evals: f.evals as u64,
                seed: opts.seed,
                sim_samples: opts.sim_samples as u64,
                length: super::model::Moments3 {
                    mean: p.length_mean(),
                    median: p.length_median(),
                    sd: p.length_sd(),
                },
                turn: super::model::Moments3 {
                    mean: p.turn_mean(),
                    median: p.turn_median(),
                    sd: p.turn_sd_moment(),
                },
            };
            (lengths, turns, Some(fitted))
        }
    };
    let density = density_grid(tracks, opts.cells)?;
    let provenance = Provenance {
        source: source.to_owned(),
        tracks: tracks.by_id.len() as u64,
        runs: runs.len() as u64,
        samples: samples as u64,
        dt: tracks.dt,
        segmentation: match opts.segmentation {
            Segmentation::R2 { .. } => Method::R2,
            Segmentation::Tolerance { .. } => Method::Tolerance,
        },
        parameter: opts.segmentation.parameter(),
        estimate: opts.estimate,
        segments: segs.lengths.len() as u64,
        turns: turns.len() as u64,
        segmented,
        tables: LengthsTurns {
            length: lengths.moments(),
            turn: turn_table.moments(),
        },
        fitted,
    };
    Ok(LiModel {
        format: FORMAT.to_owned(),
        version: VERSION,
        provenance,
        lengths,
        turns: turn_table,
        density,
    })
}

/// The visiting-frequency grid of `tracks`: `cells` cubic cells along the longest side of the
/// samples' box (widened by 0.5 % of that side all round), every sample counted in its cell,
/// the busiest cell 255 and a visited one at least 1 ([`visit_density`]).
///
/// # Errors
///
/// [`SimError::LiGrid`] for 0 cells or more than a device holds; [`SimError::LiSamples`]
/// for tracks without a sample or with a non-finite one.
pub fn density_grid(tracks: &Tracks, cells: u16) -> Result<ModelGrid> {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for (_, p) in tracks.by_id.values().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k] as f32);
            hi[k] = hi[k].max(p[k] as f32);
        }
    }
    if !(0..3).all(|k| lo[k].is_finite() && hi[k].is_finite()) {
        return Err(SimError::LiSamples {
            what: "positions",
            n: tracks.len(),
        });
    }
    let side = (0..3)
        .map(|k| hi[k] - lo[k])
        .fold(0.0, f32::max)
        .max(f32::MIN_POSITIVE);
    let margin = BOX_MARGIN * side;
    let min = lo.map(|v| v - margin);
    let max = hi.map(|v| v + margin);
    let shape = GridShape::over(min, max, cells)?;
    let dims = shape.dims.map(usize::from);
    let weights = visit_density(
        tracks,
        shape.origin.map(f64::from),
        f64::from(shape.cell),
        dims,
    );
    Ok(ModelGrid {
        origin: shape.origin,
        cell: shape.cell,
        dims: shape.dims,
        weights,
    })
}

/// The synthetic tracks of `f` as the text of a track file (`id,time,x,y,z`, one row per
/// insect and frame, by id then time; times `k/fps` in their shortest decimal, positions in
/// 6 decimals): what `swarm li synth` writes, the same bytes for the same parameters.
pub fn synthetic_csv(f: &Fixture) -> String {
    let (tracks, _) = synthetic_tracks(f);
    let mut out = String::with_capacity(tracks.len() * 40 + 16);
    out.push_str(TRACKS_HEADER);
    out.push('\n');
    for (id, samples) in &tracks.by_id {
        for (k, p) in samples {
            let t = *k as f64 / f.fps;
            let _ = writeln!(out, "{id},{t},{:.6},{:.6},{:.6}", p[0], p[1], p[2]);
        }
    }
    out
}
