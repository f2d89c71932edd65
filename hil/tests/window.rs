//! The pipelining window follows what the device says it buffers (`Identity.rx_buffer`): a
//! polled board gets one request at a time, a soft device the whole window, a line with flow
//! control the whole window whatever the device buffers.

use swarm_core::ant::AntParams;
use swarm_core::wire::{AntDevice, MAX_ANT_FRAME};
use swarm_hil::client::{Client, ClientOptions};
use swarm_hil::loopback::{Line, LinkKind, loopback};
use swarm_hil::mirror::{MirrorOptions, mirror};
use swarm_hil::soft::{SoftDevice, serve};
use swarm_hil::transport::memory_pair;
use swarm_sim::ants::AntSim;
use swarm_sim::scenario::{self, ScalarType};

fn opts() -> MirrorOptions {
    MirrorOptions {
        agents: Some(8),
        steps: 5,
        session: 7,
        progress: false,
    }
}

/// Mirrors 8 ants of fig. 7a for 5 steps on an `AntDevice<f32>` reporting `rx_buffer`, and
/// returns the window used and the device's `rx_buffer` as the report gives them.
fn window_against(rx_buffer: u32, flow_control: bool) -> (u64, u32) {
    let sc = scenario::builtin("ants-fig7a-single-colony").unwrap();
    let mut device = AntDevice::<f32>::new(AntParams::default(), "polled-ant").unwrap();
    device.set_rx_buffer(rx_buffer);
    let (dev_end, host_end) = memory_pair();
    let soft = SoftDevice::spawn(move |stop| serve(Box::new(device), dev_end, stop).map(|_| ()));
    let client_opts = ClientOptions {
        window: 8,
        flow_control,
        ..ClientOptions::default()
    };
    let mut client = Client::new(host_end, client_opts);
    let sim = AntSim::from_scenario(&sc, sc.seed).unwrap();
    let r = mirror(&sc.name, Box::new(sim), &mut client, &opts(), &mut |_| {
        Ok(())
    })
    .unwrap();
    soft.stop().unwrap();
    assert_eq!(r.mismatches, 0);
    assert_eq!(r.decisions, 8 * 5 * 2);
    (r.window, r.rx_buffer)
}

#[test]
fn a_polled_uart_gets_one_request_at_a_time() {
    // The PL011's 16-byte FIFO and the CMSDK UART's 1 byte: less than one ant request.
    assert_eq!(window_against(16, false), (1, 16));
    assert_eq!(window_against(1, false), (1, 1));
    assert_eq!(window_against(0, false), (1, 0));
}

#[test]
fn a_ring_buffer_gets_as_many_requests_as_it_holds() {
    let ring = u32::try_from(3 * MAX_ANT_FRAME).unwrap();
    assert_eq!(window_against(ring, false), (4, ring));
    assert_eq!(window_against(u32::MAX, false), (8, u32::MAX));
}

#[test]
fn a_line_with_flow_control_keeps_the_whole_window() {
    assert_eq!(window_against(16, true), (8, 16));
}

#[test]
fn the_soft_device_is_unbounded() {
    let sc = scenario::builtin("ants-fig7a-single-colony").unwrap();
    let r = loopback(&sc, ScalarType::F32, Line::clean(LinkKind::Memory), &opts()).unwrap();
    assert_eq!((r.window, r.rx_buffer), (8, u32::MAX));
}
