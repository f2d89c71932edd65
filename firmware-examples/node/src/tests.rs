//! Host tests of the node loop against an in-memory UART (`cargo test -p fw-node`).

extern crate std;

use super::*;
use std::vec;
use std::vec::Vec;
use swarm_core::fly::MAX_FLY_FRAME;
use swarm_core::wire::{
    self, Accumulator, ControllerKind, Event, Hello, Identity, MAX_ANT_FRAME, MAX_BEE_FRAME,
    params_hash,
};
use swarm_core::{Fx, ScalarKind};

/// A UART fed from a script: each `read` returns at most `chunk` bytes; writes are recorded.
/// Writes fail while `fail_writes` is set.
struct MockUart {
    input: Vec<u8>,
    pos: usize,
    chunk: usize,
    output: Vec<u8>,
    flushes: usize,
    fail_writes: bool,
}

#[derive(Debug, PartialEq)]
struct MockError;

impl embedded_io::Error for MockError {
    fn kind(&self) -> embedded_io::ErrorKind {
        embedded_io::ErrorKind::Other
    }
}

impl embedded_io::ErrorType for MockUart {
    type Error = MockError;
}

impl Read for MockUart {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, MockError> {
        let n = self.chunk.min(buf.len()).min(self.input.len() - self.pos);
        buf[..n].copy_from_slice(&self.input[self.pos..self.pos + n]);
        self.pos += n;
        Ok(n)
    }
}

