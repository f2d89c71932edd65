//! `summary.json` (what a run did, in numbers) and `run.log` (what happened, in words).

use std::collections::BTreeMap;
use std::fmt::Display;
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::frames::{AgentSample, Frame};
use super::json::{read_json, write_json};
use crate::engine::StateNames;
use crate::{Result, SimError};

/// One agent group of the scenario.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GroupSummary {
    /// Group name from the scenario.
    pub name: String,
    /// Model ("ant", "bee", ...).
    pub model: String,
    /// Number of agents.
    pub count: u32,
    /// Scalar type the controllers ran with ("f32" or "fixed").
    pub scalar: String,
}

/// Per-state agent counts at one step.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StateCounts {
    /// The step.
    pub step: u32,
    /// State name → number of agents in it (motion states and labels, see [`state_counts_of`]).
    pub counts: BTreeMap<String, u32>,
}

/// The numbers of a run, written as pretty `summary.json`.
///
/// Every field has a default, so a file missing some fields (an older version) still reads.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Summary {
    /// Scenario name.
    pub scenario: String,
    /// Random seed.
    pub seed: u64,
    /// Steps simulated.
    pub steps: u32,
    /// Total agents.
    pub agents: u32,
    /// The agent groups.
    pub groups: Vec<GroupSummary>,
    /// Backend ("cpu" or "gpu").
    pub backend: String,
    /// The GPU adapter of the `gpu` backend.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub adapter: Option<String>,
    /// Worker threads.
    pub threads: u32,
    /// Wall-clock time of the simulation loop, seconds.
    pub wall_seconds: f64,
    /// `agents · steps / wall_seconds`.
    pub agent_steps_per_s: f64,
    /// Food items delivered, by nest name.
    pub deliveries_per_nest: BTreeMap<String, u64>,
    /// `(step, total deliveries so far)` samples.
    pub deliveries_over_time: Vec<(u32, u64)>,
    /// The distance below which two agents count as colliding (world units).
    pub collision_distance: f32,
    /// Agent pairs closer than `collision_distance`, summed over the recorded steps.
    pub collisions: u64,
    /// Smallest distance between two agents seen at a recorded step (`null` with < 2 agents).
    pub min_distance: Option<f32>,
    /// Per-state counts over time.
    pub state_counts: Vec<StateCounts>,
    /// Model-specific metrics.
    pub extra: serde_json::Map<String, serde_json::Value>,
}

impl Summary {
    /// Writes pretty JSON (with a final newline) to `path`, whole or not at all.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<()> {
        write_json(path.as_ref(), self)
    }

    /// Reads a `summary.json`.
    pub fn read(path: impl AsRef<Path>) -> Result<Self> {
        read_json(path.as_ref())
    }

    /// Adds the pair statistics of one recorded frame: collisions are summed, the minimum
    /// distance kept.
    pub fn add_pair_stats(&mut self, s: PairStats) {
        self.collisions += s.collisions;
        self.min_distance = match (self.min_distance, s.min_distance) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
    }
}

/// Counts the agents of `frame` per motion state and per label under the model's `names`:
/// every name is present (0 if unused); a code past the names appears as `motion<N>` /
/// `label<N>`; a model without label (or motion) names has none counted.
pub fn state_counts_of(frame: &Frame, names: StateNames) -> StateCounts {
    let mut counts = BTreeMap::new();
    for (names, prefix, code_of) in [
        (
            names.motions,
            "motion",
            (|a: &AgentSample| a.motion) as fn(&AgentSample) -> u8,
        ),
        (names.labels, "label", |a: &AgentSample| a.label),
    ] {
        if names.is_empty() {
            continue;
        }
        let mut n = [0u32; 256];
        for a in &frame.agents {
            n[code_of(a) as usize] += 1;
        }
        for (code, &k) in n.iter().enumerate() {
            match names.get(code) {
                Some(name) => *counts.entry((*name).to_string()).or_insert(0) += k,
                None if k > 0 => *counts.entry(format!("{prefix}{code}")).or_insert(0) += k,
                None => {}
            }
        }
    }
    StateCounts {
        step: frame.step,
        counts,
    }
}

/// Close-pair statistics of one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairStats {
    /// Pairs closer than the collision distance.
    pub collisions: u64,
    /// Exact smallest distance between two agents (`None` with fewer than two agents with
    /// finite positions).
    pub min_distance: Option<f32>,
}

