//! The li2015 model file: what `swarm li fit` learned from tracked trajectories, for
//! scenarios to use (`li = { model = "model.toml" }`).
//!
//! A TOML file, format `swarm-li-model`, version 1:
//!
//! ```toml
//! format = "swarm-li-model"
//! version = 1
//!
//! [provenance]                  # where the data came from and how they were read
//! source = "tracks.csv"         # the track file's name
//! tracks = 20                   # insect ids
//! runs = 20                     # runs of consecutive frames (a gap starts a new one)
//! samples = 20000               # positions
//! dt = 0.01                     # frame interval (s)
//! segmentation = "tolerance"    # "tolerance" (c·σ̂) or "r2" (the paper's rule)
//! parameter = 3.5               # c, or the R² threshold
//! estimate = "indirect"         # "indirect" (a fitted process) or "direct" (the segments)
//! segments = 1412               # segments the segmentation found in the data
//! turns = 1392                  # turning angles between them
//! segmented = { length = { mean = 0.0134, median = 0.0081, sd = 0.016 }, turn = { .. } }
//! tables = { length = { .. }, turn = { .. } }   # the moments of the tables below
//!
//! [provenance.fitted]           # only for estimate = "indirect": the generating process
//! a = 0.41                      # lengths scale·G^(1/c), G ~ Gamma(a, 1)
//! c = 1.2
//! scale = 0.031
//! turn_sd = 0.70                # turns |N(0, turn_sd²)| (radians)
//! speed = 0.15                  # flight speed (units/s)
//! noise = 0.0002                # measurement noise (units)
//! cost = 9.1                    # the weighted squared distance of its statistics
//! evals = 130                   # simulations run
//! seed = 1                      # the simulations' seed
//! sim_samples = 100000          # samples simulated per candidate (at least)
//! length = { mean = .., median = .., sd = .. }   # the process's own moments
//! turn = { mean = .., median = .., sd = .. }
//!
//! [lengths]                     # the segment-length table (units)
//! lo = 0.0
//! hi = 0.17
//! counts = [..]                 # 1 to 64 bins over [lo, hi]: samples (or, for a fitted
//!                               # process, its probability × 10⁹) in each
//!
//! [turns]                       # the turning-angle table (radians, magnitudes in [0, π])
//! lo = 0.0
//! hi = 3.1415927
//! counts = [..]
//!
//! [density]                     # the visiting frequency over the data's box
//! origin = [x, y, z]            # lower corner of cell (0, 0, 0)
//! cell = 0.1                    # cubic cells of this side
//! dims = [16, 16, 16]           # cells along x, y, z (at most 4096 in all)
//! weights = [..]                # 0-255 per cell, x fastest, then y, then z
//! ```
//!
//! The tables are their bins, so a table read back is the one written, bit for bit
//! ([`ModelTable::table`] rebuilds the inverse CDF the insects sample). Reading checks every
//! field and names the file, the line and the field of what it refuses
//! ([`SimError::LiModelToml`], [`SimError::LiModelVersion`], [`SimError::LiModelField`]).
//! Writing replaces the file whole or not at all.

use std::fmt::Write as _;
use std::path::Path;

use serde::{Deserialize, Serialize};
use swarm_core::Vec3;
use swarm_core::li::density::{DensityGrid, MAX_CELLS};
use swarm_core::li::sampler::Table;
use swarm_core::li::{BINS, LiTable};
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::data::cell_clear;
use super::stats::histogram;
use crate::error::{Result, SimError};
use crate::space::BeeObstacle;

/// The `format` of a model file.
pub const FORMAT: &str = "swarm-li-model";
/// The `version` this build reads and writes.
pub const VERSION: u32 = 1;

/// What is wrong with a field of a model file ([`SimError::LiModelField`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelProblem {
    /// A table with no bins or more than a device holds.
    #[error("{found} bins; a table has 1 to {max}")]
    Bins {
        /// The bins given.
        found: usize,
        /// The most there may be ([`BINS`]).
        max: usize,
    },
    /// A table's range that is empty or not finite.
    #[error("lo {lo} and hi {hi}: both must be finite, with lo < hi")]
    Range {
        /// Lower end.
        lo: f32,
        /// Upper end.
        hi: f32,
    },
    /// A table whose every count is 0.
    #[error("every count is 0: the table describes no value")]
    NoCounts,
    /// A table's counts whose total does not fit 32 bits.
    #[error("the counts add up to more than 2^32 - 1")]
    CountsOverflow,
    /// A value below the smallest allowed.
    #[error("{value} is below {min}")]
    Below {
        /// The value.
        value: f64,
        /// The smallest allowed.
        min: f64,
    },
    /// A value above the largest allowed.
    #[error("{value} is above {max}")]
    Above {
        /// The value.
        value: f64,
        /// The largest allowed.
        max: f64,
    },
    /// A number that is not finite, or not positive where it must be.
    #[error("{value} is not a positive finite number")]
    NotPositive {
        /// The value.
        value: f64,
    },
    /// A number that is not finite.
    #[error("{value} is not finite")]
    NotFinite {
        /// The value.
        value: f64,
    },
    /// A grid with a zero dimension or more cells than a device holds.
    #[error("dims {dims:?}: every dimension at least 1, at most {max} cells in all")]
    Cells {
        /// The dimensions.
        dims: [u16; 3],
        /// The most cells ([`MAX_CELLS`]).
        max: usize,
    },
    /// Not one weight per cell.
    #[error("{found} weights, the grid has {cells} cells (dims {dims:?})")]
    Weights {
        /// The weights given.
        found: usize,
        /// The cells of the grid.
        cells: usize,
        /// Its dimensions.
        dims: [u16; 3],
    },
    /// A grid whose every weight is 0.
    #[error("every weight is 0: the insects would have nowhere to go")]
    NoVisits,
    /// Provenance that contradicts itself (fitted values without an indirect estimate, ...).
    #[error("{0}")]
    Inconsistent(&'static str),
}

