//! ant-node, fixed point (`Fx`, I16F16): replays the ant scenario on a Cortex-M3 and checks
//! every decision word against the host's (see `fw-scenario` and `build.rs`).
#![no_std]
#![no_main]

include!(concat!(env!("OUT_DIR"), "/expected_fixed.rs"));

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::check("ant-node-fixed [I16F16, cortex-m3]", &EXPECTED, |c| {
        fw_scenario::ant::run::<swarm_core::Fx>(c)
    })
}
