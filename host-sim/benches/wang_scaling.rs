//! W-T21 (linear scaling, Fig. 14b): one wang2014 tick of the synthetic bench world
//! (`bench_wang_world`) in f32 on a pool of 2 threads.
//!
//! - `wang_scaling/insects/N`, N ∈ {1k, 4k, 16k, 64k, 256k}: per-step time should fit a line
//!   in N (R² ≥ 0.98).
//! - `wang_scaling/world/{base,grid2x,obstacles4x}` at 64k insects: a cost grid with 2× the
//!   cells per axis, or 4× the obstacles, should change the per-step time by < 15 %.
//!
//! The fields are solved while the world is built, and one untimed tick runs before the
//! measurement; ticks are timed in windows of 32 from that state (see [`WINDOW`]). `scripts/wang-scaling.py` runs this and checks the thresholds.

use std::time::{Duration, Instant};

use criterion::measurement::WallTime;
use criterion::{
    BenchmarkGroup, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main,
};
use swarm_sim::scenario::ScalarType;
use swarm_sim::wang::{WangBenchShape, WangSim, bench_wang_world_shaped};

/// Worker threads: the project's 2-core VM.
const THREADS: usize = 2;
/// Insects of the world group.
const WORLD_N: usize = 64_000;

fn pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(THREADS)
        .build()
        .expect("a pool of 2 threads")
}

/// Ticks of one measured window: the swarm is put back to the state after the warm-up tick
/// every `WINDOW` ticks (untimed), so that every N is timed over the same stretch of the run
/// (steps 2-33, one reordering of the insects included) however many ticks criterion asks
/// for; otherwise a small swarm, ticked thousands of times, would be timed aggregated at the
/// goal and a large one still spread out.
const WINDOW: u64 = 32;

/// The bench world of `n` insects and `shape`, its fields solved, after one untimed tick.
fn world(pool: &rayon::ThreadPool, n: usize, shape: WangBenchShape) -> WangSim {
    pool.install(|| {
        let mut sim = bench_wang_world_shaped(n, 1, ScalarType::F32, shape);
        sim.tick().expect("the bench world ticks");
        sim
    })
}

/// Benchmark `id` of `g`: one tick of `start` per iteration, windows of [`WINDOW`] ticks.
fn tick(
    g: &mut BenchmarkGroup<'_, WallTime>,
    pool: &rayon::ThreadPool,
    id: BenchmarkId,
    start: &WangSim,
) {
    let mut sim = start.clone();
    g.bench_function(id, |b| {
        b.iter_custom(|iters| {
            let mut spent = Duration::ZERO;
            for k in 0..iters {
                if k % WINDOW == 0 {
                    sim.clone_from(start);
                }
                let t0 = Instant::now();
                pool.install(|| sim.tick().expect("the bench world ticks"));
                spent += t0.elapsed();
            }
            spent
        })
    });
}

/// One group, `wang_scaling`, so that criterion's directories are
/// `wang_scaling/insects/N` and `wang_scaling/world/NAME`.
fn wang_scaling(c: &mut Criterion) {
    let pool = pool();
    let mut g = c.benchmark_group("wang_scaling");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in [1_000, 4_000, 16_000, 64_000, 256_000] {
        let sim = world(&pool, n, WangBenchShape::default());
        g.throughput(Throughput::Elements(n as u64));
        tick(&mut g, &pool, BenchmarkId::new("insects", n), &sim);
    }
    g.throughput(Throughput::Elements(WORLD_N as u64));
    let base = WangBenchShape::default();
    let shapes = [
        ("base", base),
        (
            "grid2x",
            WangBenchShape {
                grid_refine: 2,
                ..base
            },
        ),
        (
            "obstacles4x",
            WangBenchShape {
                obstacle_copies: 4,
                ..base
            },
        ),
    ];
    for (name, shape) in shapes {
        let sim = world(&pool, WORLD_N, shape);
        tick(&mut g, &pool, BenchmarkId::new("world", name), &sim);
    }
    g.finish();
}

criterion_group!(benches, wang_scaling);
criterion_main!(benches);
