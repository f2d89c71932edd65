//! Host side of the bee-node image: the linker memory map, and the expected decisions.
//!
//! `fw-scenario` is a build-dependency with the same `swarm-core` features as the firmware, so
//! the scenario below runs here, on the host, through the very same code the MCU runs, and its
//! decision words become the `EXPECTED` tables the firmware checks against.

use std::{env, fs, path::PathBuf};

use fw_scenario::host::{collect, write_table};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");

    let what = "bee scenario (fw-scenario::bee)";
    let words = collect(|s| fw_scenario::bee::run::<f32>(s));
    let header = format!("Host-computed decision words of the {what}, scalar f32 (libm).");
    write_table(&out.join("expected_f32.rs"), "EXPECTED", &header, &words);

    #[cfg(feature = "fixed")]
    {
        let words = collect(|s| fw_scenario::bee::run::<fw_scenario::swarm_core::Fx>(s));
        let header = format!("Host-computed decision words of the {what}, scalar Fx (I16F16).");
        write_table(&out.join("expected_fixed.rs"), "EXPECTED", &header, &words);
    }
}
