//! The GPU backend's promise for every built-in li2015 scenario (`gpu_runs.rs` for the other
//! models), in a test process of its own: on lavapipe the fly and li scenarios run in one
//! process held over 22 GiB, and one CI run was killed for memory.

mod gpu_common;

use gpu_common::every_scenario_of;

/// Every built-in li scenario (`li-*`), found by its name, as the fly's: the lights of Fig. 6
/// move each group's density on between steps (the host sees every step until the last).
#[test]
fn li_scenarios_are_the_cpus_bytes() {
    every_scenario_of("li-", "li-fig6-lights");
}
