//! Ant scenario (PLACEHOLDER until `swarm_core::ant` lands): a few agents random-walk with
//! neighbour repulsion, exercising rand, sqrt, exp, sin/cos, atan2 of the scalar.

use crate::{Sink, Word, uniform};
use swarm_core::{Rect, StepCtx, Vec2, rand};

/// Agents in the scenario.
pub const AGENTS: usize = 6;
/// Ticks simulated.
pub const STEPS: u32 = 8;

/// Runs the scenario, emitting every decision word.
pub fn run<S: Word>(out: &mut impl Sink) {
    let bounds = Rect::new(Vec2::<S>::from_f32(0.0, 0.0), Vec2::from_f32(40.0, 40.0));
    let mut pos = [Vec2::<S>::zero(); AGENTS];
    let mut head = [S::ZERO; AGENTS];
    for i in 0..AGENTS {
        pos[i] = Vec2::new(uniform(i as u32, 0, 5.0, 35.0), uniform(i as u32, 1, 5.0, 35.0));
        head[i] = uniform(i as u32, 2, -3.0, 3.0);
    }
    for step in 0..STEPS {
        let prev = pos;
        for i in 0..AGENTS {
            let ctx = StepCtx { seed: 7, agent: i as u32, step };
            let turn = rand::angle::<S>(ctx, rand::stream::ANT_TURN, S::from_f32(0.5236));
            let mut h = Vec2::from_angle(head[i] + turn);
            for (j, q) in prev.iter().enumerate() {
                if j == i {
                    continue;
                }
                let d = prev[i] - *q;
                let r = d.length();
                if r < S::from_f32(10.0) && r > S::ZERO {
                    let w = (-r * S::from_f32(0.3)).exp();
                    h.x += d.x / r * w;
                    h.y += d.y / r * w;
                }
            }
            head[i] = h.y.atan2(h.x);
            pos[i] = bounds.clamp(prev[i] + Vec2::from_angle(head[i]) * S::from_f32(1.5));
            out.vec2(pos[i]);
            out.scalar(head[i]);
        }
    }
}
