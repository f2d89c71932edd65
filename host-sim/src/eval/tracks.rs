//! Trajectories to evaluate: measured tracks (`id,time,x,y,z` CSV) or a simulation's, cut
//! into runs of consecutive frames.

use std::collections::BTreeMap;
use std::path::Path;

use crate::{Result, SimError};

/// The header of a track file.
pub const TRACKS_HEADER: &str = "id,time,x,y,z";

/// Positions of tracked insects on a common frame grid `t = t0 + k·dt`.
#[derive(Clone, Debug, PartialEq)]
pub struct Tracks {
    /// The frame interval Δt_s (s).
    pub dt: f64,
    /// Per insect id, its positions by frame index, increasing.
    pub by_id: BTreeMap<u64, Vec<(i64, [f64; 3])>>,
}

impl Tracks {
    /// Tracks from `(id, frame, position)` samples at frame interval `dt`; a repeated
    /// (id, frame) keeps the last sample.
    pub fn from_samples(dt: f64, samples: impl IntoIterator<Item = (u64, i64, [f64; 3])>) -> Self {
        let mut by_id: BTreeMap<u64, BTreeMap<i64, [f64; 3]>> = BTreeMap::new();
        for (id, k, p) in samples {
            by_id.entry(id).or_default().insert(k, p);
        }
        Tracks {
            dt,
            by_id: by_id
                .into_iter()
                .map(|(id, t)| (id, t.into_iter().collect()))
                .collect(),
        }
    }

    /// Reads a track file: the header `id,time,x,y,z`, then one row per insect and time
    /// (any order). The frame interval is `dt` when given, else the smallest positive time
    /// step within a track; every time must then lie on the grid `t0 + k·dt` (within 1 % of
    /// dt), t0 the earliest time.
    ///
    /// # Errors
    ///
    /// The file cannot be read, the header differs, a row has too few or too many fields or
    /// a field that is not a number (line and field named), `dt` is not a positive number
    /// ([`SimError::TrackDt`]), no frame interval can be found,
    /// or a time lies off the grid ([`SimError::TrackTime`]).
    pub fn read_csv(path: &Path, dt: Option<f64>) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| SimError::io("read", path, e))?;
        let mut lines = text.lines().enumerate();
        let Some((_, header)) = lines.next() else {
            return Err(SimError::CsvEmpty { path: path.into() });
        };
        if header.trim() != TRACKS_HEADER {
            return Err(SimError::CsvHeader {
                path: path.into(),
                header: header.into(),
                expected: TRACKS_HEADER,
            });
        }
        const FIELDS: [&str; 5] = ["id", "time", "x", "y", "z"];
        let mut rows = Vec::new();
        for (i, line) in lines {
            let line_no = i + 1;
            if line.trim().is_empty() {
                continue;
            }
            let parts: Vec<&str> = line.split(',').map(str::trim).collect();
            if parts.len() < FIELDS.len() {
                return Err(SimError::CsvMissingField {
                    path: path.into(),
                    line: line_no,
                    field: FIELDS[parts.len()],
                    fields: FIELDS.len(),
                });
            }
            if parts.len() > FIELDS.len() {
                return Err(SimError::CsvExtraFields {
                    path: path.into(),
                    line: line_no,
                    fields: FIELDS.len(),
                });
            }
            let bad = |k: usize| SimError::CsvNumber {
                path: path.into(),
                line: line_no,
                field: FIELDS[k],
                value: parts[k].into(),
            };
            let id: u64 = parts[0].parse().map_err(|_| bad(0))?;
            let mut v = [0.0f64; 4];
            for (k, slot) in v.iter_mut().enumerate() {
                *slot = parts[k + 1]
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| bad(k + 1))?;
            }
            rows.push((line_no, id, v[0], [v[1], v[2], v[3]]));
        }
        let dt = match positive_dt(path, dt)? {
            Some(dt) => dt,
            None => {
                smallest_step(&rows).ok_or_else(|| SimError::TrackInterval { path: path.into() })?
            }
        };
        let t0 = rows.iter().map(|r| r.2).fold(f64::INFINITY, f64::min);
        let mut samples = Vec::with_capacity(rows.len());
        for (line, id, t, p) in rows {
            let u = (t - t0) / dt;
            let k = u.round();
            if (u - k).abs() > 0.01 {
                return Err(SimError::TrackTime {
                    path: path.into(),
                    line,
                    time: t,
                    dt,
                });
            }
            samples.push((id, k as i64, p));
        }
        Ok(Tracks::from_samples(dt, samples))
    }

    /// The tracks at `path`: a run folder (`swarm run`'s output: its recorded frames, taken
    /// as consecutive frames at interval 1, since every metric is z-scored and so free of
    /// units) or a track file ([`Tracks::read_csv`], interval `dt` or inferred).
    ///
    /// # Errors
    ///
    /// What [`RunDir::open`](crate::output::RunDir::open) or [`Tracks::read_csv`] refuse; a
    /// `dt` that is not a positive number ([`SimError::TrackDt`]).
    pub fn open(path: &Path, dt: Option<f64>) -> Result<Self> {
        if !path.is_dir() {
            return Self::read_csv(path, dt);
        }
        let dt = positive_dt(path, dt)?;
        let run = crate::output::RunDir::open(path)?;
        let samples = run.frames.iter().enumerate().flat_map(|(k, f)| {
            f.agents
                .iter()
                .map(move |a| (u64::from(a.id), k as i64, a.pos.map(f64::from)))
        });
        Ok(Tracks::from_samples(dt.unwrap_or(1.0), samples))
    }

    /// Every track cut into runs of consecutive frames: (id, first frame, positions).
    pub fn runs(&self) -> Vec<(u64, i64, Vec<[f64; 3]>)> {
        let mut out = Vec::new();
        for (&id, samples) in &self.by_id {
            let mut start = 0;
            for i in 1..=samples.len() {
                if i == samples.len() || samples[i].0 != samples[i - 1].0 + 1 {
                    let run = samples[start..i].iter().map(|s| s.1).collect();
                    out.push((id, samples[start].0, run));
                    start = i;
                }
            }
        }
        out
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.by_id.values().map(Vec::len).sum()
    }

    /// Whether there is no sample.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// `dt` when it is a positive number of seconds (or not given), else [`SimError::TrackDt`]
/// for the tracks at `path`.
fn positive_dt(path: &Path, dt: Option<f64>) -> Result<Option<f64>> {
    match dt {
        Some(dt) if !(dt.is_finite() && dt > 0.0) => Err(SimError::TrackDt {
            path: path.into(),
            dt,
        }),
        _ => Ok(dt),
    }
}

/// The smallest positive time step between two samples of one id.
fn smallest_step(rows: &[(usize, u64, f64, [f64; 3])]) -> Option<f64> {
    let mut times: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
    for r in rows {
        times.entry(r.1).or_default().push(r.2);
    }
    times
        .values_mut()
        .flat_map(|t| {
            t.sort_by(f64::total_cmp);
            t.windows(2).map(|w| w[1] - w[0]).collect::<Vec<_>>()
        })
        .filter(|d| *d > 0.0)
        .min_by(f64::total_cmp)
}
