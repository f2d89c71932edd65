//! The device endpoint on arbitrary bytes, for every controller and both scalars, with or
//! without an open session. Nothing may panic or hang; every reply must be one well-formed
//! frame; there are never more replies than delimiters; and after any bytes, a `0x00` and an
//! intact Ping are answered with exactly its Pong.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarm_core::Fx;
use swarm_core::ant::AntParams;
use swarm_core::bee::BeeParams;
use swarm_core::fly::FlyParams;
use swarm_core::wang::WangParams;
use swarm_core::wire::{
    self, AntDevice, BeeDevice, Configure, Controller, DeviceEndpoint, FlyDevice, Hello,
    MAX_FRAME, Ping, Pong, WangDevice,
};

fn frame<M: wire::Message>(seq: u16, msg: &M) -> Vec<u8> {
    let mut out = vec![0u8; MAX_FRAME];
    let n = wire::encode_message(seq, msg, &mut out).unwrap();
    out.truncate(n);
    out
}

fn run<C: Controller, const RX: usize, const TX: usize>(
    mut dev: DeviceEndpoint<C, RX, TX>,
    open: bool,
    step: usize,
    data: &[u8],
) {
    if open {
        let hash = dev.identity().params_hash;
        let mut line = frame(1, &Hello);
        line.extend(frame(
            2,
            &Configure {
                session: 1,
                params_hash: hash,
                reset_stats: true,
            },
        ));
        let mut n = 0;
        dev.serve(&line, |_| {
            n += 1;
            Ok::<(), ()>(())
        })
        .unwrap();
        assert_eq!(n, 2);
    }
    let mut replies = 0usize;
    for chunk in data.chunks(step) {
        let mut input = chunk;
        while let Some((reply, rest)) = dev.feed(input) {
            assert!(rest.len() < input.len(), "feed must make progress");
            input = rest;
            replies += 1;
            assert_eq!(reply.iter().position(|&b| b == 0), Some(reply.len() - 1));
            let mut body = reply[..reply.len() - 1].to_vec();
            assert!(wire::decode_frame(&mut body).is_ok());
        }
    }
    assert!(replies <= data.iter().filter(|&&b| b == 0).count());

    // Resynchronisation: a delimiter, then an intact Ping, is answered with its Pong.
    let mut line = vec![0u8];
    line.extend(frame(0xBEEF, &Ping { nonce: 0x5EED }));
    let mut got = Vec::new();
    dev.serve(&line, |r| {
        got.push(r.to_vec());
        Ok::<(), ()>(())
    })
    .unwrap();
    assert_eq!(got.last(), Some(&frame(0xBEEF, &Pong { nonce: 0x5EED })));
}

fuzz_target!(|data: &[u8]| {
    let Some((&mode, data)) = data.split_first() else {
        return;
    };
    let open = mode & 1 != 0;
    let step = usize::from(mode >> 4) + 1;
    match (mode >> 1) % 8 {
        0 => run(
            AntDevice::<f32>::new(AntParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
        1 => run(
            AntDevice::<Fx>::new(AntParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
        2 => run(
            BeeDevice::<f32>::new(BeeParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
        3 => run(
            BeeDevice::<Fx>::new(BeeParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
        4 => run(
            WangDevice::<f32>::new(WangParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
        5 => run(
            WangDevice::<Fx>::new(WangParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
        6 => run(
            FlyDevice::<f32>::new(FlyParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
        _ => run(
            FlyDevice::<Fx>::new(FlyParams::default(), "fuzz").unwrap(),
            open,
            step,
            data,
        ),
    }
});
