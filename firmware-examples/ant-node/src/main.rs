//! ant-node, f32 (libm), on QEMU `lm3s6965evb` (Cortex-M3): the ant device endpoint
//! (`AntDevice<f32>`, parameters of the host scenario `ants-fig7a-single-colony`) on UART0,
//! 115200 8N1, forever. See `fw-node` and `firmware-examples/README.md`.
#![no_std]
#![no_main]

use fw_support::uart::{BAUD, Lm3sUart0};

fw_support::node_handlers!();

/// The UART clock: the LM3S6965's 12 MHz internal oscillator after reset (QEMU ignores it;
/// a real board switches to the crystal or PLL first, see README.md).
const CLOCK_HZ: u32 = 12_000_000;

#[cortex_m_rt::entry]
fn main() -> ! {
    fw_support::paint_stack();
    let Some(mut uart) = Lm3sUart0::take(CLOCK_HZ, BAUD) else {
        fw_support::reset()
    };
    let Ok(mut device) = fw_node::ant_device::<f32>("ant-node") else {
        fw_support::reset()
    };
    fw_node::run(&mut device, &mut uart)
}
