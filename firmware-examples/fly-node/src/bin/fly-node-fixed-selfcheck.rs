//! fly-node-fixed-selfcheck, fixed point (`Fx`, I16F16): replays the fly scenario on a
//! Cortex-M4F and checks every decision word against the host's (see `fw-scenario` and
//! `build.rs`), prints the result over semihosting and exits QEMU (`scripts/qemu-run.sh`).
#![no_std]
#![no_main]

fw_support::selfcheck_image!("fly-node-fixed [I16F16, cortex-m4f]", fly, Fx);