impl Write for MockUart {
    fn write(&mut self, buf: &[u8]) -> Result<usize, MockError> {
        if self.fail_writes {
            return Err(MockError);
        }
        self.output.extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> Result<(), MockError> {
        self.flushes += 1;
        Ok(())
    }
}

impl MockUart {
    fn new(input: &[u8], chunk: usize) -> Self {
        MockUart {
            input: input.to_vec(),
            pos: 0,
            chunk,
            output: Vec::new(),
            flushes: 0,
            fail_writes: false,
        }
    }
    fn drain<C: Controller, const RX: usize, const TX: usize>(
        &mut self,
        device: &mut DeviceEndpoint<C, RX, TX>,
    ) {
        let mut buf = [0u8; READ_CHUNK];
        while self.pos < self.input.len() {
            let _ = poll(device, self, &mut buf);
        }
    }
}

fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// The frames in `bytes`, decoded.
fn frames(bytes: &[u8]) -> Vec<(u8, u16, Vec<u8>)> {
    let mut rx = Accumulator::<1024>::new();
    let mut out = Vec::new();
    let mut input = bytes;
    while let Some((event, rest)) = rx.feed(input) {
        if let Event::Frame(f) = event {
            out.push((f.header.kind, f.header.seq, f.payload.to_vec()));
        }
        input = rest;
    }
    out
}

fn identity_of(reply: &[u8]) -> Identity {
    let mut raw = reply[..reply.len() - 1].to_vec();
    wire::decode_message::<Identity>(&mut raw).unwrap().1
}

fn hello(seq: u16) -> Vec<u8> {
    let mut line = [0u8; 16];
    let n = wire::encode_message(seq, &Hello, &mut line).unwrap();
    line[..n].to_vec()
}

#[test]
fn ant_node_f32_answers_hello_with_the_identity_of_protocol_md_section_11() {
    // docs/protocol.md §11 step 2, byte for byte (a lone 00 first, as a host sends it).
    let mut line = vec![0u8];
    line.extend(hex("04 03 01 02 03 4e 4e 00"));
    let want = hex(
        "04 03 02 02 02 03 01 01 03 08 04 19 06 c3 03 10 c3 8b a1 c0 ec f6 b8 9a 7e \
         08 61 6e 74 2d 6e 6f 64 65 c4 0b 00",
    );
    for chunk in [1, 3, READ_CHUNK] {
        let mut device = ant_device::<f32>("ant-node").unwrap();
        // As `serial_node!` sets it on the lm3s6965evb: the PL011's 16-byte receive FIFO.
        device.set_rx_buffer(LM3S_RX_FIFO);
        let mut uart = MockUart::new(&line, chunk);
        uart.drain(&mut device);
        assert_eq!(uart.output, want, "chunk {chunk}");
        assert_eq!(uart.flushes, 1);
    }
}

#[test]
fn the_node_parameters_are_the_host_scenarios() {
    // ants-fig7a-single-colony: AntParams::default() (protocol.md §10.2 pins its f32 hash).
    assert_eq!(
        params_hash(&ant_params::<f32>()).unwrap(),
        0x7e34_e3b6_c808_45c3
    );
    assert_eq!(ant_params::<f32>(), AntParams::default());
    assert_eq!(
        ant_params::<Fx>(),
        AntParams::<f32>::default().cast::<Fx>(),
        "the host casts its f32 parameters (ANT_PARAMS_FX must equal the cast)"
    );
    assert_eq!(bee_params::<f32>(), BeeParams::default());
    assert_eq!(bee_params::<Fx>(), BeeParams::<f32>::default().cast::<Fx>());
    // fly-fig1-midges: preset `midge`, no overrides (protocol.md §10.2 pins both hashes).
    assert_eq!(fly_params::<f32>(), FlyParams::midge());
    assert_eq!(fly_params::<Fx>(), FlyParams::<f32>::midge().cast::<Fx>());
    assert_eq!(fly_params::<Fx>(), FlyParams::<Fx>::midge());
    assert_eq!(
        params_hash(&fly_params::<f32>()).unwrap(),
        0x6fe6_5802_e861_6419
    );
    assert_eq!(
        params_hash(&fly_params::<Fx>()).unwrap(),
        0xd9cd_f576_c0cf_3e24
    );
}

/// What the images report as `Identity.rx_buffer` (`fw_support::uart::RX_FIFO`, set by
/// `serial_node!`): the receive FIFO of the lm3s6965evb's PL011 (ant images) and the CMSDK
/// UART's one-byte receive buffer on the mps2-an386 (bee images).
const LM3S_RX_FIFO: u32 = 16;
const MPS2_RX_FIFO: u32 = 1;

#[test]
fn every_image_identity() {
    let cases: [(&str, Identity); 6] = [
        (
            "ant-node",
            greet(ant_device::<f32>("ant-node"), LM3S_RX_FIFO),
        ),
        (
            "ant-node-fixed",
            greet(ant_device::<Fx>("ant-node-fixed"), LM3S_RX_FIFO),
        ),
        (
            "bee-node",
            greet(bee_device::<f32>("bee-node"), MPS2_RX_FIFO),
        ),
        (
            "bee-node-fixed",
            greet(bee_device::<Fx>("bee-node-fixed"), MPS2_RX_FIFO),
        ),
        (
            "fly-node",
            greet(fly_device::<f32>("fly-node"), MPS2_RX_FIFO),
        ),
        (
            "fly-node-fixed",
            greet(fly_device::<Fx>("fly-node-fixed"), MPS2_RX_FIFO),
        ),
    ];
    let expect = [
        Identity::of(&ant_params::<f32>(), MAX_ANT_FRAME + 1, "ant-node").unwrap(),
        Identity::of(&ant_params::<Fx>(), MAX_ANT_FRAME + 1, "ant-node-fixed").unwrap(),
        Identity::of(&bee_params::<f32>(), MAX_BEE_FRAME + 1, "bee-node").unwrap(),
        Identity::of(&bee_params::<Fx>(), MAX_BEE_FRAME + 1, "bee-node-fixed").unwrap(),
        Identity::of(&fly_params::<f32>(), MAX_FLY_FRAME + 1, "fly-node").unwrap(),
        Identity::of(&fly_params::<Fx>(), MAX_FLY_FRAME + 1, "fly-node-fixed").unwrap(),
    ];
    let rx_fifo = [
        LM3S_RX_FIFO,
        LM3S_RX_FIFO,
        MPS2_RX_FIFO,
        MPS2_RX_FIFO,
        MPS2_RX_FIFO,
        MPS2_RX_FIFO,
    ];
    for (((name, got), want), rx_buffer) in cases.iter().zip(expect).zip(rx_fifo) {
        let want = Identity { rx_buffer, ..want };
        assert_eq!(got.name, *name);
        assert_eq!(*got, want, "{name}");
        assert!(got.check(&want).is_ok());
        // A host on a line without flow control keeps one request in flight (its longest
        // request frame is max_frame - 1: MAX_ANT_FRAME, MAX_BEE_FRAME or MAX_FLY_FRAME).
        assert_eq!(got.window(usize::from(want.max_frame) - 1), 1, "{name}");
    }
    assert_eq!(cases[0].1.capacities.surfaces, 6);
    assert_eq!(cases[1].1.scalar, ScalarKind::I16F16);
    assert_eq!(cases[2].1.controller, ControllerKind::BEE);
    assert_eq!(cases[2].1.capacities.surfaces, 0);
    assert_eq!(cases[4].1.controller, ControllerKind::FLY);
    assert_eq!(
        (
            cases[4].1.capacities.neighbours,
            cases[4].1.capacities.surfaces
        ),
        (16, 4)
    );
    assert_eq!(cases[5].1.scalar, ScalarKind::I16F16);
}

/// The `Identity` a new device reporting `rx_buffer` answers a `Hello` with.
fn greet<C: Controller, const RX: usize, const TX: usize>(
    device: swarm_core::Result<DeviceEndpoint<C, RX, TX>>,
    rx_buffer: u32,
) -> Identity {
    let mut device = device.unwrap();
    device.set_rx_buffer(rx_buffer);
    identity_of(&serve(&mut device, &hello(1)))
}

fn serve<C: Controller, const RX: usize, const TX: usize>(
    device: &mut DeviceEndpoint<C, RX, TX>,
    line: &[u8],
) -> Vec<u8> {
    let mut uart = MockUart::new(line, READ_CHUNK);
    uart.drain(device);
    uart.output
}

#[test]
fn a_failed_write_loses_only_its_reply() {
    let mut device = ant_device::<Fx>("ant-node-fixed").unwrap();
    // Two Hellos in one read: the first reply's write fails, the second still gets answered
    // once writes work again, and the endpoint saw every byte.
    let mut line = hello(1);
    line.extend(hello(2));
    let mut uart = MockUart::new(&line, READ_CHUNK);
    uart.fail_writes = true;
    let mut buf = [0u8; READ_CHUNK];
    assert_eq!(poll(&mut device, &mut uart, &mut buf), Err(MockError));
    assert_eq!(device.stats().requests, 2);
    uart.fail_writes = false;
    uart.input.extend(hello(3));
    assert!(poll(&mut device, &mut uart, &mut buf).is_ok());
    let got = frames(&uart.output);
    assert_eq!(got.len(), 1);
    assert_eq!((got[0].0, got[0].1), (0x02, 3));
}

#[test]
fn garbage_is_skipped_and_replies_keep_request_order() {
    let mut device = bee_device::<f32>("bee-node").unwrap();
    let mut line = hex("de ad be ef 00 00 13 37");
    line.push(0);
    for seq in 10..14 {
        line.extend(hello(seq));
    }
    let out = serve(&mut device, &line);
    let seqs: Vec<u16> = frames(&out).iter().map(|f| f.1).collect();
    assert_eq!(seqs, [10, 11, 12, 13]);
}
