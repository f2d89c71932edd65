//! ant-node-other: `ant-node` built with other parameters (w0 = 0.5 instead of 0.6), for the
//! harness's test that a device whose parameters differ from the host scenario's is refused at
//! the handshake (the parameter hash names the difference). Not for use on a robot.
#![no_std]
#![no_main]

use swarm_core::ant::AntParams;
use swarm_core::wire::AntDevice;

fw_support::serial_node!({
    let p = fw_node::ant_params::<f32>();
    AntDevice::new(AntParams { w0: 0.5, ..p }, "ant-node-other")
});
