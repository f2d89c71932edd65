//! ant-node-fixed-cycles, fixed point (`Fx`, I16F16): times the ant controller on a
//! Cortex-M3 as `ant-node-fixed` runs it (`ant::plan_checked` + `ant::resolve_checked` per
//! ant-step, `ant-node-fixed`'s parameters and frame capacities), call by call with SysTick,
//! prints one line over semihosting and exits QEMU. `scripts/qemu-cycles.sh` runs it under
//! `-icount` and converts ticks to instructions (see `fw_support::cycles`).
#![no_std]
#![no_main]

fw_support::cycles_image!("ant-node-fixed-cycles", ant, Fx);
