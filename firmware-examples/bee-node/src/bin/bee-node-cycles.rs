//! bee-node-cycles, f32 (libm, FPU): times the bee controller on a Cortex-M4F as `bee-node`
//! runs it (`bee::step_checked` per bee step, `bee-node`'s parameters and wire frame
//! capacities), call by call with SysTick, prints one line over semihosting and exits QEMU.
//! `scripts/qemu-cycles.sh` runs it under `-icount` and converts ticks to instructions (see
//! `fw_support::cycles`).
#![no_std]
#![no_main]

fw_support::cycles_image!("bee-node-cycles", bee, f32);
