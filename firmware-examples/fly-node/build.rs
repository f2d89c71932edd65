//! Host side of the fly-node image: the linker memory map, and the expected decisions.
//!
//! `fw-scenario` is a build-dependency with the same `swarm-core` features as the firmware, so
//! the scenario runs here, on the host, through the very same code the MCU runs, and its
//! decision words become the `EXPECTED` tables the firmware checks against.

fw_scenario::node_build_script!(fly, "fly scenario (fw-scenario::fly)");
