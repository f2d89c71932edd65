//! The frame layer on arbitrary bytes: `decode_frame` on the input as one frame, every
//! message type's payload decoder on it, and the streaming `Accumulator` fed the input in
//! chunks whose sizes come from the input itself. Nothing may panic or hang, and the
//! accumulator's accounting must hold.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarm_core::Fx;
use swarm_core::wire::{
    self, Accumulator, AntPlanReply, AntPlanRequest, AntResolveRequest, BeeStepReply,
    BeeStepRequest, Configure, DeviceStats, ErrorReply, Event, Identity, MAX_FRAME, Ping,
};

fn payloads(p: &[u8]) {
    let _ = wire::decode_payload::<AntPlanRequest<f32>>(p);
    let _ = wire::decode_payload::<AntPlanRequest<Fx>>(p);
    let _ = wire::decode_payload::<AntResolveRequest<f32>>(p);
    let _ = wire::decode_payload::<AntPlanReply<Fx>>(p);
    let _ = wire::decode_payload::<BeeStepRequest<f32>>(p);
    let _ = wire::decode_payload::<BeeStepRequest<Fx>>(p);
    let _ = wire::decode_payload::<BeeStepReply<f32>>(p);
    let _ = wire::decode_payload::<Identity>(p);
    let _ = wire::decode_payload::<Configure>(p);
    let _ = wire::decode_payload::<Ping>(p);
    let _ = wire::decode_payload::<DeviceStats>(p);
    let _ = wire::decode_payload::<ErrorReply>(p);
}

fuzz_target!(|data: &[u8]| {
    // One delimited frame.
    let mut one = data.to_vec();
    if let Ok(frame) = wire::decode_frame(&mut one) {
        payloads(frame.payload);
    }
    payloads(data);

    // A stream, in chunks of 1..=16 bytes chosen by the data.
    let step = usize::from(data.first().copied().unwrap_or(0) % 16) + 1;
    let mut small = Accumulator::<64>::new();
    let mut big = Accumulator::<MAX_FRAME>::new();
    let mut events = 0usize;
    for chunk in data.chunks(step) {
        let mut rest = chunk;
        while let Some((event, r)) = small.feed(rest) {
            assert!(r.len() < rest.len(), "feed must make progress");
            rest = r;
            events += 1;
            if let Event::Frame(f) = event {
                payloads(f.payload);
            }
        }
        for &b in chunk {
            let _ = big.push(b);
        }
    }
    let zeros = data.iter().filter(|&&b| b == 0).count();
    let s = small.stats();
    assert_eq!(events, (s.frames_ok + s.resyncs()) as usize);
    assert_eq!(events + s.empty as usize, zeros);
    let tail = data.iter().rev().take_while(|&&b| b != 0).count();
    assert_eq!(small.pending(), tail);
    assert_eq!(big.pending(), tail);
});
