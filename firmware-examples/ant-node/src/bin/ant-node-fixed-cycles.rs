//! ant-node-fixed-cycles, fixed point (`Fx`, I16F16): times the ant controller on a
//! Cortex-M3 as `ant-node-fixed` runs it (`ant::plan_checked` + `ant::resolve_checked` per
//! ant-step, `ant-node-fixed`'s parameters and frame capacities), call by call with SysTick,
//! prints one line over semihosting and exits QEMU. `scripts/qemu-cycles.sh` runs it under
//! `-icount` and converts ticks to instructions (see `fw_support::cycles`).
#![no_std]
#![no_main]

fw_support::selfcheck_handlers!();

// The frames of the timed run have the capacities of the node's wire frames.
const _: () = assert!(
    fw_scenario::ant::N == swarm_core::wire::WIRE_ANT_NEIGHBOURS
        && fw_scenario::ant::O == swarm_core::wire::WIRE_ANT_OBJECTS
);

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::cycles::run("ant-node-fixed-cycles", "I16F16", |meter, line| {
        let Ok(params) = fw_node::ant_params::<swarm_core::Fx>().checked() else {
            return false;
        };
        let cost = fw_scenario::ant::cost(&params, meter);
        fw_support::cycles::put_ant(line, &cost)
    })
}