/// A learned distribution as its bins: `counts[k]` in bin k of `counts.len()` equal bins over
/// `[lo, hi]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelTable {
    /// Lower end of the first bin.
    pub lo: f32,
    /// Upper end of the last bin.
    pub hi: f32,
    /// The weight of each bin (1 to [`BINS`] bins).
    pub counts: Vec<u32>,
}

/// Mean, median and standard deviation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Moments3 {
    /// Mean.
    pub mean: f64,
    /// Median.
    pub median: f64,
    /// Standard deviation.
    pub sd: f64,
}

impl From<super::stats::Moments> for Moments3 {
    fn from(m: super::stats::Moments) -> Self {
        Moments3 {
            mean: m.mean,
            median: m.median,
            sd: m.sd,
        }
    }
}

impl ModelTable {
    /// The table of `samples`: [`BINS`] equal bins over their [min, max] (spec §2.1), the
    /// count of samples in each.
    ///
    /// # Errors
    ///
    /// [`SimError::LiSamples`] when there are none, or they are not finite, or all equal.
    pub fn of_samples(what: &'static str, samples: &[f64]) -> Result<ModelTable> {
        let bad = || SimError::LiSamples {
            what,
            n: samples.len(),
        };
        if samples.iter().any(|v| !v.is_finite()) {
            return Err(bad());
        }
        let lo = samples.iter().copied().fold(f64::INFINITY, f64::min) as f32;
        let hi = samples.iter().copied().fold(f64::NEG_INFINITY, f64::max) as f32;
        if lo.is_nan() || hi.is_nan() || lo >= hi {
            return Err(bad());
        }
        let counts = histogram(samples, f64::from(lo), f64::from(hi), BINS);
        Ok(ModelTable { lo, hi, counts })
    }

    /// The table of a distribution given by its CDF: [`BINS`] equal bins over `[lo, hi]`,
    /// each weighted by its probability × 10⁹ (rounded), the probability above `hi` in the
    /// last bin.
    pub fn of_cdf(lo: f32, hi: f32, cdf: impl Fn(f64) -> f64) -> ModelTable {
        let edge =
            |k: usize| f64::from(lo) + (f64::from(hi) - f64::from(lo)) * k as f64 / BINS as f64;
        let counts = (0..BINS)
            .map(|k| {
                let above = if k + 1 == BINS { 1.0 } else { cdf(edge(k + 1)) };
                ((above - cdf(edge(k))).max(0.0) * 1e9).round() as u32
            })
            .collect();
        ModelTable { lo, hi, counts }
    }

    /// The inverse-CDF table the insects sample ([`Table::from_counts`]).
    ///
    /// # Errors
    ///
    /// [`SimError::LiSamples`] for a table [`LiModel::read`] would refuse (no bins, too
    /// many, no counts, an empty range).
    pub fn table(&self) -> Result<LiTable<f32>> {
        Table::from_counts(self.lo, self.hi, &self.counts).map_err(|_| SimError::LiSamples {
            what: "model table",
            n: self.counts.len(),
        })
    }

    /// The mean, median and sd of the table's distribution (piecewise uniform in its bins).
    pub fn moments(&self) -> Moments3 {
        let total: f64 = self.counts.iter().map(|&c| f64::from(c)).sum();
        if total <= 0.0 || self.counts.is_empty() {
            return Moments3::default();
        }
        let (lo, hi) = (f64::from(self.lo), f64::from(self.hi));
        let w = (hi - lo) / self.counts.len() as f64;
        let (mut mean, mut m2, mut below) = (0.0, 0.0, 0.0);
        let mut median = hi;
        let mut found = false;
        for (k, &c) in self.counts.iter().enumerate() {
            let p = f64::from(c) / total;
            let a = lo + k as f64 * w;
            let mid = a + 0.5 * w;
            mean += p * mid;
            m2 += p * (mid * mid + w * w / 12.0);
            if !found && p > 0.0 && below + p >= 0.5 {
                median = a + (0.5 - below) / p * w;
                found = true;
            }
            below += p;
        }
        Moments3 {
            mean,
            median,
            sd: (m2 - mean * mean).max(0.0).sqrt(),
        }
    }

