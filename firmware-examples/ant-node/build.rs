//! Host side of the ant-node image: the linker memory map, and the expected decisions.
//!
//! `fw-scenario` is a build-dependency with the same `swarm-core` features as the firmware, so
//! the scenario runs here, on the host, through the very same code the MCU runs, and its
//! decision words become the `EXPECTED` tables the firmware checks against.

use fw_scenario::host::{collect, node_build_script};

fn main() {
    let f32_words = collect(|s| fw_scenario::ant::run::<f32>(s));
    #[cfg(feature = "fixed")]
    let fixed_words = Some(collect(|s| {
        fw_scenario::ant::run::<fw_scenario::swarm_core::Fx>(s)
    }));
    #[cfg(not(feature = "fixed"))]
    let fixed_words: Option<Vec<u32>> = None;
    node_build_script(
        "ant scenario (fw-scenario::ant)",
        &f32_words,
        fixed_words.as_deref(),
    );
}
