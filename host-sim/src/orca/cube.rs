//! The random-cube scenario of the ORCA benchmark (issue 16), built exactly as RVO2-3D's side
//! of it, `scripts/rvo2/random_cube.cc`, builds it: a jittered cubic lattice, and as goals a
//! Fisher-Yates permutation of the lattice points, both from the counter hash [`mix32`].

use swarm_core::Vec3;

/// The agents' radius in the benchmark (RVO2-3D's `Sphere` example).
pub const CUBE_RADIUS: f32 = 1.5;

/// The 32-bit integer finaliser the C++ driver uses (`mix32`, a "lowbias32" hash).
pub fn mix32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// A number in `[0, 1)` with 24 random bits, for agent `i` and component `k` (the driver's
/// `unit`).
pub fn unit(seed: u32, i: u32, k: u32) -> f32 {
    let h = mix32(mix32(seed ^ 0x9e37_79b9) ^ i.wrapping_mul(3).wrapping_add(k));
    (h >> 8) as f32 / 16_777_216.0
}

/// The agents' start positions and goals.
#[derive(Clone, Debug, PartialEq)]
pub struct Cube {
    /// Start of agent `i`: lattice point `i`, jittered.
    pub positions: Vec<Vec3<f32>>,
    /// Goal of agent `i`: the (jittered) lattice point `perm[i]`.
    pub goals: Vec<Vec3<f32>>,
}

/// The lattice's edge in points: ⌈∛n⌉ (as the driver computes it, in `f64`).
fn side(n: usize) -> usize {
    (n as f64).cbrt().ceil() as usize
}

/// Lattice point `i` of a lattice of `side` points per edge, jittered by up to ±1/8 of the
/// spacing per axis.
fn lattice_point(seed: u32, i: usize, side: usize, spacing: f32) -> Vec3<f32> {
    let at = [i % side, i / side % side, i / (side * side)];
    let c = |k: usize| {
        let jitter = unit(seed, i as u32, k as u32) - 0.5;
        spacing * (at[k] as f32 + 0.25 * jitter)
    };
    Vec3::new(c(0), c(1), c(2))
}

/// The Fisher-Yates permutation of `0..n` the driver draws (`j = mix32(seed ^ i) % i`).
fn permutation(n: usize, seed: u32) -> Vec<usize> {
    let mut perm: Vec<usize> = (0..n).collect();
    for i in (2..=n).rev() {
        let j = mix32(seed ^ i as u32) as usize % i;
        perm.swap(i - 1, j);
    }
    perm
}

/// The random cube of `n` agents for `seed`: the jittered lattice of spacing `spacing` (≥ 4:
/// no two agents of radius [`CUBE_RADIUS`] start closer than two radii) and the goals.
pub fn random_cube(n: usize, seed: u32, spacing: f32) -> Cube {
    let side = side(n);
    let positions: Vec<Vec3<f32>> = (0..n)
        .map(|i| lattice_point(seed, i, side, spacing))
        .collect();
    let goals = permutation(n, seed)
        .into_iter()
        .map(|p| positions[p])
        .collect();
    Cube { positions, goals }
}

/// The preferred velocity toward `goal` from `pos` as the driver sets it: `goal − pos`,
/// normalised (RVO2-3D's `normalize`, `v · (1/|v|)`) when longer than 1.
#[inline]
pub fn toward(goal: Vec3<f32>, pos: Vec3<f32>) -> Vec3<f32> {
    let g = goal - pos;
    let l2 = g.length_sq();
    if l2 > 1.0 { g * (1.0 / l2.sqrt()) } else { g }
}
