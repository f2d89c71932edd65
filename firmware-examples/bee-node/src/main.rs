//! bee-node, f32 (libm), on QEMU `mps2-an386` (Cortex-M4F): the bee device endpoint
//! (`BeeDevice<f32>`, parameters of the host scenario `bees-fig14-shafts`) on UART0,
//! 115200 8N1, forever. See `fw-node` and `firmware-examples/README.md`.
#![no_std]
#![no_main]

fw_support::serial_node!(fw_node::bee_device::<f32>("bee-node"));
