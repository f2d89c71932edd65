//! bee-node, f32 (libm), on QEMU `mps2-an386` (Cortex-M4F): the bee device endpoint
//! (`BeeDevice<f32>`, parameters of the host scenario `bees-fig14-shafts`) on UART0,
//! 115200 8N1, forever. See `fw-node` and `firmware-examples/README.md`.
#![no_std]
#![no_main]

use fw_support::uart::{BAUD, CmsdkUart0};

fw_support::node_handlers!();

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::paint_stack();
    let Some(mut uart) = CmsdkUart0::take(BAUD) else {
        fw_support::reset()
    };
    let Ok(mut device) = fw_node::bee_device::<f32>("bee-node") else {
        fw_support::reset()
    };
    fw_node::run(&mut device, &mut uart)
}
