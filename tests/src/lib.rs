//! Cross-crate integration tests live in `tests/tests/`; this crate holds what they share.

/// The seed a behaviour test runs its scenario with: the scenario's own, unless
/// `SWARM_TEST_SEED` is set. The override is for robustness audits (the behaviour tests must
/// hold for any seed, not only the scenario's):
///
/// ```sh
/// for s in 1 2 3 4 5 6 7 8 9 10; do
///     SWARM_TEST_SEED=$s cargo test --release -p swarm-tests --test ant_behaviour --test bee_behaviour
/// done
/// ```
///
/// # Panics
/// When `SWARM_TEST_SEED` is set but is not a `u32`.
pub fn seed(scenario_seed: u32) -> u32 {
    match std::env::var("SWARM_TEST_SEED") {
        Ok(s) => {
            let seed = s
                .parse()
                .unwrap_or_else(|_| panic!("SWARM_TEST_SEED={s:?} is not a u32"));
            eprintln!("SWARM_TEST_SEED: running with seed {seed} instead of {scenario_seed}");
            seed
        }
        Err(_) => scenario_seed,
    }
}

/// Euclidean distance between two points.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The mean of `pos` (the origin for none).
pub fn centroid(pos: &[[f64; 3]]) -> [f64; 3] {
    let n = pos.len().max(1) as f64;
    std::array::from_fn(|k| pos.iter().map(|p| p[k]).sum::<f64>() / n)
}

pub mod walker;
