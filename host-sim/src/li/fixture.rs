//! Synthetic tracks standing in for the paper's data (li2015 spec §2.1 and L-T16; **they are
//! synthetic**: the Puckett-Kelley-Ouellette midge data the paper used are not public).
//!
//! The process, per insect: a start uniform in the cube `[0, side]³` and a uniform direction;
//! then segment after segment, each of a length drawn from the generalised gamma of
//! `segment_length_mm` (the paper's mean 14.57 mm, median 7.22 mm, sd 19.01 mm) and turned
//! from the previous one by |θ|, θ ~ Normal(2.34°, 40.02°) (the paper's mean and sd), at a
//! uniform azimuth ([`swarm_core::li::waypoint::direction`], the model's own turn); the
//! insect flies the polyline at a constant speed, sampled at `fps`, each sample with
//! Gaussian noise of sd `noise` per coordinate. It is not confined to the cube. Randomness
//! is counter-based ([`swarm_core::rand::rand`]): the same seed gives the same tracks.

use swarm_core::Vec3;
use swarm_core::li::waypoint::direction;
use swarm_core::rand::rand;

use crate::eval::Tracks;

/// The parameters of the synthetic process.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fixture {
    /// Number of insects (tracks).
    pub insects: u32,
    /// Samples per track.
    pub frames: u32,
    /// Flight speed (m/s): ours 0.15, the data's ~14.6 mm per 0.1 s (spec §1.3).
    pub speed: f64,
    /// Samples per second (the data's 100).
    pub fps: f64,
    /// Measurement noise, sd per coordinate (m).
    pub noise: f64,
    /// Side of the start cube (m): the laboratory's 0.91 m.
    pub side: f64,
    /// Seed.
    pub seed: u32,
}

impl Default for Fixture {
    /// 100 insects × 2,000 samples at 0.15 m/s and 100 Hz, 0.2 mm noise, seed 1.
    fn default() -> Self {
        Fixture {
            insects: 100,
            frames: 2000,
            speed: 0.15,
            fps: 100.0,
            noise: 0.0002,
            side: 0.91,
            seed: 1,
        }
    }
}

/// A stream of uniform numbers in (0, 1) for one insect.
struct Draws {
    seed: u32,
    insect: u32,
    n: u32,
}

impl Draws {
    fn uniform(&mut self) -> f64 {
        self.n = self.n.wrapping_add(1);
        (f64::from(rand(self.seed, self.insect, self.n, 0x4C49)) + 0.5) / 4_294_967_296.0
    }

    /// A standard normal (Box-Muller).
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }

    /// Gamma(shape, 1) by Marsaglia and Tsang (2000), with Gamma(a) = Gamma(a + 1)·U^{1/a}
    /// for a shape below 1.
    fn gamma(&mut self, shape: f64) -> f64 {
        if shape < 1.0 {
            let boost = self.uniform().powf(1.0 / shape);
            return self.gamma(shape + 1.0) * boost;
        }
        let d = shape - 1.0 / 3.0;
        let c = 1.0 / (9.0 * d).sqrt();
        loop {
            let x = self.normal();
            let v = (1.0 + c * x).powi(3);
            if v > 0.0 && self.uniform().ln() < 0.5 * x * x + d - d * v + d * v.ln() {
                return d * v;
            }
        }
    }
}

/// A segment length (mm) of the fixture: the generalised gamma X = 37.6463·Y^{1/1.276084},
/// Y ~ Gamma(0.369292, 1) (SciPy `gengamma(a=0.369292, c=1.276084, scale=37.6463)`), whose
/// mean, median and sd are the paper's 14.57, 7.22 and 19.01 mm (spec §2.1, L-T2).
fn segment_length_mm(d: &mut Draws) -> f64 {
    37.6463 * d.gamma(0.369292).powf(1.0 / 1.276084)
}

/// A turning angle (radians) of the fixture: Normal(2.34°, 40.02°) wrapped to (−π, π].
fn turn(d: &mut Draws) -> f64 {
    let t = (2.34 + 40.02 * d.normal()).to_radians();
    let w = t.rem_euclid(std::f64::consts::TAU);
    if w > std::f64::consts::PI {
        w - std::f64::consts::TAU
    } else {
        w
    }
}

/// What the process drew, to compare a pipeline's estimates with.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Drawn {
    /// Every segment length drawn (m), in order per insect.
    pub lengths: Vec<f64>,
    /// Every turning angle drawn (radians, signed as drawn).
    pub turns: Vec<f64>,
}

/// `n` segment lengths (mm) of the fixture's distribution, for checking it (L-T2).
pub fn segment_lengths_mm(seed: u32, n: usize) -> Vec<f64> {
    let mut d = Draws {
        seed,
        insect: u32::MAX,
        n: 0,
    };
    (0..n).map(|_| segment_length_mm(&mut d)).collect()
}

/// `n` turning angles (radians, signed) of the fixture's distribution.
pub fn turning_angles(seed: u32, n: usize) -> Vec<f64> {
    let mut d = Draws {
        seed,
        insect: u32::MAX - 1,
        n: 0,
    };
    (0..n).map(|_| turn(&mut d)).collect()
}

/// The synthetic tracks of `f` (ids 0.., frame k at time k/fps) and what was drawn.
pub fn synthetic_tracks(f: &Fixture) -> (Tracks, Drawn) {
    let mut drawn = Drawn::default();
    let mut samples = Vec::with_capacity(f.insects as usize * f.frames as usize);
    let step = f.speed / f.fps;
    for insect in 0..f.insects {
        let mut d = Draws {
            seed: f.seed,
            insect,
            n: 0,
        };
        let mut pos = [0, 1, 2].map(|_| d.uniform() * f.side);
        let unit = |d: &mut Draws| {
            let z = d.uniform() * 2.0 - 1.0;
            let phi = (d.uniform() * 2.0 - 1.0) * std::f64::consts::PI;
            direction(Vec3::<f32>::zero(), 0.0, phi as f32, z as f32)
        };
        let mut heading = unit(&mut d);
        let mut left = segment_length_mm(&mut d) / 1000.0;
        drawn.lengths.push(left);
        for k in 0..f.frames {
            let noisy = pos.map(|x| x + f.noise * d.normal());
            samples.push((u64::from(insect), i64::from(k), noisy));
            // Fly `step` along the polyline, turning at each vertex.
            let mut go = step;
            while go > left {
                pos = advance(pos, heading, left);
                go -= left;
                let theta = turn(&mut d);
                let phi = (d.uniform() * 2.0 - 1.0) * std::f64::consts::PI;
                heading = direction(heading, theta as f32, phi as f32, 0.0);
                drawn.turns.push(theta);
                left = segment_length_mm(&mut d) / 1000.0;
                drawn.lengths.push(left);
            }
            pos = advance(pos, heading, go);
            left -= go;
        }
    }
    (Tracks::from_samples(1.0 / f.fps, samples), drawn)
}

/// `pos` moved `by` along `heading`.
fn advance(pos: [f64; 3], heading: Vec3<f32>, by: f64) -> [f64; 3] {
    let h = [heading.x, heading.y, heading.z];
    [0, 1, 2].map(|i| pos[i] + by * f64::from(h[i]))
}