/// Counts the agent pairs of `frame` closer than `collision_distance` (strictly) and finds the
/// exact minimum inter-agent distance, in O(n log n) with a sorted uniform grid. Agents with
/// non-finite positions are ignored.
pub fn pair_stats(frame: &Frame, collision_distance: f32) -> PairStats {
    let pts: Vec<[f64; 3]> = frame
        .agents
        .iter()
        .filter(|a| a.pos.iter().all(|c| c.is_finite()))
        .map(|a| a.pos.map(f64::from))
        .collect();
    let n = pts.len();
    if n < 2 {
        return PairStats::default();
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext: Vec<f64> = (0..3).map(|k| hi[k] - lo[k]).collect();
    let dims = ext.iter().filter(|&&e| e > 0.0).count().max(1) as f64;
    let vol: f64 = ext
        .iter()
        .filter(|&&e| e > 0.0)
        .product::<f64>()
        .max(f64::MIN_POSITIVE);
    // Typical nearest-neighbour spacing, and never a grid finer than 2^20 cells per axis.
    let spacing = (vol / n as f64).powf(1.0 / dims);
    let max_ext = ext.iter().cloned().fold(0.0, f64::max);
    let d = f64::from(collision_distance.max(0.0));
    let d2 = d * d;
    let mut cell = d.max(spacing).max(max_ext / f64::from(1u32 << 20));
    if cell <= 0.0 || !cell.is_finite() {
        cell = 1.0;
    }
    let mut collisions = 0u64;
    let mut counted = false;
    loop {
        let (c, best2) = grid_pass(&pts, &lo, cell, if counted { None } else { Some(d2) });
        if !counted {
            collisions = c;
            counted = true;
        }
        // Every pair closer than `cell` has been seen, so a minimum below it is exact.
        if best2 <= cell * cell || cell > max_ext * 2.0 {
            return PairStats {
                collisions,
                min_distance: Some(best2.sqrt() as f32),
            };
        }
        cell *= 4.0;
    }
}

/// One pass over a grid of `cell`-sized cells: counts pairs with squared distance < `d2` (when
/// given; such pairs are all found when `d ≤ cell`) and returns the smallest squared distance
/// among the pairs in neighbouring cells.
fn grid_pass(pts: &[[f64; 3]], lo: &[f64; 3], cell: f64, d2: Option<f64>) -> (u64, f64) {
    const B: u32 = 21;
    let key_of =
        |c: [i64; 3]| -> u64 { ((c[0] as u64) << (2 * B)) | ((c[1] as u64) << B) | (c[2] as u64) };
    let coords = |p: &[f64; 3]| -> [i64; 3] {
        [0, 1, 2].map(|k| (((p[k] - lo[k]) / cell).floor() as i64).clamp(0, (1 << B) - 2))
    };
    let mut order: Vec<(u64, u32)> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| (key_of(coords(p)), i as u32))
        .collect();
    order.sort_unstable();
    // Cell starts.
    let mut cells: Vec<(u64, usize, usize)> = Vec::new();
    let mut s = 0;
    while s < order.len() {
        let k = order[s].0;
        let mut e = s + 1;
        while e < order.len() && order[e].0 == k {
            e += 1;
        }
        cells.push((k, s, e));
        s = e;
    }
    let find = |k: u64| cells.binary_search_by_key(&k, |c| c.0).ok();
    let mut count = 0u64;
    let mut best2 = f64::INFINITY;
    let mut visit = |a: usize, b: usize| {
        let (p, q) = (&pts[a], &pts[b]);
        let dd = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
        if dd < best2 {
            best2 = dd;
        }
        if let Some(d2) = d2
            && dd < d2
        {
            count += 1;
        }
    };
    for &(k, s, e) in &cells {
        let c = [
            (k >> (2 * B)) as i64,
            ((k >> B) & ((1 << B) - 1)) as i64,
            (k & ((1 << B) - 1)) as i64,
        ];
        // Pairs inside the cell.
        for i in s..e {
            for j in i + 1..e {
                visit(order[i].1 as usize, order[j].1 as usize);
            }
        }
        // Pairs with the neighbouring cells of larger key (each cell pair once).
        for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                for dz in -1..=1i64 {
                    let nc = [c[0] + dx, c[1] + dy, c[2] + dz];
                    if nc.iter().any(|&v| v < 0) {
                        continue;
                    }
                    let nk = key_of(nc);
                    if nk <= k {
                        continue;
                    }
                    if let Some(ci) = find(nk) {
                        let (_, s2, e2) = cells[ci];
                        for i in s..e {
                            for j in s2..e2 {
                                visit(order[i].1 as usize, order[j].1 as usize);
                            }
                        }
                    }
                }
            }
        }
    }
    (count, best2)
}

