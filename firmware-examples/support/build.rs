//! cortex-m-rt's `device` feature makes its `link.x` include `device.x` (normally from a
//! peripheral access crate, naming the interrupt handlers). The images name none: an empty one.
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::write(out.join("device.x"), "/* no named device interrupts */\n").expect("write device.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=build.rs");
}
