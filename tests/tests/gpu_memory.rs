//! GPU engines leave nothing behind: many engine lifetimes in one process (a test loop, a
//! Python session calling `swarm.run` in a loop, a Ray worker taking task after task) hold the
//! memory of one. Its own test process: resident memory is the process's, and no other test
//! may run beside it.

use swarm_sim::models;
use swarm_sim::scenario::{Backend, ScalarType};

/// Engine lifetimes per model.
const LIFETIMES: usize = 20;
/// Lifetimes before the baseline is read: the first opens the device and compiles the
/// model's kernels, the driver settles its pools on the second.
const WARM_UP: usize = 2;
/// The most resident memory the later lifetimes of one model may add, in MiB.
const MAX_GROWTH_MIB: f64 = 100.0;

/// This process's resident memory, in MiB (`VmRSS` of `/proc/self/status`).
fn resident_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status");
    let kib: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .expect("VmRSS in /proc/self/status");
    kib / 1024.0
}

/// One lifetime: model `name`'s GPU benchmark world of 250 agents built on the process's
/// device, ticked, read back, dropped. (What leaked was per engine, whatever its size: the
/// kernels compiled and the driver's pools of a device each, 2-22 MiB a lifetime.)
fn lifetime(name: &str, seed: u32) {
    let mut engine = models::bench_engine(name, 250, seed, ScalarType::Fixed, Backend::Gpu)
        .unwrap_or_else(|e| panic!("{name} on the GPU: {e}"));
    for _ in 0..4 {
        engine.tick().unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    engine.snapshot().expect("snapshot");
    engine.take_snapshot().expect("read back");
    let _ = engine.frame();
}

/// Every model with a GPU engine (found in the registry: a model added later is held to it
/// without a line here), [`LIFETIMES`] lifetimes each in fixed point (one scalar: a leak is not
/// the scalar's, and each scalar's kernels take lavapipe 10-30 s to compile), a seed each:
/// after the first [`WARM_UP`], resident memory grows by at most [`MAX_GROWTH_MIB`].
#[test]
fn engine_lifetimes_hold_memory_flat() {
    let with_gpu: Vec<&str> = models::all()
        .iter()
        .filter(|m| m.gpu.is_some())
        .map(|m| m.name)
        .collect();
    assert!(with_gpu.len() >= 5, "{with_gpu:?}");
    let mut report = Vec::new();
    for name in with_gpu {
        let mut base = 0.0;
        for i in 0..LIFETIMES {
            lifetime(name, i as u32 + 1);
            if i + 1 == WARM_UP {
                base = resident_mib();
            }
        }
        let growth = resident_mib() - base;
        eprintln!(
            "{name}: {growth:+.1} MiB over lifetimes {WARM_UP}-{LIFETIMES} (from {base:.0} MiB)"
        );
        report.push((name, growth));
    }
    for (name, growth) in report {
        assert!(
            growth <= MAX_GROWTH_MIB,
            "{name}: {LIFETIMES} GPU engine lifetimes grew resident memory by {growth:.0} MiB \
             after the first {WARM_UP} (at most {MAX_GROWTH_MIB} MiB)"
        );
    }
}