    fn check(
        &self,
        field: &'static str,
        min: f32,
        max: f32,
    ) -> std::result::Result<(), (String, ModelProblem)> {
        let at = |f: &str| format!("{field}.{f}");
        if !(self.lo.is_finite() && self.hi.is_finite() && self.lo < self.hi) {
            return Err((
                at("hi"),
                ModelProblem::Range {
                    lo: self.lo,
                    hi: self.hi,
                },
            ));
        }
        if self.lo < min {
            return Err((
                at("lo"),
                ModelProblem::Below {
                    value: f64::from(self.lo),
                    min: f64::from(min),
                },
            ));
        }
        if self.hi > max {
            return Err((
                at("hi"),
                ModelProblem::Above {
                    value: f64::from(self.hi),
                    max: f64::from(max),
                },
            ));
        }
        if self.counts.is_empty() || self.counts.len() > BINS {
            return Err((
                at("counts"),
                ModelProblem::Bins {
                    found: self.counts.len(),
                    max: BINS,
                },
            ));
        }
        let total: u64 = self.counts.iter().map(|&c| u64::from(c)).sum();
        if total == 0 {
            return Err((at("counts"), ModelProblem::NoCounts));
        }
        if total > u64::from(u32::MAX) {
            return Err((at("counts"), ModelProblem::CountsOverflow));
        }
        Ok(())
    }
}

/// A visiting-frequency grid as the file holds it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelGrid {
    /// The lower corner of cell (0, 0, 0).
    pub origin: [f32; 3],
    /// The side of a cell.
    pub cell: f32,
    /// Cells along x, y and z.
    pub dims: [u16; 3],
    /// w_c per cell, x fastest, then y, then z.
    pub weights: Vec<u8>,
}

impl ModelGrid {
    /// The number of cells (saturating).
    pub fn cells(&self) -> usize {
        self.dims
            .iter()
            .fold(1usize, |n, &d| n.saturating_mul(usize::from(d)))
    }

    /// The lower and upper corners of the grid.
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        let max = [0, 1, 2].map(|k| self.origin[k] + self.cell * f32::from(self.dims[k]));
        (self.origin, max)
    }

    /// The grid placed in a world `[min, max]` (the rule of a scenario that uses a model
    /// file): as it is, cell for cell, when it lies inside the world (within 10⁻⁴ of the
    /// world's longest side); cells any part of which is inside an active obstacle
    /// ([`cell_clear`]) set to 0, and every other cell at least 1 (ours, as the Gaussian
    /// densities of [`gaussian_weights`](super::data::gaussian_weights): Metropolis-Hastings
    /// never enters
    /// a zero cell, so an insect in a cell the data never visited could not leave it; with
    /// the floor it wanders until it finds the visited ones). Outside the grid the density
    /// is 0, as everywhere a grid does not cover: spawn the insects inside it.
    ///
    /// # Errors
    ///
    /// `Err((grid_min, grid_max))` when the grid reaches outside the world.
    pub fn placed(
        &self,
        world: ([f32; 3], [f32; 3]),
        obstacles: &[BeeObstacle],
    ) -> std::result::Result<DensityGrid<f32>, ([f32; 3], [f32; 3])> {
        let (lo, hi) = self.bounds();
        let side = (0..3).map(|k| world.1[k] - world.0[k]).fold(0.0, f32::max);
        let slack = 1e-4 * side;
        if (0..3).any(|k| lo[k] < world.0[k] - slack || hi[k] > world.1[k] + slack) {
            return Err((lo, hi));
        }
        let [nx, ny, _] = self.dims.map(usize::from);
        let weights: Vec<u8> = self
            .weights
            .iter()
            .enumerate()
            .map(|(i, &w)| {
                let idx = [i % nx, (i / nx) % ny, i / (nx * ny)];
                let c = [0, 1, 2].map(|k| self.origin[k] + (idx[k] as f32 + 0.5) * self.cell);
                if cell_clear(obstacles, c, self.cell) {
                    w.max(1)
                } else {
                    0
                }
            })
            .collect();
        let o = self.origin;
        // Checked when the file was read: the shape holds.
        DensityGrid::new(Vec3::new(o[0], o[1], o[2]), self.cell, self.dims, &weights)
            .map_err(|_| (lo, hi))
    }

    fn check(&self) -> std::result::Result<(), (String, ModelProblem)> {
        let at = |f: &str| format!("density.{f}");
        for (k, &v) in self.origin.iter().enumerate() {
            if !v.is_finite() {
                return Err((
                    format!("density.origin[{k}]"),
                    ModelProblem::NotFinite {
                        value: f64::from(v),
                    },
                ));
            }
        }
        if !(self.cell.is_finite() && self.cell > 0.0) {
            return Err((
                at("cell"),
                ModelProblem::NotPositive {
                    value: f64::from(self.cell),
                },
            ));
        }
        let cells = self.cells();
        if self.dims.contains(&0) || cells > MAX_CELLS {
            return Err((
                at("dims"),
                ModelProblem::Cells {
                    dims: self.dims,
                    max: MAX_CELLS,
                },
            ));
        }
        if self.weights.len() != cells {
            return Err((
                at("weights"),
                ModelProblem::Weights {
                    found: self.weights.len(),
                    cells,
                    dims: self.dims,
                },
            ));
        }
        if self.weights.iter().all(|&w| w == 0) {
            return Err((at("weights"), ModelProblem::NoVisits));
        }
        Ok(())
    }
}

/// How the tracks were segmented.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// The paper's R² rule.
    R2,
    /// The noise-following tolerance.
    Tolerance,
}

