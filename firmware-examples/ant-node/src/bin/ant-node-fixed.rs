//! ant-node-fixed, fixed point (`Fx`, I16F16), on QEMU `lm3s6965evb` (Cortex-M3): the ant
//! device endpoint (`AntDevice<Fx>`, parameters of the host scenario `ants-fig7a-single-colony`)
//! on UART0, 115200 8N1, forever. See `fw-node` and `firmware-examples/README.md`.
#![no_std]
#![no_main]

fw_support::serial_node!(fw_node::ant_device::<swarm_core::Fx>("ant-node-fixed"));
