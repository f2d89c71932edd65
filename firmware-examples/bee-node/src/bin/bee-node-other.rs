//! bee-node-other: `bee-node` built with other parameters (κ2 = 3.21 instead of Table I's
//! 2.3), for the harness's test that a device whose parameters differ from the host scenario's
//! is refused at the handshake (the parameter hash names the difference). Not for use on a
//! robot.
#![no_std]
#![no_main]

use fw_support::uart::{BAUD, CmsdkUart0};
use swarm_core::bee::BeeParams;
use swarm_core::wire::BeeDevice;

fw_support::node_handlers!();

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::paint_stack();
    let Some(mut uart) = CmsdkUart0::take(BAUD) else {
        fw_support::reset()
    };
    let params = BeeParams {
        kappa2: 3.21,
        ..fw_node::bee_params::<f32>()
    };
    let Ok(mut device) = BeeDevice::<f32>::new(params, "bee-node-other") else {
        fw_support::reset()
    };
    fw_node::run(&mut device, &mut uart)
}
