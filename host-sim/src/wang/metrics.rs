//! The measures of wang2014 a run reports in `summary.json`: the share of insects minimum
//! distance enforcement displaced per frame (Table 1's last row), polarisation, the speed the
//! insects keep and how far they spread (the noise comparisons of Figs. 11 and 13: curl noise
//! keeps its speed and spreads, Perlin noise gathers the insects at its sinks, random noise
//! makes them vibrate in place), and the world's corrections.

use serde_json::{Map, Value, json};

use super::sim::Counts;

/// Running totals over a run, one [`Metrics::tick`] per step.
#[derive(Clone, Debug, Default)]
pub struct Metrics {
    /// Steps seen.
    pub steps: u64,
    /// Σ over steps of the share of insects MDE displaced (%).
    pub mde_percent_sum: f64,
    /// The largest share of one step (%).
    pub mde_percent_max: f64,
    /// Σ polarisation.
    pub polarisation_sum: f64,
    /// Polarisation at the last step.
    pub polarisation_last: f64,
    /// Mean speed after the first step.
    pub speed_first: Option<f64>,
    /// Mean speed at the last step.
    pub speed_last: f64,
    /// Positions at the start, by id.
    pub start: Vec<[f64; 3]>,
    /// Mean squared displacement from the start at the last step (m²).
    pub msd_last: f64,
    /// World corrections and MDE pushes since the start.
    pub counts: Counts,
}

pub use crate::eval::frame_polarisation as polarisation;

/// The mean speed ‖V‖.
pub fn mean_speed(vel: &[[f64; 3]]) -> f64 {
    let sum: f64 = vel
        .iter()
        .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        .sum();
    sum / vel.len().max(1) as f64
}

/// The mean squared displacement between `a` and `b` (same length, by id).
pub fn msd(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>())
        .sum();
    sum / a.len().max(1) as f64
}

impl Metrics {
    /// Starts from the insects' positions (by id).
    pub fn new(start: Vec<[f64; 3]>) -> Self {
        Metrics {
            start,
            ..Metrics::default()
        }
    }

    /// Counts one step: its counts, and the insects' positions and velocities after it.
    pub fn tick(&mut self, c: Counts, pos: &[[f64; 3]], vel: &[[f64; 3]]) {
        let n = pos.len().max(1) as f64;
        let share = 100.0 * c.pushed as f64 / n;
        self.steps += 1;
        self.mde_percent_sum += share;
        self.mde_percent_max = self.mde_percent_max.max(share);
        let phi = polarisation(vel);
        self.polarisation_sum += phi;
        self.polarisation_last = phi;
        let speed = mean_speed(vel);
        self.speed_first.get_or_insert(speed);
        self.speed_last = speed;
        self.msd_last = msd(pos, &self.start);
        self.counts += c;
    }

    /// The summary's fields.
    pub fn to_json(&self) -> Map<String, Value> {
        let steps = self.steps.max(1) as f64;
        let first = self.speed_first.unwrap_or(0.0);
        let ratio = if first > 0.0 {
            self.speed_last / first
        } else {
            0.0
        };
        let agent_steps = self.steps as f64 * self.start.len().max(1) as f64;
        let v = json!({
            "mde_percent_mean": self.mde_percent_sum / steps,
            "mde_percent_max": self.mde_percent_max,
            "polarisation_mean": self.polarisation_sum / steps,
            "polarisation_last": self.polarisation_last,
            "speed_first": first,
            "speed_last": self.speed_last,
            "speed_ratio": ratio,
            "msd_last": self.msd_last,
            "world_corrections_obstacle": self.counts.obstacle,
            "world_corrections_bounds": self.counts.bounds,
            "world_corrections_per_agent_step":
                (self.counts.obstacle + self.counts.bounds) as f64 / agent_steps,
            "mde_pushed": self.counts.pushed,
        });
        match v {
            Value::Object(m) => m,
            _ => Map::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polarisation_is_one_when_aligned_and_near_zero_when_opposed() {
        assert!((polarisation(&[[1.0, 0.0, 0.0], [3.0, 0.0, 0.0]]) - 1.0).abs() < 1e-12);
        assert!(polarisation(&[[1.0, 0.0, 0.0], [-2.0, 0.0, 0.0]]).abs() < 1e-12);
        assert_eq!(polarisation(&[]), 0.0);
        assert!((mean_speed(&[[3.0, 4.0, 0.0], [0.0, 0.0, 1.0]]) - 3.0).abs() < 1e-12);
        assert!((msd(&[[1.0, 0.0, 0.0]], &[[0.0, 0.0, 0.0]]) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_mde_share_is_a_mean_percentage_per_step() {
        let mut m = Metrics::new(vec![[0.0; 3]; 4]);
        let v = [[1.0, 0.0, 0.0]; 4];
        let c = |pushed| Counts {
            pushed,
            ..Counts::default()
        };
        m.tick(c(1), &[[0.0; 3]; 4], &v);
        m.tick(c(0), &[[0.0; 3]; 4], &v);
        let j = m.to_json();
        assert_eq!(j["mde_percent_mean"], 12.5);
        assert_eq!(j["mde_percent_max"], 25.0);
        assert_eq!(j["polarisation_last"], 1.0);
    }
}
