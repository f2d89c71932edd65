//! ant-node-selfcheck, f32 (libm): replays the ant scenario on a Cortex-M3 and checks every
//! decision word against the host's (see `fw-scenario` and `build.rs`), prints the result over
//! semihosting and exits QEMU (`scripts/qemu-run.sh`).
#![no_std]
#![no_main]

fw_support::selfcheck_image!("ant-node [f32/libm, cortex-m3]", ant, f32);
