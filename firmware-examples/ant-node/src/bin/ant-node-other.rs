//! ant-node-other: `ant-node` built with other parameters (w0 = 0.5 instead of 0.6), for the
//! harness's test that a device whose parameters differ from the host scenario's is refused at
//! the handshake (the parameter hash names the difference). Not for use on a robot.
#![no_std]
#![no_main]

use fw_support::uart::{BAUD, Lm3sUart0};
use swarm_core::ant::AntParams;
use swarm_core::wire::AntDevice;

fw_support::node_handlers!();

/// As in `ant-node`.
const CLOCK_HZ: u32 = 12_000_000;

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::paint_stack();
    let Some(mut uart) = Lm3sUart0::take(CLOCK_HZ, BAUD) else {
        fw_support::reset()
    };
    let params = AntParams {
        w0: 0.5,
        ..fw_node::ant_params::<f32>()
    };
    let Ok(mut device) = AntDevice::<f32>::new(params, "ant-node-other") else {
        fw_support::reset()
    };
    fw_node::run(&mut device, &mut uart)
}