/// The run log: one line per event, each prefixed with the seconds since the log was opened and
/// flushed at once, so the file can be followed while a run goes on. (The log is the one output
/// that grows in place rather than appearing whole.)
#[derive(Debug)]
pub struct RunLog {
    path: PathBuf,
    file: File,
    start: Instant,
}

impl RunLog {
    /// Starts a new log at `path`, replacing an old one.
    pub fn create(path: impl AsRef<Path>) -> Result<Self> {
        Self::open(path.as_ref(), false)
    }

    /// Opens `path` for appending (created if missing).
    pub fn append(path: impl AsRef<Path>) -> Result<Self> {
        Self::open(path.as_ref(), true)
    }

    fn open(path: &Path, append: bool) -> Result<Self> {
        let file = OpenOptions::new()
            .create(true)
            .write(true)
            .append(append)
            .truncate(!append)
            .open(path)
            .map_err(|e| SimError::io("opening", path, e))?;
        Ok(Self {
            path: path.to_path_buf(),
            file,
            start: Instant::now(),
        })
    }

    /// The log's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends `[   12.345s] msg` and a newline, flushed. Multi-line messages get the prefix on
    /// their first line only.
    pub fn line(&mut self, msg: impl Display) -> Result<()> {
        let t = self.start.elapsed().as_secs_f64();
        let text = format!("[{t:>9.3}s] {msg}\n");
        self.file
            .write_all(text.as_bytes())
            .and_then(|()| self.file.flush())
            .map_err(|e| SimError::io("writing", &self.path, e))
    }
}

#[cfg(test)]
mod tests {
    use super::super::frames::AgentSample;
    use super::*;
    use crate::output::testing::{read_error, round_trip, temp_path};

    fn full() -> Summary {
        let mut extra = serde_json::Map::new();
        extra.insert("trail_straightness".into(), serde_json::json!(1.125));
        extra.insert("notes".into(), serde_json::json!(["a", {"b": 2}]));
        Summary {
            scenario: "xiang-fig7a".into(),
            seed: 42,
            steps: 3000,
            agents: 500,
            groups: vec![GroupSummary {
                name: "colony".into(),
                model: "ant".into(),
                count: 500,
                scalar: "f32".into(),
            }],
            backend: "cpu".into(),
            adapter: None,
            threads: 2,
            wall_seconds: 1.5,
            agent_steps_per_s: 1.0e6,
            deliveries_per_nest: [("nest0".to_string(), 17u64)].into_iter().collect(),
            deliveries_over_time: vec![(0, 0), (100, 3), (200, 17)],
            collision_distance: 0.5,
            collisions: 12,
            min_distance: Some(0.25),
            state_counts: vec![StateCounts {
                step: 0,
                counts: [("basic".to_string(), 500u32)].into_iter().collect(),
            }],
            extra,
        }
    }

    #[test]
    fn json_round_trip() {
        let (_dir, p) = temp_path("summary.json");
        let s = full();
        let text = round_trip(&p, &s, Summary::write, Summary::read);
        assert!(text.ends_with("}\n"));
        assert!(text.contains("\n  \"scenario\": \"xiang-fig7a\""), "{text}");
        // None minimum distance is null and reads back.
        let s2 = Summary {
            min_distance: None,
            ..s
        };
        let text = round_trip(&p, &s2, Summary::write, Summary::read);
        assert!(text.contains("\"min_distance\": null"), "{text}");
    }