/// How the tables were estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Estimate {
    /// The segments' own lengths and turns (the paper's).
    Direct,
    /// The process whose segmentation reproduces the data's statistics
    /// ([`infer`](super::infer)).
    Indirect,
}

/// The moments of the lengths and the turns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LengthsTurns {
    /// Segment lengths (units).
    pub length: Moments3,
    /// Turning-angle magnitudes (radians).
    pub turn: Moments3,
}

/// The generating process of an indirect estimate ([`infer::Fitted`](super::infer::Fitted)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FittedProcess {
    /// Shape a of the lengths' gamma variate.
    pub a: f64,
    /// Power c of the lengths.
    pub c: f64,
    /// Scale of the lengths (units).
    pub scale: f64,
    /// The turns' normal sd (radians).
    pub turn_sd: f64,
    /// Flight speed (units/s).
    pub speed: f64,
    /// Measurement noise (units).
    pub noise: f64,
    /// The weighted squared distance of its statistics from the data's.
    pub cost: f64,
    /// Simulations run.
    pub evals: u64,
    /// The simulations' seed.
    pub seed: u32,
    /// Samples simulated per candidate (at least).
    pub sim_samples: u64,
    /// The process's moments.
    pub length: Moments3,
    /// The process's turn moments.
    pub turn: Moments3,
}

/// Where a model's data came from and how they were read.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    /// The track file's name.
    pub source: String,
    /// Insect ids.
    pub tracks: u64,
    /// Runs of consecutive frames.
    pub runs: u64,
    /// Positions.
    pub samples: u64,
    /// Frame interval (s).
    pub dt: f64,
    /// The segmentation.
    pub segmentation: Method,
    /// Its parameter (c or R²).
    pub parameter: f64,
    /// How the tables were estimated.
    pub estimate: Estimate,
    /// Segments found in the data.
    pub segments: u64,
    /// Turns found between them.
    pub turns: u64,
    /// The moments of what the segmentation found.
    pub segmented: LengthsTurns,
    /// The moments of the tables.
    pub tables: LengthsTurns,
    /// The process of an indirect estimate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fitted: Option<FittedProcess>,
}

/// A model file's contents.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiModel {
    /// [`FORMAT`].
    pub format: String,
    /// [`VERSION`].
    pub version: u32,
    /// Where the data came from.
    pub provenance: Provenance,
    /// Segment lengths (units).
    pub lengths: ModelTable,
    /// Turning-angle magnitudes (radians).
    pub turns: ModelTable,
    /// The visiting frequency.
    pub density: ModelGrid,
}

/// The header every model file starts with.
#[derive(Deserialize)]
struct Header {
    format: Option<toml::Value>,
    version: Option<toml::Value>,
}

/// 1-based line and column (in characters) of byte `offset` of `text`.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// The 1-based line of the field at `path` (`density.weights`, `density.origin[1]`): of
/// its deepest part the file has.
fn line_of(text: &str, path: &str) -> usize {
    let Ok(tree) = DeTable::parse(text) else {
        return 1;
    };
    let mut span = 0..0;
    let mut value: Option<&Spanned<DeValue<'_>>> = None;
    for part in path.split('.') {
        let (key, index) = match part.split_once('[') {
            Some((k, i)) => (k, i.trim_end_matches(']').parse::<usize>().ok()),
            None => (part, None),
        };
        let next = match value {
            None => tree.get_ref().get(key),
            Some(v) => v.get_ref().as_table().and_then(|t| t.get(key)),
        };
        let Some(mut found) = next else { break };
        if let Some(i) = index
            && let Some(item) = found.get_ref().as_array().and_then(|a| a.get(i))
        {
            found = item;
        }
        span = found.span();
        value = Some(found);
    }
    line_column(text, span.start).0
}

impl LiModel {
    /// Reads and checks the model file at `path`.
    ///
    /// # Errors
    ///
    /// [`SimError::Io`] when it cannot be read; [`SimError::LiModelToml`] when it is not
    /// TOML or a field is missing, unknown or of the wrong type; [`SimError::LiModelVersion`]
    /// for another format or version; [`SimError::LiModelField`] for a value that breaks a
    /// rule ([`LiModel::check`]).
    pub fn read(path: &Path) -> Result<LiModel> {
        let text = std::fs::read_to_string(path).map_err(|e| SimError::io("reading", path, e))?;
        Self::parse(&text, path)
    }

    /// [`LiModel::read`] on the text of the file at `path`.
    ///
    /// # Errors
    ///
    /// As [`LiModel::read`].
    pub fn parse(text: &str, path: &Path) -> Result<LiModel> {
        let toml_error = |e: toml::de::Error| {
            let (line, column) = line_column(text, e.span().map_or(0, |s| s.start));
            SimError::LiModelToml {
                path: path.into(),
                line,
                column,
                source: Box::new(e),
            }
        };
        let header: Header = toml::from_str(text).map_err(toml_error)?;
        let format = header.format.as_ref().and_then(|v| v.as_str());
        let version = header.version.as_ref().and_then(toml::Value::as_integer);
        if format != Some(FORMAT) || version != Some(i64::from(VERSION)) {
            return Err(SimError::LiModelVersion {
                path: path.into(),
                format: header.format.map(|v| v.to_string()),
                version: header.version.map(|v| v.to_string()),
            });
        }
        let model: LiModel = toml::from_str(text).map_err(toml_error)?;
        model
            .check()
            .map_err(|(field, problem)| SimError::LiModelField {
                path: path.into(),
                line: line_of(text, &field),
                field,
                problem,
            })?;
        Ok(model)
    }

