//! fly-node-cycles, f32 (libm, FPU): times the fly controller on a Cortex-M4F as `fly-node`
//! runs it (`fly::step_checked` per insect step, `fly-node`'s parameters and wire frame
//! capacities), call by call with SysTick, prints one line over semihosting and exits QEMU.
//! `scripts/qemu-cycles.sh` runs it under `-icount` and converts ticks to instructions (see
//! `fw_support::cycles`).
#![no_std]
#![no_main]

fw_support::cycles_image!("fly-node-cycles", fly, f32);
