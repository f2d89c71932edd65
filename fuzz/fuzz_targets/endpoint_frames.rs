//! The device endpoint on *intact* frames with arbitrary payloads: the fuzz data is cut into
//! requests (a kind selector byte, a length byte, then the payload bytes), each sent as a
//! frame with a good CRC, so the fuzzer reaches the payload decoders and the controllers.
//! With the session open, every frame of a request kind must get exactly one reply, with its
//! sequence number, in order; frames of a reply kind or of kind `0x00` none.
#![no_main]

use libfuzzer_sys::fuzz_target;
use serde::ser::{Serialize, SerializeTuple, Serializer};
use swarm_core::Fx;
use swarm_core::ant::AntParams;
use swarm_core::bee::BeeParams;
use swarm_core::fly::FlyParams;
use swarm_core::li::{LiDevice, LiParams};
use swarm_core::wang::WangParams;
use swarm_core::wire::{
    self, AntDevice, BeeDevice, Configure, Controller, DeviceEndpoint, FlyDevice, Hello,
    MAX_FRAME, WangDevice, kind,
};

/// Serializes as its bytes, with no length prefix.
struct Raw<'a>(&'a [u8]);

impl Serialize for Raw<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(self.0.len())?;
        for b in self.0 {
            t.serialize_element(b)?;
        }
        t.end()
    }
}

const KINDS: [u8; 20] = [
    kind::HELLO,
    kind::CONFIGURE,
    kind::PING,
    kind::STATS_REQUEST,
    kind::ANT_PLAN_REQUEST,
    kind::ANT_RESOLVE_REQUEST,
    kind::BEE_STEP_REQUEST,
    kind::WANG_ADVECT_REQUEST,
    kind::WANG_SEPARATE_REQUEST,
    kind::FLY_STEP_REQUEST,
    kind::LI_STEP_REQUEST,
    kind::ANT_PLAN_REPLY,
    kind::WANG_SEPARATE_REPLY,
    kind::FLY_STEP_REPLY,
    kind::LI_STEP_REPLY,
    kind::ERROR_REPLY,
    0x00,
    0x09,
    0x42,
    0xff,
];

fn run<C: Controller, const RX: usize, const TX: usize>(
    mut dev: DeviceEndpoint<C, RX, TX>,
    mut data: &[u8],
) {
    let hash = dev.identity().params_hash;
    let mut line = Vec::new();
    erased::Msg::put(&Hello, &mut line, 0);
    let configure = Configure {
        session: 1,
        params_hash: hash,
        reset_stats: true,
    };
    erased::Msg::put(&configure, &mut line, 1);
    let mut expect = vec![0u16, 1];
    let mut seq = 2u16;
    let mut out = vec![0u8; MAX_FRAME * 2];
    while let [sel, len, rest @ ..] = data {
        let kind = KINDS[usize::from(*sel) % KINDS.len()];
        let n = usize::from(*len).min(rest.len());
        let (payload, tail) = rest.split_at(n);
        data = tail;
        // Long payloads: repeat the bytes up to 700 (a full bee request is up to 930).
        let mut p = payload.to_vec();
        if sel & 0x80 != 0 && !p.is_empty() {
            while p.len() < 700 {
                p.extend_from_slice(payload);
            }
        }
        let len = wire::encode_frame(kind, seq, &Raw(&p), &mut out).unwrap();
        line.extend_from_slice(&out[..len]);
        // A request is answered unless it is longer than the receive buffer (dropped as
        // oversize, it has no trustworthy seq); a reply kind or 0x00 never is.
        if !kind::never_answered(kind) && len - 1 <= RX {
            expect.push(seq);
        }
        seq = seq.wrapping_add(1);
    }
    let mut got = Vec::new();
    dev.serve(&line, |r| {
        assert_eq!(r.iter().position(|&b| b == 0), Some(r.len() - 1));
        let mut body = r[..r.len() - 1].to_vec();
        let frame = wire::decode_frame(&mut body).expect("a reply is a valid frame");
        got.push(frame.header.seq);
        Ok::<(), ()>(())
    })
    .unwrap();
    assert_eq!(got, expect);
}

/// Encodes a typed message without generics in the closure above.
mod erased {
    pub trait Msg {
        fn put(&self, line: &mut Vec<u8>, seq: u16);
    }
    impl<M: swarm_core::wire::Message> Msg for M {
        fn put(&self, line: &mut Vec<u8>, seq: u16) {
            let mut out = [0u8; 128];
            let n = swarm_core::wire::encode_message(seq, self, &mut out).unwrap();
            line.extend_from_slice(&out[..n]);
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&mode, data)) = data.split_first() else {
        return;
    };
    match mode % 10 {
        0 => run(
            AntDevice::<f32>::new(AntParams::default(), "fuzz").unwrap(),
            data,
        ),
        1 => run(
            AntDevice::<Fx>::new(AntParams::default(), "fuzz").unwrap(),
            data,
        ),
        2 => run(
            BeeDevice::<f32>::new(BeeParams::default(), "fuzz").unwrap(),
            data,
        ),
        3 => run(
            BeeDevice::<Fx>::new(BeeParams::default(), "fuzz").unwrap(),
            data,
        ),
        4 => run(
            WangDevice::<f32>::new(WangParams::default(), "fuzz").unwrap(),
            data,
        ),
        5 => run(
            WangDevice::<Fx>::new(WangParams::default(), "fuzz").unwrap(),
            data,
        ),
        6 => run(
            FlyDevice::<f32>::new(FlyParams::default(), "fuzz").unwrap(),
            data,
        ),
        7 => run(
            FlyDevice::<Fx>::new(FlyParams::default(), "fuzz").unwrap(),
            data,
        ),
        8 => run(
            LiDevice::<f32>::new(LiParams::default(), "fuzz").unwrap(),
            data,
        ),
        _ => run(
            LiDevice::<Fx>::new(LiParams::default(), "fuzz").unwrap(),
            data,
        ),
    }
});
