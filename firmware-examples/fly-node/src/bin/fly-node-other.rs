//! fly-node-other: `fly-node` built with other parameters (Table 1's Fruitfly column instead of
//! the Midge column), for the harness's test that a device whose parameters differ from the
//! host scenario's is refused at the handshake (the parameter hash names the difference). Not
//! for use on a robot.
#![no_std]
#![no_main]

use swarm_core::fly::{FlyDevice, FlyParams};

fw_support::serial_node!(FlyDevice::new(
    FlyParams::<f32>::fruitfly(),
    "fly-node-other"
));
