//! bee-node-other: `bee-node` built with other parameters (κ2 = 3.21 instead of Table I's
//! 2.3), for the harness's test that a device whose parameters differ from the host scenario's
//! is refused at the handshake (the parameter hash names the difference). Not for use on a
//! robot.
#![no_std]
#![no_main]

use swarm_core::bee::BeeParams;
use swarm_core::wire::BeeDevice;

fw_support::serial_node!({
    let p = fw_node::bee_params::<f32>();
    BeeDevice::new(BeeParams { kappa2: 3.21, ..p }, "bee-node-other")
});