    /// Checks every field: the tables (1 to [`BINS`] bins, a finite range with lo < hi,
    /// some count, lengths not below 0, turns within [0, π]), the grid (finite origin,
    /// positive cell, 1 to [`MAX_CELLS`] cells, one weight each, some weight), the provenance
    /// (finite, non-negative numbers; a fitted process exactly when the estimate is
    /// indirect).
    ///
    /// # Errors
    ///
    /// The first field that breaks a rule (its path, `lengths.counts`) and why.
    pub fn check(&self) -> std::result::Result<(), (String, ModelProblem)> {
        self.lengths.check("lengths", 0.0, f32::INFINITY)?;
        self.turns.check("turns", 0.0, std::f32::consts::PI)?;
        self.density.check()?;
        let p = &self.provenance;
        let at = |f: &str| format!("provenance.{f}");
        if !(p.dt.is_finite() && p.dt > 0.0) {
            return Err((at("dt"), ModelProblem::NotPositive { value: p.dt }));
        }
        if !(p.parameter.is_finite() && p.parameter > 0.0) {
            return Err((
                at("parameter"),
                ModelProblem::NotPositive { value: p.parameter },
            ));
        }
        let moments = |name: &str, m: &LengthsTurns| {
            for (what, x) in [("length", m.length), ("turn", m.turn)] {
                for (f, v) in [("mean", x.mean), ("median", x.median), ("sd", x.sd)] {
                    if !v.is_finite() {
                        return Err((
                            format!("provenance.{name}.{what}.{f}"),
                            ModelProblem::NotFinite { value: v },
                        ));
                    }
                }
            }
            Ok(())
        };
        moments("segmented", &p.segmented)?;
        moments("tables", &p.tables)?;
        match (&p.fitted, p.estimate) {
            (Some(_), Estimate::Direct) => {
                return Err((
                    at("fitted"),
                    ModelProblem::Inconsistent(
                        "a fitted process, but `estimate = \"direct\"` (the tables are the \
                         segments' own)",
                    ),
                ));
            }
            (None, Estimate::Indirect) => {
                return Err((
                    at("fitted"),
                    ModelProblem::Inconsistent(
                        "missing: `estimate = \"indirect\"` needs the fitted process",
                    ),
                ));
            }
            (Some(f), _) => {
                for (name, v) in [
                    ("a", f.a),
                    ("c", f.c),
                    ("scale", f.scale),
                    ("turn_sd", f.turn_sd),
                    ("speed", f.speed),
                ] {
                    if !(v.is_finite() && v > 0.0) {
                        return Err((
                            format!("provenance.fitted.{name}"),
                            ModelProblem::NotPositive { value: v },
                        ));
                    }
                }
                for (name, v) in [("noise", f.noise), ("cost", f.cost)] {
                    if !(v.is_finite() && v >= 0.0) {
                        return Err((
                            format!("provenance.fitted.{name}"),
                            ModelProblem::Below { value: v, min: 0.0 },
                        ));
                    }
                }
                moments(
                    "fitted",
                    &LengthsTurns {
                        length: f.length,
                        turn: f.turn,
                    },
                )?;
            }
            (None, Estimate::Direct) => {}
        }
        Ok(())
    }

