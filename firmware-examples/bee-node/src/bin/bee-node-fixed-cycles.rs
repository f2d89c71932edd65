//! bee-node-fixed-cycles, fixed point (`Fx`, I16F16): times the bee controller on a
//! Cortex-M4F as `bee-node-fixed` runs it (`bee::step_checked` per bee step,
//! `bee-node-fixed`'s parameters and wire frame capacities), call by call with SysTick, prints
//! one line over semihosting and exits QEMU. `scripts/qemu-cycles.sh` runs it under `-icount`
//! and converts ticks to instructions (see `fw_support::cycles`).
#![no_std]
#![no_main]

use swarm_core::Fx;
use swarm_core::wire::{WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS};

fw_support::selfcheck_handlers!();

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::cycles::run("bee-node-fixed-cycles", "I16F16", |meter, line| {
        let Ok(params) = fw_node::bee_params::<Fx>().checked() else {
            return false;
        };
        let cost =
            fw_scenario::bee::cost::<Fx, WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS>(&params, meter);
        fw_support::cycles::put_bee(line, &cost)
    })
}
