//! ant-node, f32 (libm), on QEMU `lm3s6965evb` (Cortex-M3): the ant device endpoint
//! (`AntDevice<f32>`, parameters of the host scenario `ants-fig7a-single-colony`) on UART0,
//! 115200 8N1, forever. See `fw-node` and `firmware-examples/README.md`.
#![no_std]
#![no_main]

fw_support::serial_node!(fw_node::ant_device::<f32>("ant-node"));
