//! ant-node-fixed-selfcheck, fixed point (`Fx`, I16F16): replays the ant scenario on a
//! Cortex-M3 and checks every decision word against the host's (see `fw-scenario` and `build.rs`),
//! prints the result over semihosting and exits QEMU (`scripts/qemu-run.sh`).
#![no_std]
#![no_main]

fw_support::selfcheck_handlers!();

include!(concat!(env!("OUT_DIR"), "/expected_fixed.rs"));

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::check("ant-node-fixed [I16F16, cortex-m3]", &EXPECTED, |c| {
        fw_scenario::ant::run::<swarm_core::Fx>(c)
    })
}