    /// The model as the text of its file (TOML with comments; arrays of the grid one x-row a
    /// line). [`LiModel::parse`] of it gives the model back.
    pub fn to_toml(&self) -> String {
        let mut s = String::new();
        let p = &self.provenance;
        let _ = writeln!(
            s,
            "# A li2015 model (Li et al. 2015): segment lengths, turning angles and the visiting\n\
             # frequency learned from tracked trajectories by `swarm li fit`. Scenarios use it with\n\
             # `li = {{ model = \"<this file>\" }}`; the format is documented in\n\
             # host-sim/src/li/model.rs."
        );
        let _ = writeln!(s, "format = {}", quote(&self.format));
        let _ = writeln!(s, "version = {}", self.version);
        let _ = writeln!(s, "\n[provenance]");
        let _ = writeln!(s, "source = {}", quote(&p.source));
        let _ = writeln!(s, "tracks = {}", p.tracks);
        let _ = writeln!(s, "runs = {}", p.runs);
        let _ = writeln!(s, "samples = {}", p.samples);
        let _ = writeln!(s, "dt = {}", float(p.dt));
        let method = match p.segmentation {
            Method::R2 => "r2",
            Method::Tolerance => "tolerance",
        };
        let _ = writeln!(s, "segmentation = {}", quote(method));
        let _ = writeln!(s, "parameter = {}", float(p.parameter));
        let estimate = match p.estimate {
            Estimate::Direct => "direct",
            Estimate::Indirect => "indirect",
        };
        let _ = writeln!(s, "estimate = {}", quote(estimate));
        let _ = writeln!(s, "segments = {}", p.segments);
        let _ = writeln!(s, "turns = {}", p.turns);
        let _ = writeln!(
            s,
            "# What the segmentation found (lengths in the tracks' unit, turns in radians)."
        );
        let _ = writeln!(s, "segmented = {}", lengths_turns(&p.segmented));
        let _ = writeln!(
            s,
            "# The moments of the tables below (what a scenario samples)."
        );
        let _ = writeln!(s, "tables = {}", lengths_turns(&p.tables));
        if let Some(f) = &p.fitted {
            let _ = writeln!(
                s,
                "\n# The process whose segmented tracks match the data's statistics: lengths\n\
                 # scale·G^(1/c) with G ~ Gamma(a, 1), turns |N(0, turn_sd²)|."
            );
            let _ = writeln!(s, "[provenance.fitted]");
            for (k, v) in [
                ("a", f.a),
                ("c", f.c),
                ("scale", f.scale),
                ("turn_sd", f.turn_sd),
                ("speed", f.speed),
                ("noise", f.noise),
                ("cost", f.cost),
            ] {
                let _ = writeln!(s, "{k} = {}", float(v));
            }
            let _ = writeln!(s, "evals = {}", f.evals);
            let _ = writeln!(s, "seed = {}", f.seed);
            let _ = writeln!(s, "sim_samples = {}", f.sim_samples);
            let _ = writeln!(s, "length = {}", moments3(&f.length));
            let _ = writeln!(s, "turn = {}", moments3(&f.turn));
        }
        for (name, t, what) in [
            (
                "lengths",
                &self.lengths,
                "segment lengths (the tracks' unit)",
            ),
            ("turns", &self.turns, "turning-angle magnitudes (radians)"),
        ] {
            let _ = writeln!(s, "\n# The {what}: counts in equal bins over [lo, hi].");
            let _ = writeln!(s, "[{name}]");
            let _ = writeln!(s, "lo = {}", float32(t.lo));
            let _ = writeln!(s, "hi = {}", float32(t.hi));
            let _ = writeln!(s, "counts = [");
            for row in t.counts.chunks(8) {
                let items: Vec<String> = row.iter().map(u32::to_string).collect();
                let _ = writeln!(s, "    {},", items.join(", "));
            }
            let _ = writeln!(s, "]");
        }
        let d = &self.density;
        let _ = writeln!(
            s,
            "\n# The visiting frequency: cubic cells from origin, 0-255 per cell, x fastest\n\
             # (one x-row a line), then y, then z."
        );
        let _ = writeln!(s, "[density]");
        let _ = writeln!(
            s,
            "origin = [{}, {}, {}]",
            float32(d.origin[0]),
            float32(d.origin[1]),
            float32(d.origin[2])
        );
        let _ = writeln!(s, "cell = {}", float32(d.cell));
        let _ = writeln!(s, "dims = [{}, {}, {}]", d.dims[0], d.dims[1], d.dims[2]);
        let _ = writeln!(s, "weights = [");
        for row in d.weights.chunks(usize::from(d.dims[0].max(1))) {
            let items: Vec<String> = row.iter().map(u8::to_string).collect();
            let _ = writeln!(s, "    {},", items.join(", "));
        }
        let _ = writeln!(s, "]");
        s
    }

    /// Writes the model to `path`, whole or not at all (a temporary file renamed over it).
    ///
    /// # Errors
    ///
    /// [`SimError::Io`] when the file cannot be written.
    pub fn write(&self, path: &Path) -> Result<()> {
        crate::output::remove_stale_temps(path);
        crate::output::write_atomic_bytes(path, self.to_toml().as_bytes())
    }
}

