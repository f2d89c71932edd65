//! ant-node-cycles, f32 (libm): times the ant controller on a Cortex-M3 as `ant-node` runs it
//! (`ant::plan_checked` + `ant::resolve_checked` per ant-step, `ant-node`'s parameters and
//! frame capacities), call by call with SysTick, prints one line over semihosting and exits
//! QEMU. `scripts/qemu-cycles.sh` runs it under `-icount` and converts ticks to instructions
//! (see `fw_support::cycles`).
#![no_std]
#![no_main]

fw_support::cycles_image!("ant-node-cycles", ant, f32);
