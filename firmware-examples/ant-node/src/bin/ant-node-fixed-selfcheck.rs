//! ant-node-fixed-selfcheck, fixed point (`Fx`, I16F16): replays the ant scenario on a
//! Cortex-M3 and checks every decision word against the host's (see `fw-scenario` and `build.rs`),
//! prints the result over semihosting and exits QEMU (`scripts/qemu-run.sh`).
#![no_std]
#![no_main]

fw_support::selfcheck_image!("ant-node-fixed [I16F16, cortex-m3]", ant, Fx);