    #[test]
    fn partial_json_reads_with_defaults_and_bad_json_names_file() {
        let (_dir, p) = temp_path("summary.json");
        std::fs::write(&p, r#"{"scenario": "x", "steps": 3}"#).unwrap();
        let s = Summary::read(&p).unwrap();
        assert_eq!((s.scenario.as_str(), s.steps, s.agents), ("x", 3, 0));
        let msg = read_error(&p, r#"{"steps": "many"}"#, Summary::read);
        assert!(
            msg.contains("summary.json") && msg.contains("line 1"),
            "{msg}"
        );
    }

    fn frame(pos: &[[f32; 3]]) -> Frame {
        Frame {
            step: 0,
            agents: pos
                .iter()
                .enumerate()
                .map(|(i, &p)| AgentSample {
                    id: i as u32,
                    pos: p,
                    ..Default::default()
                })
                .collect(),
        }
    }

    fn brute(f: &Frame, d: f32) -> (u64, Option<f32>) {
        let mut c = 0;
        let mut m = f64::INFINITY;
        for i in 0..f.agents.len() {
            for j in i + 1..f.agents.len() {
                let p = f.agents[i].pos.map(f64::from);
                let q = f.agents[j].pos.map(f64::from);
                let dd = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
                if dd < f64::from(d) * f64::from(d) {
                    c += 1;
                }
                m = m.min(dd);
            }
        }
        (c, m.is_finite().then(|| m.sqrt() as f32))
    }

    #[test]
    fn pair_stats_match_brute_force() {
        let mut s = 99u32;
        let mut rnd = move || {
            s = s.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (s >> 8) as f32 / (1u32 << 24) as f32
        };
        for (n, scale, d, three) in [
            (300, 100.0, 2.0, false),
            (300, 100.0, 0.0, false),
            (200, 10.0, 1.5, true),
            (50, 1000.0, 0.1, true),
            (2, 1.0e4, 1.0, false),
        ] {
            let pts: Vec<[f32; 3]> = (0..n)
                .map(|_| {
                    [
                        rnd() * scale,
                        rnd() * scale,
                        if three { rnd() * scale } else { 0.0 },
                    ]
                })
                .collect();
            let f = frame(&pts);
            let got = pair_stats(&f, d);
            let (c, m) = brute(&f, d);
            assert_eq!(got.collisions, c, "n={n} d={d}");
            assert_eq!(got.min_distance, m, "n={n} d={d}");
        }
        assert_eq!(pair_stats(&frame(&[[0.0; 3]]), 1.0), PairStats::default());
        // Coincident agents.
        let f = frame(&[[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [5.0, 1.0, 0.0]]);
        assert_eq!(
            pair_stats(&f, 1.0),
            PairStats {
                collisions: 1,
                min_distance: Some(0.0)
            }
        );
        let mut s = Summary::default();
        s.add_pair_stats(pair_stats(&f, 1.0));
        s.add_pair_stats(PairStats {
            collisions: 2,
            min_distance: Some(3.0),
        });
        assert_eq!((s.collisions, s.min_distance), (3, Some(0.0)));
    }

    #[test]
    fn state_counts() {
        let mut f = frame(&[[0.0; 3]; 5]);
        f.agents[0].motion = 0;
        f.agents[1].label = 1;
        f.agents[2].label = 2;
        f.agents[3].motion = 7;
        let names = StateNames {
            labels: &["nothing", "food", "nest"],
            motions: &["stop", "basic", "neighbors", "environment"],
        };
        let c = state_counts_of(&f, names).counts;
        assert_eq!(c["stop"], 5 - 1);
        assert_eq!(c["motion7"], 1);
        assert_eq!(c["basic"], 0);
        assert_eq!(c["nothing"], 3);
        assert_eq!(c["food"], 1);
        assert_eq!(c["nest"], 1);
        assert_eq!(c["environment"], 0);
        assert_eq!(c.len(), 8);
        // A model without labels counts none; an unnamed label code with agents is counted.
        let motions_only = StateNames {
            labels: &[],
            motions: &["cruising", "avoiding"],
        };
        let c = state_counts_of(&f, motions_only).counts;
        assert_eq!(
            c.keys().collect::<Vec<_>>(),
            ["avoiding", "cruising", "motion7"]
        );
        let one_label = StateNames {
            labels: &["calm"],
            motions: &[],
        };
        let c = state_counts_of(&f, one_label).counts;
        assert_eq!((c["calm"], c["label1"], c["label2"]), (3, 1, 1));
    }

    #[test]
    fn run_log_appends_flushed_lines() {
        let (_dir, p) = temp_path("run.log");
        let mut log = RunLog::create(&p).unwrap();
        log.line("start").unwrap();
        log.line(format_args!("step {}", 10)).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2);
        assert!(lines[0].ends_with("s] start") && lines[1].ends_with("s] step 10"));
        drop(log);
        RunLog::append(&p).unwrap().line("more").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap().lines().count(), 3);
        RunLog::create(&p).unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "");
    }
}
