//! fly-node, f32 (libm), on QEMU `mps2-an386` (Cortex-M4F): the fly device endpoint
//! (`FlyDevice<f32>`: ren2016's insect with ORCA, parameters of the host scenario
//! `fly-fig1-midges`, Table 1's Midge column) on UART0, 115200 8N1, forever. See `fw-node` and
//! `firmware-examples/README.md`.
#![no_std]
#![no_main]

fw_support::serial_node!(fw_node::fly_device::<f32>("fly-node"));
