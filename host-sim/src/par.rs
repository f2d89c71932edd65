//! Parallel loops over agents whose failures are deterministic.

use std::sync::Mutex;

use rayon::prelude::*;

use crate::error::{Result, SimError};

/// A pool of `threads` workers (`None`: one per core), with the count it got. Zero threads
/// is an error, not rayon's "pick for me": results are identical for any count, but a
/// benchmark or a summary must say what ran.
pub(crate) fn pool(threads: Option<usize>) -> Result<(rayon::ThreadPool, usize)> {
    let threads =
        threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if threads == 0 {
        return Err(SimError::NoThreads);
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|source| SimError::ThreadPool { threads, source })?;
    Ok((pool, threads))
}

/// The most agents one rayon task takes at once: small enough that a worker whose CPU is
/// taken away (a VM's vCPU, a busy core) holds up the others for well under a millisecond,
/// since the rest of its work can be stolen; large enough that splitting costs nothing.
const LEAF: usize = 1024;

/// Runs `f(scratch, k, item)` on every `(k, item)` of `items` in parallel, each worker with its
/// own `scratch` from `init`. Returns the error of the item with the lowest `key(k)` that
/// failed, whatever the thread count: the engines, which reorder their slots, pass each
/// slot's agent id, so that the agent a run names depends neither on where its slot lies nor
/// on the engine (the GPU's never reorder).
///
/// Unlike rayon's `try_for_each_init`, no result travels through the reduction: an agent step
/// that succeeds costs nothing beyond the call (failures are rare and only end a run).
pub(crate) fn for_each_agent_by<I, T, W>(
    items: I,
    key: impl Fn(usize) -> u64 + Sync + Send,
    init: impl Fn() -> W + Sync + Send,
    f: impl Fn(&mut W, usize, T) -> Result<()> + Sync + Send,
) -> Result<()>
where
    I: IndexedParallelIterator<Item = T>,
{
    let first: Mutex<Option<(u64, SimError)>> = Mutex::new(None);
    items
        .enumerate()
        .with_max_len(LEAF)
        .for_each_init(init, |w, (k, item)| {
            if let Err(e) = f(w, k, item) {
                let key = key(k);
                let mut slot = first.lock().unwrap_or_else(|p| p.into_inner());
                if slot.as_ref().is_none_or(|(j, _)| key < *j) {
                    *slot = Some((key, e));
                }
            }
        });
    match first.into_inner().unwrap_or_else(|p| p.into_inner()) {
        Some((_, e)) => Err(e),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lowest_failing_index_wins_at_any_thread_count() {
        for threads in [1, 2, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = vec![0u32; 10_000];
            let r = pool.install(|| {
                for_each_agent_by(
                    out.par_iter_mut(),
                    |k| k as u64,
                    || (),
                    |_, k, o| {
                        *o = k as u32;
                        if k % 997 == 996 {
                            Err(SimError::NoAgent {
                                id: k as u32,
                                agents: 0,
                            })
                        } else {
                            Ok(())
                        }
                    },
                )
            });
            assert_eq!(
                r.unwrap_err().to_string(),
                SimError::NoAgent { id: 996, agents: 0 }.to_string()
            );
            assert!(out.iter().enumerate().all(|(k, &o)| o == k as u32));
        }
        let none = for_each_agent_by(
            (0..10u32).into_par_iter(),
            |k| k as u64,
            || (),
            |_, _, _| Ok(()),
        );
        assert!(none.is_ok());
    }

    /// With a key, the failure of the lowest key wins, wherever its item lies.
    #[test]
    fn the_lowest_failing_key_wins() {
        for threads in [1, 2, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let r = pool.install(|| {
                for_each_agent_by(
                    (0..5_000u32).into_par_iter(),
                    |k| 10_000 - k as u64,
                    || (),
                    |_, k, _| match k % 1_000 {
                        7 => Err(SimError::NoAgent {
                            id: k as u32,
                            agents: 0,
                        }),
                        _ => Ok(()),
                    },
                )
            });
            let e = r.unwrap_err().to_string();
            assert_eq!(
                e,
                SimError::NoAgent {
                    id: 4_007,
                    agents: 0
                }
                .to_string()
            );
        }
    }
}