/// A TOML basic string.
fn quote(s: &str) -> String {
    let mut out = String::from("\"");
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A finite f64 as a TOML float that reads back to the same bits (the shortest such
/// decimal, with a decimal point).
fn float(v: f64) -> String {
    let s = format!("{v:?}");
    if s.contains(['.', 'e', 'E', 'n', 'i']) {
        s
    } else {
        format!("{s}.0")
    }
}

/// A finite f32 as a TOML float that reads back (through f64) to the same bits.
fn float32(v: f32) -> String {
    let s = format!("{v:?}");
    if s.contains(['.', 'e', 'E', 'n', 'i']) {
        s
    } else {
        format!("{s}.0")
    }
}

fn moments3(m: &Moments3) -> String {
    format!(
        "{{ mean = {}, median = {}, sd = {} }}",
        float(m.mean),
        float(m.median),
        float(m.sd)
    )
}

fn lengths_turns(m: &LengthsTurns) -> String {
    format!(
        "{{ length = {}, turn = {} }}",
        moments3(&m.length),
        moments3(&m.turn)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small valid model (direct estimate).
    pub(crate) fn sample() -> LiModel {
        let m = Moments3 {
            mean: 0.0146,
            median: 0.0072,
            sd: 0.019,
        };
        LiModel {
            format: FORMAT.into(),
            version: VERSION,
            provenance: Provenance {
                source: "tracks \"a\".csv".into(),
                tracks: 2,
                runs: 3,
                samples: 400,
                dt: 0.01,
                segmentation: Method::Tolerance,
                parameter: 3.5,
                estimate: Estimate::Direct,
                segments: 40,
                turns: 37,
                segmented: LengthsTurns { length: m, turn: m },
                tables: LengthsTurns { length: m, turn: m },
                fitted: None,
            },
            lengths: ModelTable {
                lo: 0.0001,
                hi: 0.13,
                counts: vec![5, 0, 3, 1],
            },
            turns: ModelTable {
                lo: 0.0,
                hi: std::f32::consts::PI,
                counts: vec![1; 64],
            },
            density: ModelGrid {
                origin: [-0.1, 0.2, 1e-7],
                cell: 0.3,
                dims: [3, 2, 2],
                weights: vec![0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 255],
            },
        }
    }

    fn parse(text: &str) -> Result<LiModel> {
        LiModel::parse(text, Path::new("m.toml"))
    }

    /// Written and read back: the same model, bit for bit (f32 ranges, f64 moments), and the
    /// same text again; a fitted process too.
    #[test]
    fn a_model_file_round_trips() {
        let mut m = sample();
        let text = m.to_toml();
        assert_eq!(parse(&text).unwrap(), m);
        m.provenance.estimate = Estimate::Indirect;
        m.provenance.fitted = Some(FittedProcess {
            a: 0.369292,
            c: 1.276084,
            scale: 0.0376463,
            turn_sd: 0.698,
            speed: 0.15,
            noise: 0.0002,
            cost: 12.25,
            evals: 130,
            seed: 7,
            sim_samples: 100_000,
            length: Moments3::default(),
            turn: Moments3 {
                mean: 1.0 / 3.0,
                median: 1e-300,
                sd: 123456789.0,
            },
        });
        let text = m.to_toml();
        let back = parse(&text).unwrap();
        assert_eq!(back, m);
        assert_eq!(back.to_toml(), text);
        // Awkward floats read back exactly.
        for v in [0.1f32, 1e-7, 3.0, 1.0 / 3.0, f32::MIN_POSITIVE, 12345.678] {
            let s = float32(v);
            assert_eq!(s.parse::<f64>().unwrap() as f32, v, "{s}");
        }
        for v in [0.1f64, 1e-300, 3.0, 1.0 / 3.0, 1e21] {
            let s = float(v);
            assert!(s.contains(['.', 'e']), "{s}");
            assert_eq!(s.parse::<f64>().unwrap(), v, "{s}");
        }
    }

    /// `text` with the first `from` replaced by `to`.
    fn edit(from: &str, to: &str) -> String {
        let text = sample().to_toml();
        assert!(text.contains(from), "{from}");
        text.replacen(from, to, 1)
    }

    fn field_error(text: &str) -> (usize, String, ModelProblem) {
        match parse(text) {
            Err(SimError::LiModelField {
                line,
                field,
                problem,
                ..
            }) => (line, field, problem),
            other => panic!("{other:?}"),
        }
    }

    /// Every rule names its field and line, and says what is wrong.
    #[test]
    fn broken_fields_are_named() {
        let rows = "    3, 4, 5,\n    6, 7, 8,\n    9, 10, 255,\n";
        let (line, field, problem) = field_error(&edit(rows, "    3,\n"));
        assert_eq!(field, "density.weights");
        assert_eq!(
            problem,
            ModelProblem::Weights {
                found: 4,
                cells: 12,
                dims: [3, 2, 2]
            }
        );
        let text = edit(rows, "    3,\n");
        let at = text.lines().position(|l| l.starts_with("weights")).unwrap() + 1;
        assert_eq!(line, at);
        let err = parse(&text).unwrap_err().to_string();
        assert!(
            err.starts_with(&format!("m.toml:{at}: `density.weights`: 4 weights")),
            "{err}"
        );

        assert_eq!(
            field_error(&edit("hi = 0.13", "hi = -1.0")).2,
            ModelProblem::Range {
                lo: 0.0001,
                hi: -1.0
            }
        );
        assert_eq!(
            field_error(&edit("lo = 0.0001", "lo = -0.5")).1,
            "lengths.lo"
        );
        assert_eq!(
            field_error(&edit("hi = 3.1415927", "hi = 4.0")).2,
            ModelProblem::Above {
                value: 4.0,
                max: f64::from(std::f32::consts::PI)
            }
        );
        assert_eq!(
            field_error(&edit("    5, 0, 3, 1,", "    0, 0, 0, 0,")),
            (
                field_error(&edit("    5, 0, 3, 1,", "    0, 0, 0, 0,")).0,
                "lengths.counts".into(),
                ModelProblem::NoCounts
            )
        );
        let many = format!("    {}", vec!["1"; 65].join(", "));
        assert_eq!(
            field_error(&edit("    5, 0, 3, 1,", &many)).2,
            ModelProblem::Bins { found: 65, max: 64 }
        );
        assert_eq!(
            field_error(&edit("cell = 0.3", "cell = 0.0")).1,
            "density.cell"
        );
        assert_eq!(
            field_error(&edit("dims = [3, 2, 2]", "dims = [3, 0, 2]")).2,
            ModelProblem::Cells {
                dims: [3, 0, 2],
                max: MAX_CELLS
            }
        );
        let zeros = "    0, 0, 0,\n    0, 0, 0,\n    0, 0, 0,\n    0, 0, 0,";
        let text = sample().to_toml();
        let start = text.find("weights = [\n").unwrap() + "weights = [\n".len();
        let end = text[start..].find(']').unwrap() + start;
        let text = format!("{}{zeros}\n{}", &text[..start], &text[end..]);
        assert_eq!(field_error(&text).2, ModelProblem::NoVisits);
        assert_eq!(
            field_error(&edit("dt = 0.01", "dt = -0.01")).1,
            "provenance.dt"
        );
        assert_eq!(
            field_error(&edit("estimate = \"direct\"", "estimate = \"indirect\"")).1,
            "provenance.fitted"
        );
        let (_, field, _) = field_error(&edit("origin = [-0.1", "origin = [nan"));
        assert_eq!(field, "density.origin[0]");
    }

    /// Not TOML, a missing, unknown or mistyped field: the reader's message at its line; another
    /// format or version: said so.
    #[test]
    fn malformed_files_are_refused() {
        let toml_error = |text: &str| match parse(text) {
            Err(SimError::LiModelToml { line, source, .. }) => (line, source.message().to_owned()),
            other => panic!("{other:?}"),
        };
        let (line, message) = toml_error(&edit("cell = 0.3", "cell = \"wide\""));
        let text = sample().to_toml();
        assert_eq!(
            line,
            text.lines().position(|l| l.starts_with("cell")).unwrap() + 1
        );
        assert!(message.contains("invalid type"), "{message}");
        let (_, message) = toml_error(&edit("cell = 0.3", "cel = 0.3"));
        assert!(message.contains("unknown field `cel`"), "{message}");
        let (_, message) = toml_error(&edit(
            "segmentation = \"tolerance\"",
            "segmentation = \"pca\"",
        ));
        assert!(message.contains("unknown variant `pca`"), "{message}");
        let (_, message) = toml_error(&edit("cell = 0.3\n", ""));
        assert!(message.contains("missing field `cell`"), "{message}");
        let (line, _) = toml_error(&edit("dims = [3, 2, 2]", "dims = [3, 2, 2"));
        assert!(line > 1);
        let version = |text: &str| match parse(text) {
            Err(e @ SimError::LiModelVersion { .. }) => e.to_string(),
            other => panic!("{other:?}"),
        };
        let err = version(&edit("version = 1", "version = 2"));
        assert!(
            err.contains("`version = 2`") && err.contains("version = 1"),
            "{err}"
        );
        let err = version("name = \"a scenario?\"\n");
        assert!(err.contains("`format = (missing)`"), "{err}");
        assert!(LiModel::read(Path::new("/nonexistent/model.toml")).is_err());
    }

    /// The tables: the bins' own moments, the CDF's bins, and the sampler built from them.
    #[test]
    fn tables_from_samples_and_from_a_cdf() {
        let t = ModelTable::of_samples("x", &[0.0, 1.0, 1.0, 3.0]).unwrap();
        assert_eq!((t.lo, t.hi, t.counts.len()), (0.0, 3.0, BINS));
        assert_eq!(t.counts.iter().sum::<u32>(), 4);
        assert!(ModelTable::of_samples("x", &[2.0, 2.0]).is_err());
        // Uniform on [0, 2]: mean 1, median 1, sd 2/√12.
        let u = ModelTable::of_cdf(0.0, 2.0, |x| (x / 2.0).clamp(0.0, 1.0));
        assert!(u.counts.iter().all(|&c| c == 15_625_000), "{:?}", u.counts);
        let m = u.moments();
        assert!((m.mean - 1.0).abs() < 1e-9 && (m.median - 1.0).abs() < 1e-9);
        assert!((m.sd - 2.0 / 12f64.sqrt()).abs() < 1e-9);
        // The probability above hi goes to the last bin.
        let e = ModelTable::of_cdf(0.0, 1.0, |x| 1.0 - (-x).exp());
        let total: u64 = e.counts.iter().map(|&c| u64::from(c)).sum();
        assert!((total as i64 - 1_000_000_000).abs() < 64, "{total}");
        let table = e.table().unwrap();
        assert_eq!(table.bins(), BINS);
        assert_eq!(table.cdf.last().copied(), Some(1.0));
    }

    /// The grid is used as it is inside the world, refused outside it, and obstacle cells are
    /// emptied.
    #[test]
    fn grids_are_placed_in_the_world_or_refused() {
        use crate::space::Shape3;
        let g = sample().density;
        let (lo, hi) = g.bounds();
        assert_eq!(lo, g.origin);
        assert!(
            (hi[1] - 0.8).abs() < 1e-6 && (hi[2] - 0.6).abs() < 1e-6,
            "{hi:?}"
        );
        let world = ([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]);
        let d = g.placed(world, &[]).unwrap();
        assert_eq!((d.dims, d.cell), (g.dims, g.cell));
        assert_eq!(d.weights[0], 1, "an unvisited free cell keeps the floor");
        assert_eq!(d.weights[1..], g.weights[1..]);
        assert_eq!(
            g.placed(([0.0; 3], [1.0; 3]), &[]).unwrap_err(),
            g.bounds(),
            "origin x -0.1 is outside"
        );
        let ball = BeeObstacle::new(
            0,
            "ball",
            Shape3::Sphere {
                center: [0.35, 0.35, 0.15],
                radius: 0.05,
            },
            true,
        );
        let d = g.placed(world, &[ball]).unwrap();
        assert_eq!(d.weights[..2], [1, 0], "the ball's cell");
        assert_eq!(d.weights[2..], g.weights[2..]);
    }
}
