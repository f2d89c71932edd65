//! bee-node-cycles, f32 (libm, FPU): times the bee controller on a Cortex-M4F as `bee-node`
//! runs it (`bee::step_checked` per bee step, `bee-node`'s parameters and wire frame
//! capacities), call by call with SysTick, prints one line over semihosting and exits QEMU.
//! `scripts/qemu-cycles.sh` runs it under `-icount` and converts ticks to instructions (see
//! `fw_support::cycles`).
#![no_std]
#![no_main]

use swarm_core::wire::{WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS};

fw_support::selfcheck_handlers!();

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::cycles::run("bee-node-cycles", "f32", |meter, line| {
        let Ok(params) = fw_node::bee_params::<f32>().checked() else {
            return false;
        };
        let cost =
            fw_scenario::bee::cost::<f32, WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS>(&params, meter);
        fw_support::cycles::put_bee(line, &cost)
    })
}
