//! `shaders/rand.wgsl` against `swarm_core::rand`, bit for bit.

use swarm_core::rand::{angle, chance, mix32, rand, stream, unit};
use swarm_core::{Fx, StepCtx};

use super::{FX_EDGES, RANDOM, Rng, check};
use crate::gpu::shaders::{Module, RAND, SCALAR_FX};

/// `rand.wgsl` over `Fx`.
const FX_RAND: &[&Module] = &[&SCALAR_FX, &RAND];

/// A step context and a stream: the pinned ones, small counters (as a run has them) and random
/// words.
fn contexts(seed: u32) -> Vec<[u32; 4]> {
    let mut g = Rng::new(seed);
    let mut v = vec![
        [0, 0, 0, 0],
        [42, 7, 1000, 2],
        [u32::MAX, u32::MAX, u32::MAX, u32::MAX],
        [0x9e37_79b9, 0, 0, 0],
    ];
    v.extend((0..RANDOM).map(|i| {
        if i % 2 == 0 {
            [g.next(), g.next(), g.next(), g.next()]
        } else {
            [
                g.below(100),
                g.below(100_000),
                g.below(1_000_000),
                g.below(0x22),
            ]
        }
    }));
    v
}

fn ctx([seed, agent, step]: [u32; 3]) -> StepCtx {
    StepCtx { seed, agent, step }
}

#[test]
fn streams() {
    check(
        "the RAND_ stream constants",
        FX_RAND,
        "put(0u, RAND_ANT_STOP); put(1u, RAND_ANT_TURN); put(2u, RAND_ANT_FALLBACK);
         put(3u, RAND_ANT_SIDE); put(4u, RAND_BEE_PHASE); put(5u, RAND_BEE_PHASE_BASE);",
        &[[0]],
        |_| {
            [
                stream::ANT_STOP,
                stream::ANT_TURN,
                stream::ANT_FALLBACK,
                stream::ANT_SIDE,
                stream::BEE_PHASE,
                stream::BEE_PHASE_BASE,
            ]
        },
    );
}

#[test]
fn mix32_words() {
    let mut g = Rng::new(50);
    let mut inputs: Vec<[u32; 1]> = [0u32, 1, 0x8000_0000, u32::MAX, 0x9e37_79b9]
        .iter()
        .map(|&x| [x])
        .collect();
    inputs.extend((0..RANDOM).map(|i| [if i % 2 == 0 { g.next() } else { i as u32 }]));
    check(
        "rand_mix32",
        FX_RAND,
        "put(0u, rand_mix32(u0));",
        &inputs,
        |[x]| [mix32(x)],
    );
}

#[test]
fn rand_words() {
    check(
        "rand_rand",
        FX_RAND,
        "put(0u, rand_rand(u0, u1, u2, u3));",
        &contexts(51),
        |[seed, agent, step, stream]| [rand(seed, agent, step, stream)],
    );
}

#[test]
fn unit_fx() {
    check(
        "rand_unit over Fx",
        FX_RAND,
        "put_i32(0u, rand_unit(u0, u1, u2, u3));",
        &contexts(52),
        |[seed, agent, step, stream]| {
            [unit::<Fx>(ctx([seed, agent, step]), stream).to_bits() as u32]
        },
    );
}

#[test]
fn angle_fx() {
    let mut g = Rng::new(53);
    let inputs: Vec<[u32; 5]> = contexts(53)
        .into_iter()
        .enumerate()
        .map(|(i, [a, b, c, d])| {
            let theta = FX_EDGES.get(i).copied().unwrap_or_else(|| g.fx());
            [a, b, c, d, theta as u32]
        })
        .collect();
    check(
        "rand_angle over Fx",
        FX_RAND,
        "put_i32(0u, rand_angle(u0, u1, u2, u3, a4));",
        &inputs,
        |[seed, agent, step, stream, theta]| {
            let theta = Fx::from_bits(theta as i32);
            [angle::<Fx>(ctx([seed, agent, step]), stream, theta).to_bits() as u32]
        },
    );
}

#[test]
fn chance_fx() {
    // Probabilities anywhere, and the unit value of the draw itself and its neighbours (where
    // the comparison decides).
    let mut g = Rng::new(54);
    let inputs: Vec<[u32; 5]> = contexts(54)
        .into_iter()
        .enumerate()
        .map(|(i, [a, b, c, d])| {
            let u = unit::<Fx>(ctx([a, b, c]), d).to_bits();
            let p = match i % 4 {
                0 => g.fx(),
                1 => FX_EDGES[i / 4 % FX_EDGES.len()],
                _ => u + (g.below(3) as i32) - 1,
            };
            [a, b, c, d, p as u32]
        })
        .collect();
    check(
        "rand_chance over Fx",
        FX_RAND,
        "put_bool(0u, rand_chance(u0, u1, u2, u3, a4));",
        &inputs,
        |[seed, agent, step, stream, p]| {
            let p = Fx::from_bits(p as i32);
            [u32::from(chance::<Fx>(ctx([seed, agent, step]), stream, p))]
        },
    );
}
