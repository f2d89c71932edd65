//! fly-node-fixed, fixed point (`Fx`, I16F16), on QEMU `mps2-an386` (Cortex-M4F): the fly
//! device endpoint (`FlyDevice<Fx>`, parameters of the host scenario `fly-fig1-midges`) on
//! UART0, 115200 8N1, forever. See `fw-node` and `firmware-examples/README.md`.
#![no_std]
#![no_main]

fw_support::serial_node!(fw_node::fly_device::<swarm_core::Fx>("fly-node-fixed"));
