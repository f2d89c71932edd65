//! Bee scenario (PLACEHOLDER until `swarm_core::bee` lands): 3-D point agents with a goal
//! spring and SPH-like neighbour repulsion.

use crate::{Sink, Word, uniform};
use swarm_core::Vec3;

/// Agents in the scenario.
pub const AGENTS: usize = 5;
/// Ticks simulated.
pub const STEPS: u32 = 6;

/// Runs the scenario, emitting every decision word.
pub fn run<S: Word>(out: &mut impl Sink) {
    let goal = Vec3::<S>::from_f32(2.0, 1.0, 3.0);
    let dt = S::from_f32(0.05);
    let mut pos = [Vec3::<S>::zero(); AGENTS];
    let mut vel = [Vec3::<S>::zero(); AGENTS];
    for i in 0..AGENTS {
        let k = i as u32;
        pos[i] = Vec3::new(uniform(k, 0, -2.0, 2.0), uniform(k, 1, 0.0, 2.0), uniform(k, 2, -2.0, 2.0));
    }
    for step in 0..STEPS {
        let prev = pos;
        for i in 0..AGENTS {
            let mut f = (goal - prev[i]) * S::from_f32(0.8);
            for (j, q) in prev.iter().enumerate() {
                if j == i {
                    continue;
                }
                let d = prev[i] - *q;
                let r2 = d.dot(d);
                let h2 = S::from_f32(1.0);
                if r2 < h2 {
                    let w = (h2 - r2).powi(3) * S::from_f32(4.0);
                    f = f + d * w;
                }
            }
            let phase = S::from_i32(step as i32) * S::from_f32(0.7) + S::from_i32(i as i32);
            f.y += phase.sin() * S::from_f32(0.2);
            vel[i] = vel[i] + f * dt;
            pos[i] = prev[i] + vel[i] * dt;
            let roll = vel[i].x.atan2(vel[i].z.abs() + S::ONE);
            out.vec3(vel[i]);
            out.scalar(roll);
            out.scalar(vel[i].length());
        }
    }
}
