//! fly-node-selfcheck, f32 (libm): replays the fly scenario on a Cortex-M4F and checks every
//! decision word against the host's (see `fw-scenario` and `build.rs`), prints the result over
//! semihosting and exits QEMU (`scripts/qemu-run.sh`).
#![no_std]
#![no_main]

fw_support::selfcheck_image!("fly-node [f32/libm, cortex-m4f]", fly, f32);
