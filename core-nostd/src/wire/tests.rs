//! Tests of the device endpoint: the pinned session transcript of `docs/protocol.md`, the
//! session rules, bit-for-bit agreement with direct controller calls, and properties over
//! random, corrupted, truncated and concatenated byte streams.

use proptest::prelude::*;
use serde::Serialize;
use serde::de::DeserializeOwned;

use super::test_util::{code_bytes, frame_of, hex};
use super::*;
use crate::ant::{
    self, AntNeighbor, AntObject, AntParams, AntPlan, AntState, Label, MotionState, StopReason,
    StopTimer, Surface,
};
use crate::bee::{self, BeeNeighbor, BeeParams, BeeState, ObstacleSense};
use crate::fly::{
    self, FlyParams, FlyState, Neighbour, STIMULUS_PREDATOR, Stimulus, Surface as Surface3,
};
use crate::rand::rand;
use crate::wang::{self, AdvectFrame, Boundary, Close, WangParams, WangState};
use crate::{Error, Fx, Rect, Scalar, StepCtx, Vec2, Vec3};

// ---- helpers ----

/// Every reply frame the device sends for `input`, in order.
fn replies<C: Controller, const RX: usize, const TX: usize>(
    dev: &mut DeviceEndpoint<C, RX, TX>,
    input: &[u8],
) -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    dev.serve(input, |r| {
        out.push(r.to_vec());
        Ok::<(), ()>(())
    })
    .unwrap();
    out
}

/// The refusal in `r`, as its variant and the field it names (for the errors that name one).
fn refusal<T>(r: Result<T>) -> Option<(&'static str, &'static str)> {
    match r {
        Err(Error::NonFinite { field, .. }) => Some(("NonFinite", field)),
        Err(Error::OutOfRange { field, .. }) => Some(("OutOfRange", field)),
        Err(Error::Inconsistent { field, .. }) => Some(("Inconsistent", field)),
        _ => None,
    }
}

/// Arbitrary numbers without end: `words` over and over, each read by `from_bits`.
fn arbitrary<'a, S>(words: &'a [u32], from_bits: impl Fn(u32) -> S + 'a) -> impl FnMut() -> S + 'a {
    let mut w = words.iter().copied().cycle();
    move || from_bits(w.next().unwrap_or(0))
}

/// The one reply frame the device sends for `req` (sequence number `seq`).
#[track_caller]
fn reply_to<C: Controller, const RX: usize, const TX: usize, M: Message>(
    dev: &mut DeviceEndpoint<C, RX, TX>,
    seq: u16,
    req: &M,
) -> Vec<u8> {
    let mut r = replies(dev, &frame_of(seq, req));
    assert_eq!(r.len(), 1, "one reply");
    r.remove(0)
}

/// Decodes one reply frame (with its delimiter) as `M`.
fn decode<M: Message>(frame: &[u8]) -> (Header, M) {
    let (last, body) = frame.split_last().unwrap();
    assert_eq!(*last, 0);
    assert!(!body.contains(&0));
    let mut body = body.to_vec();
    decode_message::<M>(&mut body).unwrap()
}

/// The header and error code of an `ErrorReply` frame.
fn error_code(frame: &[u8]) -> (u16, u8) {
    let (h, e) = decode::<ErrorReply>(frame);
    (h.seq, e.code)
}

/// A device with its session open (Hello, Configure with reset).
fn open<C: Controller, const RX: usize, const TX: usize>(
    dev: &mut DeviceEndpoint<C, RX, TX>,
    session: u32,
) {
    let hash = dev.identity().params_hash;
    let mut line = frame_of(0xfff0, &Hello);
    line.extend(frame_of(
        0xfff1,
        &Configure {
            session,
            params_hash: hash,
            reset_stats: true,
        },
    ));
    let r = replies(dev, &line);
    assert_eq!(r.len(), 2);
    assert_eq!(
        decode::<Configured>(&r[1]),
        (
            Header::new(kind::CONFIGURED, 0xfff1),
            Configured { session }
        )
    );
    assert_eq!(dev.state(), SessionState::Open { session });
}

fn ant_device<S: Scalar + Serialize + DeserializeOwned>() -> AntDevice<S> {
    AntDevice::<S>::new(AntParams::default(), "ant-test").unwrap()
}

fn bee_device<S: Scalar + Serialize + DeserializeOwned>() -> BeeDevice<S> {
    BeeDevice::<S>::new(BeeParams::default(), "bee-test").unwrap()
}

fn wang_device<S: Scalar + Serialize + DeserializeOwned>() -> WangDevice<S> {
    WangDevice::<S>::new(WangParams::default(), "wang-test").unwrap()
}

fn fly_device<S: Scalar + Serialize + DeserializeOwned>(params: FlyParams<S>) -> FlyDevice<S> {
    FlyDevice::<S>::new(params, "fly-test").unwrap()
}

/// A small deterministic generator for test inputs (counter-based, like the controllers).
struct Gen {
    seed: u32,
    n: u32,
}

impl Gen {
    fn new(seed: u32) -> Self {
        Gen { seed, n: 0 }
    }
    fn u32(&mut self) -> u32 {
        self.n += 1;
        rand(self.seed, 0xA11CE, self.n, 3)
    }
    fn below(&mut self, n: u32) -> u32 {
        self.u32() % n
    }
    fn unit(&mut self) -> f32 {
        (self.u32() >> 8) as f32 / (1u32 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }
    fn chance(&mut self, p: f32) -> bool {
        self.unit() < p
    }
    fn v2<S: Scalar>(&mut self, lo: f32, hi: f32) -> Vec2<S> {
        Vec2::new(
            S::from_f32(self.range(lo, hi)),
            S::from_f32(self.range(lo, hi)),
        )
    }
    fn v3<S: Scalar>(&mut self, lo: f32, hi: f32) -> Vec3<S> {
        Vec3::new(
            S::from_f32(self.range(lo, hi)),
            S::from_f32(self.range(lo, hi)),
            S::from_f32(self.range(lo, hi)),
        )
    }
    fn label(&mut self) -> Label {
        [Label::Nothing, Label::Food, Label::Nest][self.below(3) as usize]
    }
}

/// A random, mostly valid ant plan request (a few are invalid on purpose: error paths).
fn ant_plan_request<S: Scalar>(g: &mut Gen) -> AntPlanRequest<S> {
    let bounds = Rect::new(Vec2::from_f32(0.0, 0.0), Vec2::from_f32(100.0, 100.0));
    let pos = g.v2::<S>(1.0, 99.0);
    let a = g.range(-3.2, 3.2);
    let heading = Vec2::new(S::from_f32(a.cos()), S::from_f32(a.sin()));
    let mut state = AntState::exploring(1, pos, heading);
    state.label = g.label();
    state.origin = if state.label == Label::Nest {
        1
    } else {
        g.below(4) as u16
    };
    state.arrival = g.v2(0.0, 100.0);
    state.motion = [
        MotionState::BasicMovement,
        MotionState::InteractNeighbors,
        MotionState::InteractEnvironment,
    ][g.below(3) as usize];
    if g.chance(0.2) {
        state.motion = MotionState::Stop;
        let reason = match state.label {
            Label::Food => StopReason::DroppingFood,
            _ => [StopReason::Casual, StopReason::CollectingFood][g.below(2) as usize],
        };
        state.stop = Some(StopTimer {
            reason,
            remaining: 1 + g.below(3) as u16,
            place: 1,
        });
    }
    let mut frame = WirePlanFrame::new(bounds);
    for i in 0..g.below(WIRE_ANT_NEIGHBOURS as u32 + 1) {
        let label = g.label();
        let nest = g.below(3) as u16;
        let _ = frame.neighbours.push(AntNeighbor {
            id: 100 + i,
            pos: pos + g.v2(-2.0, 2.0),
            label,
            nest,
            origin: if label == Label::Nest {
                nest
            } else {
                g.below(4) as u16
            },
            arrival: g.v2(0.0, 100.0),
        });
    }
    for _ in 0..g.below(WIRE_ANT_OBJECTS as u32 + 1) {
        let center = pos + g.v2(-3.0, 3.0);
        let radius = S::from_f32(g.range(0.5, 3.0));
        let o = match g.below(4) {
            0 => match Surface::seen_from(pos, center) {
                Some(surface) => AntObject::Obstacle(surface),
                None => continue,
            },
            1 => AntObject::Disturbance { center, radius },
            2 => AntObject::Food {
                id: g.below(4) as u16,
                center,
                radius,
            },
            _ => AntObject::Nest {
                id: g.below(3) as u16,
                center,
                radius,
            },
        };
        let _ = frame.objects.push(o);
    }
    let ctx = StepCtx {
        seed: g.u32(),
        agent: g.below(100),
        step: g.u32(),
    };
    AntPlanRequest { state, frame, ctx }
}

/// A random resolve request around `plan`.
fn ant_resolve_request<S: Scalar>(g: &mut Gen, plan: AntPlan<S>) -> AntResolveRequest<S> {
    let mut frame = WireResolveFrame::new(Rect::new(
        Vec2::from_f32(0.0, 0.0),
        Vec2::from_f32(100.0, 100.0),
    ));
    for _ in 0..g.below(WIRE_ANT_NEIGHBOURS as u32 + 1) {
        let _ = frame.neighbours.push(plan.predicted + g.v2(-2.0, 2.0));
    }
    // Obstacle surfaces near the ant, seen from its position; now and then one whose normal
    // is not a unit vector (refused: OutOfRange).
    for _ in 0..g.below(ant::SURFACES as u32 + 1) {
        let closest = plan.state.pos + g.v2(-1.5, 1.5);
        if let Some(mut surface) = Surface::seen_from(plan.state.pos, closest) {
            if g.chance(0.02) {
                surface.normal = surface.normal * S::from_f32(1.5);
            }
            let _ = frame.obstacles.push(surface);
        }
    }
    AntResolveRequest { plan, frame }
}

/// A random, mostly valid bee step request.
fn bee_request<S: Scalar>(g: &mut Gen) -> BeeStepRequest<S> {
    let pos = g.v3::<S>(-5.0, 5.0);
    let mut state = BeeState::new(pos, g.v3(-1.0, 1.0));
    state.density = S::from_f32(g.range(0.0, 0.2));
    let mut frame = WireBeeFrame::new(S::from_f32(g.range(0.0, 10.0)));
    for _ in 0..g.below(WIRE_BEE_NEIGHBOURS as u32 + 1) {
        let _ = frame.neighbours.push(BeeNeighbor {
            pos: pos + g.v3(-2.0, 2.0),
            vel: g.v3(-1.0, 1.0),
            density: S::from_f32(g.range(0.0, 0.2)),
        });
    }
    for _ in 0..g.below(WIRE_BEE_TARGETS as u32 + 1) {
        let _ = frame.targets.push(pos + g.v3(-3.0, 3.0));
    }
    if g.chance(0.5) {
        frame.goal = Some(g.v3(-10.0, 10.0));
    }
    if g.chance(0.5) {
        frame.obstacle = Some(ObstacleSense {
            point: pos + g.v3(-2.0, 2.0),
            normal: Vec3::new(S::ZERO, S::ZERO, -S::ONE),
        });
    }
    BeeStepRequest { state, frame }
}

/// A random, mostly valid fly step request: neighbours nearest first (one may carry the
/// insect's own id), a stimulus of either kind, a ground plane and walls as surfaces.
fn fly_request<S: Scalar>(g: &mut Gen) -> FlyStepRequest<S> {
    let pos = g.v3::<S>(-5.0, 5.0) + Vec3::new(S::ZERO, S::from_f32(6.0), S::ZERO);
    let mut state = FlyState::new(pos, g.v3(-3.0, 3.0));
    if g.chance(0.3) {
        state.escaping = true;
        state.escape_theta = S::from_f32(g.range(-1.57, 0.0));
    }
    let agent = g.below(20);
    let mut frame = WireFlyFrame::new();
    let mut dist = 0.0;
    for k in 0..g.below(WIRE_FLY_NEIGHBOURS as u32 + 1) {
        dist += g.range(0.05, 0.6);
        let d = g.v3::<f32>(-1.0, 1.0);
        let len = d.length().max(1e-3);
        let off = Vec3::new(
            S::from_f32(d.x / len * dist),
            S::from_f32(d.y / len * dist),
            S::from_f32(d.z / len * dist),
        );
        let id = if g.chance(0.05) { agent } else { 100 + k };
        let _ = frame.neighbours.push(Neighbour {
            id,
            pos: pos + off,
            vel: g.v3(-3.0, 3.0),
        });
    }
    if g.chance(0.5) {
        frame.stimulus = Some(Stimulus {
            pos: pos + g.v3(-6.0, 6.0),
            kind: g.below(2) as u8,
        });
    }
    if g.chance(0.5) {
        let _ = frame.surfaces.push(Surface3 {
            point: Vec3::new(pos.x, S::ZERO, pos.z),
            normal: Vec3::new(S::ZERO, S::ONE, S::ZERO),
        });
    }
    for _ in 0..g.below(4) {
        let _ = frame.surfaces.push(Surface3 {
            point: pos + Vec3::new(S::from_f32(g.range(0.2, 2.0)), S::ZERO, S::ZERO),
            normal: Vec3::new(-S::ONE, S::ZERO, S::ZERO),
        });
    }
    FlyStepRequest {
        state,
        frame,
        ctx: StepCtx {
            seed: g.u32(),
            agent,
            step: g.u32(),
        },
    }
}

/// What a device must answer to `req` (kind `M::KIND`, `seq`): the reply frame of the direct
/// call, or the error reply of its error.
fn expected<R: Message>(seq: u16, direct: Result<R>) -> Vec<u8> {
    match direct {
        Ok(reply) => frame_of(seq, &reply),
        Err(e) => frame_of(seq, &ErrorReply::new(&e)),
    }
}

// ---- the pinned transcript (docs/protocol.md, section 11) ----

/// The host's bytes and the device's answers of the worked session of `docs/protocol.md`,
/// computed with the Python reference of its appendix B. Returns (host bytes, device bytes)
/// per step.
fn transcript() -> Vec<(Vec<u8>, Vec<u8>)> {
    vec![
        // 1. A lone 0x00, then Configure (seq 1) before Hello: NoSession (14).
        (
            hex("00 04 03 03 01 0b 2a c3 8b a1 c0 ec f6 b8 9a 7e 03 12 74 00"),
            hex("04 03 0f 01 04 0e ce fd 00"),
        ),
        // 2. Hello (seq 2) -> Identity.
        (
            hex("04 03 01 02 03 4e 4e 00"),
            hex(
                "04 03 02 02 02 03 01 01 03 08 04 19 06 c3 03 10 c3 8b a1 c0 ec f6 b8 9a 7e
                 08 61 6e 74 2d 6e 6f 64 65 c4 0b 00",
            ),
        ),
        // 3. Configure (seq 3, session 42, the device's hash, no reset) -> Configured.
        (
            hex("04 03 03 03 0b 2a c3 8b a1 c0 ec f6 b8 9a 7e 03 d4 fe 00"),
            hex("04 03 04 03 04 2a 57 e9 00"),
        ),
        // 4. Garbage, then a Ping with a corrupted CRC: both dropped, no reply.
        (hex("de ad 00 04 03 05 04 07 84 86 88 08 46 0b 00"), vec![]),
        // 5. Ping (seq 4, nonce 0xdeadbeef) -> Pong.
        (
            hex("04 03 05 04 08 ef fd b6 f5 0d b6 35 00"),
            hex("04 03 06 04 08 ef fd b6 f5 0d c3 fd 00"),
        ),
        // 6. StatsRequest (seq 5) -> DeviceStats.
        (
            hex("04 03 07 05 03 79 65 00"),
            hex("04 03 08 05 04 05 01 01 01 01 06 01 0d 05 03 01 01 05 01 2a 60 7e 00"),
        ),
        // 7. Configure (seq 6) with another hash: ParamsMismatch (15), session closed.
        (
            hex("04 03 03 06 0b 2b c2 8b a1 c0 ec f6 b8 9a 7e 03 16 09 00"),
            hex("04 03 0f 06 04 0f 7f 68 00"),
        ),
    ]
}

#[test]
fn pinned_session_transcript() {
    // Reporting a 16-byte receive buffer, as the firmware's ant-node does (its PL011 FIFO).
    let mut dev = AntDevice::<f32>::new(AntParams::default(), "ant-node").unwrap();
    dev.set_rx_buffer(16);
    for (i, (host, device)) in transcript().into_iter().enumerate() {
        let got: Vec<u8> = replies(&mut dev, &host).concat();
        assert_eq!(got, device, "step {}", i + 1);
    }
    assert_eq!(dev.state(), SessionState::Greeted);
}

#[test]
fn pinned_transcript_messages() {
    // The same frames, message by message (what a client encodes and decodes).
    let params = AntParams::<f32>::default();
    let hash = params_hash(&params).unwrap();
    assert_eq!(hash, 0x7e34_e3b6_c808_45c3);
    assert_eq!(frame_of(2, &Hello), hex("04 03 01 02 03 4e 4e 00"));
    let mut id = Identity::of(&params, MAX_ANT_FRAME + 1, "ant-node").unwrap();
    id.rx_buffer = 16;
    let mut dev = AntDevice::<f32>::new(params, "ant-node").unwrap();
    dev.set_rx_buffer(16);
    assert_eq!(id, dev.identity());
    assert_eq!(id.window(MAX_ANT_FRAME), 1);
    let t = transcript();
    assert_eq!(frame_of(2, &id), t[1].1);
    let configure = Configure {
        session: 42,
        params_hash: hash,
        reset_stats: false,
    };
    assert_eq!(frame_of(3, &configure), t[2].0);
    assert_eq!(frame_of(3, &Configured { session: 42 }), t[2].1);
    assert_eq!(
        frame_of(
            1,
            &ErrorReply {
                code: ErrorReply::NO_SESSION
            }
        ),
        t[0].1
    );
    assert_eq!(frame_of(4, &Ping { nonce: 0xdead_beef }), t[4].0);
    assert_eq!(frame_of(4, &Pong { nonce: 0xdead_beef }), t[4].1);
    assert_eq!(frame_of(5, &StatsRequest), t[5].0);
    let stats = DeviceStats {
        link: Stats {
            frames_ok: 5,
            crc_errors: 1,
            cobs_errors: 1,
            truncated: 0,
            version_errors: 0,
            oversize: 0,
            empty: 1,
            bytes_dropped: 13,
        },
        requests: 5,
        replies: 3,
        errors: 1,
        decode_errors: 0,
        ignored: 0,
        session: Some(42),
    };
    assert_eq!(frame_of(5, &stats), t[5].1);
    assert_eq!(decode::<DeviceStats>(&t[5].1).1, stats);
}

// ---- session rules ----

#[test]
fn decisions_are_refused_before_the_session() {
    let mut dev = ant_device::<f32>();
    let mut g = Gen::new(1);
    let req = ant_plan_request::<f32>(&mut g);
    // Idle: NoSession.
    let r = replies(&mut dev, &frame_of(10, &req));
    assert_eq!(error_code(&r[0]), (10, ErrorReply::NO_SESSION));
    // Greeted (Hello, no Configure): NoSession.
    let r = replies(&mut dev, &frame_of(11, &Hello));
    assert_eq!(decode::<Identity>(&r[0]).0.seq, 11);
    assert_eq!(dev.state(), SessionState::Greeted);
    let r = replies(&mut dev, &frame_of(12, &req));
    assert_eq!(error_code(&r[0]), (12, ErrorReply::NO_SESSION));
    // Open: served.
    open(&mut dev, 5);
    let r = replies(&mut dev, &frame_of(13, &req));
    assert_eq!(r[0], expected(13, req.run(&AntParams::default())));
    // A new Hello closes the session.
    replies(&mut dev, &frame_of(14, &Hello));
    assert_eq!(dev.state(), SessionState::Greeted);
    let r = replies(&mut dev, &frame_of(15, &req));
    assert_eq!(error_code(&r[0]), (15, ErrorReply::NO_SESSION));
    assert_eq!(dev.stats().session, None);
}

#[test]
fn configure_with_other_params_is_refused() {
    let mut dev = ant_device::<Fx>();
    let other = AntParams::<Fx> {
        speed: Fx::from_f32(2.0),
        ..AntParams::default()
    };
    let bad = Configure {
        session: 1,
        params_hash: params_hash(&other).unwrap(),
        reset_stats: false,
    };
    let mut line = frame_of(1, &Hello);
    line.extend(frame_of(2, &bad));
    let r = replies(&mut dev, &line);
    assert_eq!(error_code(&r[1]), (2, ErrorReply::PARAMS_MISMATCH));
    assert_eq!(dev.state(), SessionState::Greeted);
    // The host's handshake check says why, naming the hashes.
    let identity = decode::<Identity>(&r[0]).1;
    let want = Identity::of(&other, MAX_ANT_FRAME, "").unwrap();
    let msg = identity.check(&want).unwrap_err().to_string();
    assert!(
        msg.contains(&format!(
            "params hash {:#018x} ≠ {:#018x}",
            identity.params_hash, want.params_hash
        )),
        "{msg}"
    );
    // Retrying with the right hash opens the session.
    open(&mut dev, 2);
}

#[test]
fn identity_says_what_the_device_runs() {
    use crate::{MathBackend, ScalarKind};
    let ant = ant_device::<Fx>().identity();
    let bee = bee_device::<f32>().identity();
    // What each runs (controller, scalar, math backend) and its capacities (neighbours,
    // objects, targets, surfaces).
    let ant_runs = (
        ControllerKind::ANT,
        ScalarKind::I16F16,
        MathBackend::Integer,
    );
    let bee_runs = (ControllerKind::BEE, ScalarKind::F32, MathBackend::F32);
    let wang = wang_device::<Fx>().identity();
    let wang_runs = (
        ControllerKind::WANG,
        ScalarKind::I16F16,
        MathBackend::Integer,
    );
    let fly = fly_device::<f32>(FlyParams::default()).identity();
    let fly_runs = (ControllerKind::FLY, ScalarKind::F32, MathBackend::F32);
    for (id, runs, capacities) in [
        (&ant, ant_runs, (8, 4, 0, 6)),
        (&bee, bee_runs, (16, 0, 16, 0)),
        (&wang, wang_runs, (8, 0, 0, 0)),
        (&fly, fly_runs, (16, 0, 0, 4)),
    ] {
        let c = id.capacities;
        assert_eq!((id.controller, id.scalar, id.math), runs);
        assert_eq!((c.neighbours, c.objects, c.targets, c.surfaces), capacities);
        // A new endpoint buffers nothing beyond the frame it serves.
        assert_eq!(id.rx_buffer, 0);
    }
    assert_eq!(usize::from(ant.capacities.surfaces), ant::SURFACES);
    let mut dev = ant_device::<f32>();
    dev.set_rx_buffer(16);
    assert_eq!(dev.identity().rx_buffer, 16);
    assert_eq!(usize::from(ant.max_frame), MAX_ANT_FRAME + 1);
    // The buffer sizes of docs/protocol.md, section 10.7.
    assert_eq!((MAX_ANT_FRAME, MAX_BEE_FRAME), (450, 941));
    assert_eq!((MAX_ANT_REPLY_FRAME, MAX_BEE_REPLY_FRAME), (82, 130));
    assert_eq!((MAX_WANG_FRAME, MAX_WANG_REPLY_FRAME), (214, 79));
    assert_eq!(usize::from(wang.max_frame), MAX_WANG_FRAME + 1);
    assert_eq!(ControllerKind::WANG.to_string(), "wang");
    assert_eq!(
        wang.params_hash,
        params_hash(&WangParams::<Fx>::default()).unwrap()
    );
    assert_eq!(usize::from(bee_device::<Fx>().identity().max_frame), 942);
    assert_eq!((MAX_FLY_FRAME, MAX_FLY_REPLY_FRAME), (760, 79));
    assert_eq!(usize::from(fly.max_frame), MAX_FLY_FRAME + 1);
    assert_eq!(
        (ControllerKind::FLY, ControllerKind::FLY.to_string()),
        (ControllerKind(3), "fly".to_string())
    );
    assert_eq!(
        (
            usize::from(fly.capacities.neighbours),
            usize::from(fly.capacities.surfaces)
        ),
        (WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES)
    );
    assert_eq!(
        fly.params_hash,
        params_hash(&FlyParams::<f32>::midge()).unwrap()
    );
    let fly_fx = fly_device::<Fx>(FlyParams::default()).identity();
    assert_eq!(
        (fly_fx.controller, fly_fx.scalar, fly_fx.math),
        (
            ControllerKind::FLY,
            ScalarKind::I16F16,
            MathBackend::Integer
        )
    );
    assert_eq!(
        fly_fx.params_hash,
        params_hash(&FlyParams::<f32>::midge().cast::<Fx>()).unwrap()
    );
    assert_ne!(fly_fx.params_hash, fly.params_hash);
    // Another preset, another hash; bad parameters: no device.
    assert_ne!(
        fly_device::<f32>(FlyParams::fruitfly())
            .identity()
            .params_hash,
        fly.params_hash
    );
    let p = FlyParams::<f32> {
        max_speed: 10.0, // γ·max_speed·Δt = 1.116 > ½
        ..FlyParams::midge()
    };
    assert_eq!(
        FlyDevice::<f32>::new(p, "x").err(),
        Some(Error::BadParam { field: "max_speed" })
    );
    assert_eq!(ant.name, "ant-test");
    assert_eq!(
        bee.params_hash,
        params_hash(&BeeParams::<f32>::default()).unwrap()
    );
    // Bad parameters or a long name: no device.
    let p = AntParams::<f32> {
        speed: -1.0,
        ..AntParams::default()
    };
    assert_eq!(
        AntDevice::<f32>::new(p, "x").err(),
        Some(Error::BadParam { field: "speed" })
    );
    assert_eq!(
        AntDevice::<f32>::new(AntParams::default(), &"x".repeat(25)).err(),
        Some(Error::BadParam { field: "name" })
    );
}

#[test]
fn ping_and_stats_work_in_every_state() {
    let mut dev = bee_device::<Fx>();
    let r = replies(&mut dev, &frame_of(1, &Ping { nonce: 77 }));
    assert_eq!(
        decode::<Pong>(&r[0]),
        (Header::new(kind::PONG, 1), Pong { nonce: 77 })
    );
    let r = replies(&mut dev, &frame_of(2, &StatsRequest));
    let s = decode::<DeviceStats>(&r[0]).1;
    assert_eq!((s.link.frames_ok, s.requests, s.replies), (2, 2, 1));
    assert_eq!(s.session, None);
    open(&mut dev, 9);
    let r = replies(&mut dev, &frame_of(3, &StatsRequest));
    let s = decode::<DeviceStats>(&r[0]).1;
    // Reset by the Configure, which with its Configured is not counted: only this request.
    assert_eq!((s.link.frames_ok, s.requests, s.replies), (1, 1, 0));
    assert_eq!(s.session, Some(9));
    assert_eq!(dev.stats().replies, 1);
}

#[test]
fn every_kind_that_is_not_a_request_of_this_device() {
    let mut dev = ant_device::<f32>();
    open(&mut dev, 1);
    // Reply kinds: dropped, counted, unanswered.
    let mut line = frame_of(1, &Pong { nonce: 1 });
    line.extend(frame_of(2, &ErrorReply { code: 1 }));
    line.extend(frame_of(3, &Configured { session: 1 }));
    line.extend(frame_of(
        4,
        &AntResolveReply {
            state: AntState::<f32>::exploring(
                0,
                Vec2::from_f32(1.0, 1.0),
                Vec2::from_f32(1.0, 0.0),
            ),
        },
    ));
    line.extend(frame_of(
        4,
        &FlyStepReply::<f32> {
            decision: fly::FlyDecision::default(),
            state: FlyState::default(),
        },
    ));
    assert!(replies(&mut dev, &line).is_empty());
    assert_eq!(dev.stats().ignored, 5);
    // A bee request to an ant device, and unknown kinds: UnknownKind.
    let mut g = Gen::new(2);
    let mut bee = bee_request::<f32>(&mut g);
    bee.frame.neighbours.clear(); // small enough for an ant device's receive buffer
    bee.frame.targets.clear();
    let mut line = frame_of(5, &bee);
    for (i, k) in [0x09u8, 0x0e, 0x14, 0x30, 0x40, 0x42, 0x80, 0xff]
        .into_iter()
        .enumerate()
    {
        line.extend(frame_of_kind(k, 6 + i as u16, &()));
    }
    let r = replies(&mut dev, &line);
    let codes: Vec<_> = r.iter().map(|f| error_code(f)).collect();
    assert_eq!(
        codes,
        (5..14)
            .map(|s| (s, ErrorReply::UNKNOWN_KIND))
            .collect::<Vec<_>>()
    );
    assert_eq!(dev.stats().decode_errors, 9);
}

fn frame_of_kind<T: Serialize + ?Sized>(kind: u8, seq: u16, msg: &T) -> Vec<u8> {
    let mut out = vec![0u8; 2 * MAX_FRAME];
    let n = encode_frame(kind, seq, msg, &mut out).unwrap();
    out.truncate(n);
    out
}

#[test]
fn payloads_that_do_not_decode_get_payload_errors() {
    let mut dev = ant_device::<f32>();
    open(&mut dev, 1);
    let mut line = Vec::new();
    // Hello and StatsRequest with a stray byte, a Ping cut short, a plan request of junk, a
    // resolve request with too many neighbours, a bool that is 2.
    line.extend(frame_of_kind(kind::HELLO, 1, &0u8));
    line.extend(frame_of_kind(kind::STATS_REQUEST, 2, &0u8));
    line.extend(frame_of_kind(kind::PING, 3, &()));
    line.extend(frame_of_kind(kind::ANT_PLAN_REQUEST, 4, &[0xffu8; 7]));
    let mut g = Gen::new(3);
    let plan = ant_plan_request::<f32>(&mut g)
        .run(&AntParams::default())
        .map(|r| r.plan);
    let plan = plan.unwrap_or(AntPlan {
        state: AntState::exploring(0, Vec2::from_f32(5.0, 5.0), Vec2::from_f32(0.0, 1.0)),
        predicted: Vec2::from_f32(5.0, 6.0),
    });
    let nine: heapless::Vec<Vec2<f32>, 9> = (0..9).map(|_| plan.predicted).collect();
    line.extend(frame_of_kind(
        kind::ANT_RESOLVE_REQUEST,
        5,
        &(
            plan,
            Rect::<f32>::new(Vec2::from_f32(0.0, 0.0), Vec2::from_f32(100.0, 100.0)),
            nine,
        ),
    ));
    line.extend(frame_of_kind(
        kind::CONFIGURE,
        6,
        &(1u8, 1u8, 2u8), // reset_stats = 2
    ));
    let r = replies(&mut dev, &line);
    let codes: Vec<_> = r.iter().map(|f| error_code(f)).collect();
    assert_eq!(
        codes,
        (1..7).map(|s| (s, ErrorReply::PAYLOAD)).collect::<Vec<_>>()
    );
    let s = dev.stats();
    assert_eq!((s.decode_errors, s.errors), (6, 6));
    assert_eq!(dev.state(), SessionState::Open { session: 1 });
}

#[test]
fn a_frame_of_another_version_is_answered_with_version() {
    let mut dev = ant_device::<f32>();
    // A CRC-valid Ping of version 2 (the previous release), seq 0x1234, and a version-2
    // ErrorReply (not answered).
    let v2 = |kind: u8, seq: u16, payload: &[u8]| {
        let mut raw = vec![2, kind];
        raw.extend_from_slice(&seq.to_le_bytes());
        raw.extend_from_slice(payload);
        raw.extend_from_slice(&CRC16.checksum(&raw).to_le_bytes());
        let mut out = vec![0u8; 64];
        let n = cobs::try_encode(&raw, &mut out).unwrap();
        out.truncate(n);
        out.push(0);
        out
    };
    let mut line = v2(kind::PING, 0x1234, &[5]);
    // docs/protocol.md, section 10.4 (computed with the Python reference, appendix A).
    assert_eq!(line, hex("08 02 05 34 12 05 1b c5 00"));
    line.extend(v2(kind::ERROR_REPLY, 0x1235, &[1]));
    let r = replies(&mut dev, &line);
    assert_eq!(r.len(), 1);
    assert_eq!(r[0][1], PROTOCOL_VERSION); // answered in our version
    assert_eq!(r[0], hex("08 03 0f 34 12 0a 0e f6 00"));
    assert_eq!(error_code(&r[0]), (0x1234, ErrorReply::VERSION));
    let s = dev.stats();
    assert_eq!((s.link.version_errors, s.errors, s.requests), (2, 1, 0));
    assert_eq!(s.ignored, 1); // the ErrorReply
}

#[test]
fn bad_frames_are_counted_and_unanswered() {
    let mut dev = ant_device::<f32>();
    open(&mut dev, 3);
    let good = frame_of(1, &Ping { nonce: 1 });
    let mut bad_crc = good.clone();
    bad_crc[6] ^= 0x10;
    let mut line = Vec::new();
    line.extend_from_slice(&bad_crc);
    line.extend_from_slice(b"\x01\x02\x03\x00"); // COBS-valid but 2 raw bytes: Truncated
    line.extend_from_slice(b"\x09\x01\x00"); // COBS error
    line.extend(std::iter::repeat_n(0x55u8, MAX_ANT_FRAME + 10)); // oversize
    line.push(0);
    line.extend_from_slice(&good);
    let r = replies(&mut dev, &line);
    assert_eq!(r, vec![frame_of(1, &Pong { nonce: 1 })]);
    let s = dev.stats();
    assert_eq!(
        (
            s.link.crc_errors,
            s.link.truncated,
            s.link.cobs_errors,
            s.link.oversize
        ),
        (1, 1, 1, 1)
    );
    assert_eq!(s.link.resyncs(), 4);
    assert_eq!(
        s.link.bytes_dropped as usize,
        (bad_crc.len() - 1) + 3 + 2 + MAX_ANT_FRAME + 10
    );
}

#[test]
fn a_frame_of_exactly_rx_bytes_is_served() {
    // The longest ant request (a plan request with every list full, Fx, widest varints)
    // fits an AntDevice.
    let mut dev = ant_device::<Fx>();
    open(&mut dev, 1);
    let mut g = Gen::new(4);
    let mut req = ant_plan_request::<Fx>(&mut g);
    while req.frame.neighbours.len() < WIRE_ANT_NEIGHBOURS
        || req.frame.objects.len() < WIRE_ANT_OBJECTS
    {
        req = ant_plan_request::<Fx>(&mut g);
    }
    let f = frame_of(7, &req);
    assert!(f.len() <= MAX_ANT_FRAME);
    let r = replies(&mut dev, &f);
    assert_eq!(r.len(), 1);
    assert_eq!(dev.stats().link.oversize, 0);
}

#[test]
fn a_repeated_request_gets_the_same_reply() {
    let mut dev = ant_device::<f32>();
    open(&mut dev, 1);
    let mut g = Gen::new(5);
    for _ in 0..20 {
        let f = frame_of(42, &ant_plan_request::<f32>(&mut g));
        let mut twice = f.clone();
        twice.extend_from_slice(&f);
        let r = replies(&mut dev, &twice);
        assert_eq!(r.len(), 2);
        assert_eq!(r[0], r[1]);
    }
}

#[test]
fn reset_goes_back_to_power_up() {
    let mut dev = ant_device::<f32>();
    open(&mut dev, 1);
    replies(&mut dev, &[1, 2, 3]);
    assert_eq!(dev.pending(), 3);
    dev.reset();
    assert_eq!(dev.state(), SessionState::Idle);
    assert_eq!(dev.pending(), 0);
    assert_eq!(dev.stats(), DeviceStats::default());
}

// ---- the kinds message_kinds! accepts ----

#[test]
fn model_kinds_are_distinct_and_outside_the_session_protocol() {
    check_model_kinds(&[]);
    check_model_kinds(&[kind::ANT_PLAN_REQUEST, kind::ANT_PLAN_REPLY, 0x80, 0xff]);
    for (kinds, says) in [
        (&[0x90, 0x91, 0x90][..], "share a kind"),
        (&[0x90, kind::ERROR_REPLY][..], "session protocol"),
        (&[0x00][..], "session protocol"),
    ] {
        let err = std::panic::catch_unwind(|| check_model_kinds(kinds)).unwrap_err();
        let msg = (err.downcast_ref::<&str>().map(|m| m.to_string()))
            .or_else(|| err.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        assert!(msg.contains(says), "{kinds:?}: {msg}");
    }
}

// ---- the endpoint decides exactly what the controllers decide ----

fn ant_agrees<S: Scalar + Serialize + DeserializeOwned>(seed: u32, n: usize) {
    let params = AntParams::<S>::default();
    let mut dev = ant_device::<S>();
    open(&mut dev, seed);
    let mut g = Gen::new(seed);
    let (mut served, mut refused) = (0, 0);
    for i in 0..n {
        let seq = i as u16;
        let mut req = ant_plan_request::<S>(&mut g);
        if i % 13 == 0 {
            req.state.heading = Vec2::new(S::ZERO, S::ZERO); // refused: not a unit heading
        }
        let direct = ant::plan(&req.state, &req.frame, &params, req.ctx);
        assert_eq!(
            reply_to(&mut dev, seq, &req),
            expected(seq, direct.map(|plan| AntPlanReply { plan })),
            "plan {i}"
        );
        let Ok(plan) = direct else {
            refused += 1;
            continue;
        };
        served += 1;
        let req = ant_resolve_request(&mut g, plan);
        let direct = ant::resolve(&req.plan, &req.frame, &params);
        let r = replies(&mut dev, &frame_of(seq, &req));
        assert_eq!(
            r[0],
            expected(seq, direct.map(|state| AntResolveReply { state })),
            "resolve {i}"
        );
        // And the decoded reply is the direct value, bit for bit.
        if let Ok(state) = direct {
            let (_, got) = decode::<AntResolveReply<S>>(&r[0]);
            assert_eq!(frame_of(0, &got), frame_of(0, &AntResolveReply { state }));
        }
    }
    // The generator exercises both paths.
    assert!(
        served > n / 2 && refused > 0,
        "{served} served, {refused} refused"
    );
}

#[test]
fn ant_endpoint_equals_direct_calls_in_both_scalars() {
    ant_agrees::<f32>(11, 400);
    ant_agrees::<Fx>(12, 400);
}

fn bee_agrees<S: Scalar + Serialize + DeserializeOwned>(seed: u32, n: usize) {
    let params = BeeParams::<S>::default();
    let mut dev = bee_device::<S>();
    open(&mut dev, seed);
    let mut g = Gen::new(seed);
    let mut served = 0;
    for i in 0..n {
        let seq = (i * 7) as u16;
        let mut req = bee_request::<S>(&mut g);
        if i % 17 == 0 {
            req.frame.t = -S::ONE; // refused: t < 0
        }
        let direct = bee::step(&req.state, &req.frame, &params);
        served += usize::from(direct.is_ok());
        assert_eq!(
            reply_to(&mut dev, seq, &req),
            expected(
                seq,
                direct.map(|(decision, state)| BeeStepReply { decision, state })
            ),
            "step {i}"
        );
    }
    assert!(served > n / 2 && served < n);
}

/// A random, mostly valid wang advect request.
fn wang_advect_request<S: Scalar>(g: &mut Gen) -> AdvectRequest<S> {
    let pos = g.v3::<S>(-20.0, 20.0);
    let state = WangState {
        pos,
        vel: g.v3(-2.0, 2.0),
    };
    let mut frame = AdvectFrame::new(Vec3::new(S::ZERO, S::ZERO, S::ONE));
    if g.chance(0.6) {
        let n = Vec3::new(S::ZERO, S::ONE, S::ZERO);
        frame.boundary = Some(Boundary {
            point: pos - n * S::from_f32(g.range(0.0, 1.2)),
            normal: n,
            curvature: S::from_f32(g.range(0.0, 0.5)),
            axis: if g.chance(0.5) {
                Vec3::new(S::ONE, S::ZERO, S::ZERO)
            } else {
                Vec3::zero()
            },
        });
    }
    if g.chance(0.5) {
        frame.lamp = Some(g.v3(-10.0, 10.0));
    }
    AdvectRequest {
        state,
        frame,
        ctx: StepCtx {
            seed: g.u32(),
            agent: g.below(16),
            step: g.u32(),
        },
    }
}

fn wang_agrees<S: Scalar + Serialize + DeserializeOwned>(seed: u32, n: usize) {
    let params = WangParams::<S>::default();
    let mut dev = wang_device::<S>();
    open(&mut dev, seed);
    let mut g = Gen::new(seed);
    let (mut served, mut pushed) = (0, 0);
    for i in 0..n {
        let seq = (i * 7) as u16;
        let mut req = wang_advect_request::<S>(&mut g);
        if i % 17 == 0 {
            req.frame.guide = req.frame.guide * S::from_f32(2.0); // refused: |guide| > 1.01
        }
        let direct = wang::advect(&req.state, &req.frame, &params, req.ctx);
        assert_eq!(
            reply_to(&mut dev, seq, &req),
            expected(seq, direct.map(|moved| AdvectReply { moved })),
            "advect {i}"
        );
        let Ok(moved) = direct else {
            continue;
        };
        served += 1;
        let mut frame = WireSeparateFrame::new();
        for k in 0..g.below(WIRE_WANG_NEIGHBOURS as u32 + 1) {
            let _ = frame.neighbours.push(Close {
                id: k,
                pos: moved.pos + g.v3(-0.1, 0.1),
            });
        }
        if g.chance(0.1) {
            let _ = frame.neighbours.push(Close {
                id: 100,
                pos: moved.pos, // coincident
            });
        }
        if i % 13 == 0 && !frame.neighbours.is_empty() {
            frame.neighbours[0].pos.x = S::from_f32(20_000.0); // refused: out of range
        }
        let req = SeparateRequest {
            moved,
            frame,
            ctx: req.ctx,
        };
        let direct = wang::separate(&req.moved, &req.frame, &params, req.ctx);
        if let Ok((_, k)) = direct {
            pushed += usize::from(k > 0);
        }
        assert_eq!(
            reply_to(&mut dev, seq.wrapping_add(1), &req),
            expected(
                seq.wrapping_add(1),
                direct.map(|(state, pushes)| SeparateReply { state, pushes })
            ),
            "separate {i}"
        );
    }
    assert!(
        served > n / 2 && served < n && pushed > n / 4,
        "{served} {pushed}"
    );
}

#[test]
fn wang_endpoint_serves_both_phases_as_direct_calls_in_both_scalars() {
    wang_agrees::<f32>(31, 200);
    wang_agrees::<Fx>(32, 200);
}

fn fly_agrees<S: Scalar + Serialize + DeserializeOwned>(seed: u32, n: usize, params: FlyParams<S>) {
    let mut dev = fly_device::<S>(params);
    open(&mut dev, seed);
    let mut g = Gen::new(seed);
    let (mut served, mut escaping, mut infeasible) = (0, 0, 0);
    for i in 0..n {
        let seq = (i * 5) as u16;
        let mut req = fly_request::<S>(&mut g);
        if i % 17 == 0 {
            // refused: an unknown stimulus kind
            req.frame.stimulus = Some(Stimulus {
                pos: req.state.pos,
                kind: 2,
            });
        }
        if i % 19 == 0 && req.frame.neighbours.len() > 1 {
            let id = req.frame.neighbours[0].id;
            req.frame.neighbours[1].id = id; // refused: an id twice
        }
        let direct = fly::step(&req.state, &req.frame, &params, req.ctx);
        if let Ok((state, decision)) = &direct {
            served += 1;
            escaping += usize::from(state.escaping);
            infeasible += usize::from(decision.infeasible);
        }
        let reply = reply_to(&mut dev, seq, &req);
        assert_eq!(
            reply,
            expected(
                seq,
                direct.map(|(state, decision)| FlyStepReply { decision, state })
            ),
            "step {i}"
        );
        // And the decoded reply is the direct value, bit for bit.
        if let Ok((state, decision)) = direct {
            let (h, got) = decode::<FlyStepReply<S>>(&reply);
            assert_eq!((h.kind, h.seq), (kind::FLY_STEP_REPLY, seq));
            assert_eq!(got, FlyStepReply { decision, state });
        }
    }
    assert!(
        served > n / 2 && served < n,
        "{served} served of {n} ({escaping} escaping, {infeasible} infeasible)"
    );
    if params.chi_res > S::ZERO && params.r_res > S::ZERO {
        assert!(escaping > 0, "the escape response was exercised");
    }
}

#[test]
fn fly_endpoint_equals_direct_calls_in_both_scalars() {
    fly_agrees::<f32>(41, 200, FlyParams::default());
    fly_agrees::<Fx>(42, 200, FlyParams::default());
    fly_agrees::<f32>(43, 150, FlyParams::escape());
    fly_agrees::<Fx>(44, 150, FlyParams::<f32>::escape().cast());
}

/// A fly device answers bad input with the typed `ErrorReply` of the first failed check (or
/// `Payload`, `UnknownKind`, `NoSession`) and goes on serving.
#[test]
fn fly_device_refuses_bad_input_and_keeps_serving() {
    let params = FlyParams::<f32>::default();
    let mut dev = fly_device::<f32>(params);
    let mut g = Gen::new(45);
    let mut good = fly_request::<f32>(&mut g);
    while good.run(&params).is_err() {
        good = fly_request::<f32>(&mut g);
    }
    let served = frame_of(1, &good.run(&params).unwrap());
    // Before the session: NoSession.
    assert_eq!(
        error_code(&reply_to(&mut dev, 1, &good)),
        (1, ErrorReply::NO_SESSION)
    );
    open(&mut dev, 5);
    assert_eq!(reply_to(&mut dev, 1, &good), served);
    let with = |f: &dyn Fn(&mut FlyStepRequest<f32>)| {
        let mut r = good.clone();
        f(&mut r);
        r
    };
    let ground = Surface3 {
        point: Vec3::zero(),
        normal: Vec3::new(0.0, 1.0, 0.0),
    };
    // (request, error code, the refusal the controller names)
    type Case = (
        FlyStepRequest<f32>,
        u8,
        Option<(&'static str, &'static str)>,
    );
    let cases: [Case; 8] = [
        (
            with(&|r| r.state.pos.x = f32::NAN),
            ErrorReply::NON_FINITE,
            Some(("NonFinite", "state.pos")),
        ),
        (
            with(&|r| r.state.vel.y = 16_001.0),
            ErrorReply::OUT_OF_RANGE,
            Some(("OutOfRange", "state.vel")),
        ),
        (
            with(&|r| r.state.escape_theta = 1.6),
            ErrorReply::OUT_OF_RANGE,
            Some(("OutOfRange", "state.escape_theta")),
        ),
        (
            with(&|r| {
                r.frame.neighbours.clear();
                let n = Neighbour {
                    id: 9,
                    pos: r.state.pos + Vec3::new(1.0, 0.0, 0.0),
                    vel: Vec3::zero(),
                };
                r.frame.neighbours.push(n).unwrap();
                r.frame.neighbours.push(n).unwrap();
            }),
            ErrorReply::INCONSISTENT,
            Some(("Inconsistent", "frame.neighbours.id")),
        ),
        (
            with(&|r| {
                r.frame.stimulus = Some(Stimulus {
                    pos: Vec3::zero(),
                    kind: 2,
                })
            }),
            ErrorReply::OUT_OF_RANGE,
            Some(("OutOfRange", "frame.stimulus.kind")),
        ),
        (
            with(&|r| {
                r.frame.stimulus = Some(Stimulus {
                    pos: Vec3::new(0.0, f32::INFINITY, 0.0),
                    kind: STIMULUS_PREDATOR,
                })
            }),
            ErrorReply::NON_FINITE,
            Some(("NonFinite", "frame.stimulus.pos")),
        ),
        (
            with(&|r| {
                r.frame.surfaces.clear();
                r.frame
                    .surfaces
                    .push(Surface3 {
                        normal: Vec3::new(0.0, 1.02, 0.0),
                        ..ground
                    })
                    .unwrap();
            }),
            ErrorReply::OUT_OF_RANGE,
            Some(("OutOfRange", "frame.surfaces.normal")),
        ),
        (
            with(&|r| {
                r.frame.surfaces.clear();
                r.frame
                    .surfaces
                    .push(Surface3 {
                        point: Vec3::new(-16_001.0, 0.0, 0.0),
                        ..ground
                    })
                    .unwrap();
            }),
            ErrorReply::OUT_OF_RANGE,
            Some(("OutOfRange", "frame.surfaces.point")),
        ),
    ];
    for (i, (req, code, refused)) in cases.iter().enumerate() {
        assert_eq!(refusal(req.run(&params)), *refused, "case {i}");
        let seq = 10 + i as u16;
        assert_eq!(
            error_code(&reply_to(&mut dev, seq, req)),
            (seq, *code),
            "case {i}"
        );
        // And the device goes on serving.
        assert_eq!(reply_to(&mut dev, 1, &good), served, "after case {i}");
    }
    // Lists over their capacity do not decode: Payload.
    type Wide = fly::FlyFrame<f32, { WIRE_FLY_NEIGHBOURS + 1 }, { WIRE_FLY_SURFACES + 1 }>;
    let mut over = Wide::new();
    for k in 0..=WIRE_FLY_NEIGHBOURS as u32 {
        over.neighbours
            .push(Neighbour {
                id: k,
                pos: good.state.pos + Vec3::new(k as f32 + 1.0, 0.0, 0.0),
                vel: Vec3::zero(),
            })
            .unwrap();
    }
    let mut five = Wide::new();
    while five.surfaces.push(ground).is_ok() {}
    for (seq, frame) in [(30, over), (31, five)] {
        let f = frame_of_kind(kind::FLY_STEP_REQUEST, seq, &(good.state, frame, good.ctx));
        let r = replies(&mut dev, &f);
        assert_eq!(error_code(&r[0]), (seq, ErrorReply::PAYLOAD));
    }
    // Other controllers' requests and the fly reply kind.
    let mut line = Vec::new();
    for (i, k) in [
        kind::ANT_PLAN_REQUEST,
        kind::ANT_RESOLVE_REQUEST,
        kind::BEE_STEP_REQUEST,
        kind::WANG_ADVECT_REQUEST,
        kind::WANG_SEPARATE_REQUEST,
        0x42,
    ]
    .into_iter()
    .enumerate()
    {
        line.extend(frame_of_kind(k, 40 + i as u16, &()));
    }
    line.extend(frame_of(46, &good.run(&params).unwrap()));
    let codes: Vec<_> = replies(&mut dev, &line)
        .iter()
        .map(|f| error_code(f))
        .collect();
    assert_eq!(
        codes,
        (40..46)
            .map(|s| (s, ErrorReply::UNKNOWN_KIND))
            .collect::<Vec<_>>()
    );
    assert_eq!(dev.stats().ignored, 1); // the FlyStepReply
    assert_eq!(reply_to(&mut dev, 1, &good), served);
}

#[test]
fn bee_endpoint_equals_direct_calls_in_both_scalars() {
    bee_agrees::<f32>(21, 200);
    bee_agrees::<Fx>(22, 200);
}

#[test]
fn pipelined_bytewise_and_chunked_give_the_same_replies() {
    let mut g = Gen::new(31);
    let mut line = vec![0u8];
    line.extend(frame_of(1, &Hello));
    let hash = params_hash(&AntParams::<f32>::default()).unwrap();
    line.extend(frame_of(
        2,
        &Configure {
            session: 1,
            params_hash: hash,
            reset_stats: false,
        },
    ));
    for seq in 3..40u16 {
        match seq % 3 {
            0 => line.extend(frame_of(seq, &Ping { nonce: seq.into() })),
            _ => line.extend(frame_of(seq, &ant_plan_request::<f32>(&mut g))),
        }
    }
    let mut whole = ant_device::<f32>();
    let all = replies(&mut whole, &line);
    // One reply per request, in order.
    let seqs: Vec<u16> = all
        .iter()
        .map(|f| {
            let mut b = f[..f.len() - 1].to_vec();
            decode_frame(&mut b).unwrap().header.seq
        })
        .collect();
    assert_eq!(seqs, (1..40).collect::<Vec<_>>());
    // Byte by byte with push.
    let mut bytewise = ant_device::<f32>();
    let mut out = Vec::new();
    for &b in &line {
        if let Some(r) = bytewise.push(b) {
            out.push(r.to_vec());
        }
    }
    assert_eq!(out, all);
    // In odd chunks with the pull API.
    let mut pull = ant_device::<f32>();
    let mut out = Vec::new();
    for chunk in line.chunks(37) {
        let mut input = chunk;
        while let Some((reply, rest)) = pull.feed(input) {
            out.push(reply.to_vec());
            input = rest;
        }
    }
    assert_eq!(out, all);
}

#[test]
fn serve_stops_at_the_first_write_error() {
    let mut dev = ant_device::<f32>();
    let mut line = frame_of(1, &Ping { nonce: 1 });
    line.extend(frame_of(2, &Ping { nonce: 2 }));
    let mut n = 0;
    let r = dev.serve(&line, |_| {
        n += 1;
        Err("uart")
    });
    assert_eq!((r, n), (Err("uart"), 1));
}

// ---- properties: any bytes, no panic, no hang; every intact frame answered ----

/// What goes on the line in a property test.
#[derive(Clone, Debug)]
enum Piece {
    /// An intact request (preceded by a 0x00 so earlier noise cannot merge with it).
    Ping(u32),
    /// An intact ant plan request from this generator seed.
    Plan(u32),
    /// Random bytes (may contain zeros).
    Garbage(Vec<u8>),
    /// A request with one non-code byte changed (never to 0x00): a CRC error.
    Corrupt(u32, prop::sample::Index, u8),
    /// A strict prefix of a request, then the frame's end is lost.
    Truncated(u32, prop::sample::Index),
}

fn piece() -> impl Strategy<Value = Piece> {
    prop_oneof![
        any::<u32>().prop_map(Piece::Ping),
        any::<u32>().prop_map(Piece::Plan),
        proptest::collection::vec(any::<u8>(), 0..60).prop_map(Piece::Garbage),
        (any::<u32>(), any::<prop::sample::Index>(), 1u8..)
            .prop_map(|(a, b, c)| Piece::Corrupt(a, b, c)),
        (any::<u32>(), any::<prop::sample::Index>()).prop_map(|(a, b)| Piece::Truncated(a, b)),
    ]
}

/// Builds the line; returns it with the frames that are intact, in order.
fn build_line<S: Scalar + Serialize + DeserializeOwned>(
    pieces: &[Piece],
) -> (Vec<u8>, Vec<Vec<u8>>) {
    let mut line = Vec::new();
    let mut intact = Vec::new();
    for (i, p) in pieces.iter().enumerate() {
        let seq = 1000 + i as u16;
        match p {
            Piece::Ping(nonce) => {
                let f = frame_of(seq, &Ping { nonce: *nonce });
                line.push(0);
                line.extend_from_slice(&f);
                intact.push(f);
            }
            Piece::Plan(s) => {
                let f = frame_of(seq, &ant_plan_request::<S>(&mut Gen::new(*s)));
                line.push(0);
                line.extend_from_slice(&f);
                intact.push(f);
            }
            Piece::Garbage(bytes) => line.extend_from_slice(bytes),
            Piece::Corrupt(s, at, x) => {
                let mut f = frame_of(seq, &ant_plan_request::<S>(&mut Gen::new(*s)));
                let body_len = f.len() - 1;
                let codes = code_bytes(&f[..body_len]);
                let i = at.index(body_len);
                if !codes.contains(&i) && f[i] ^ x != 0 {
                    f[i] ^= x;
                } else {
                    f[body_len - 1] = if f[body_len - 1] == 0x55 { 0x56 } else { 0x55 };
                    // (the last byte may be a code byte only for a 1-byte run: then this
                    // changes a length and COBS or the CRC rejects it)
                }
                line.push(0);
                line.extend_from_slice(&f);
            }
            Piece::Truncated(nonce, at) => {
                let f = frame_of(seq, &Ping { nonce: *nonce });
                line.push(0);
                line.extend_from_slice(&f[..at.index(f.len() - 1)]);
            }
        }
    }
    (line, intact)
}

/// Whether `want` appears in `got` as a subsequence.
fn is_subsequence(want: &[Vec<u8>], got: &[Vec<u8>]) -> bool {
    let mut it = got.iter();
    want.iter().all(|w| it.any(|g| g == w))
}

proptest! {
    #[test]
    fn random_bytes_never_panic_and_replies_are_frames(
        chunks in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..200), 0..8),
        open_first: bool,
    ) {
        let mut dev = bee_device::<Fx>();
        if open_first {
            open(&mut dev, 1);
        }
        let mut out = Vec::new();
        for c in &chunks {
            out.extend(replies(&mut dev, c));
        }
        let zeros = chunks.iter().flatten().filter(|&&b| b == 0).count();
        prop_assert!(out.len() <= zeros);
        for r in &out {
            // Every reply is one well-formed frame of this version.
            prop_assert_eq!(r.iter().position(|&b| b == 0), Some(r.len() - 1));
            let mut body = r[..r.len() - 1].to_vec();
            prop_assert!(decode_frame(&mut body).is_ok());
        }
        let s = dev.stats();
        // (Configure with reset zeroes the counters, its own reply included.)
        prop_assert_eq!(s.replies as usize + s.errors as usize, out.len());
    }

    #[test]
    fn every_intact_frame_is_answered_in_order(
        pieces in proptest::collection::vec(piece(), 0..12),
        chunk in 1usize..97,
    ) {
        let (line, intact) = build_line::<f32>(&pieces);
        // What a clean line gives, one intact frame at a time.
        let mut reference = ant_device::<f32>();
        open(&mut reference, 7);
        let want: Vec<Vec<u8>> = intact.iter().map(|f| {
            let r = replies(&mut reference, f);
            assert_eq!(r.len(), 1);
            r.into_iter().next().unwrap()
        }).collect();
        // The noisy line, in chunks.
        let mut dev = ant_device::<f32>();
        open(&mut dev, 7);
        let mut got = Vec::new();
        for c in line.chunks(chunk) {
            got.extend(replies(&mut dev, c));
        }
        prop_assert!(is_subsequence(&want, &got), "want {} replies, got {}", want.len(), got.len());
        // Corrupted frames were all dropped; every reply beyond the intact frames' came from
        // a truncated or random frame that passed its CRC by chance (rare).
        // Any extra reply came from a truncated or random frame that passed its CRC by chance.
        prop_assert!(got.len() >= want.len());
    }

    #[test]
    fn fx_requests_with_any_numbers_never_panic(
        words in proptest::collection::vec(any::<u32>(), 40),
        seed: u32,
    ) {
        // A valid request whose numbers are then replaced by arbitrary bits.
        let mut req = ant_plan_request::<Fx>(&mut Gen::new(seed));
        let mut next = arbitrary(&words, |bits| Fx::from_bits(bits as i32));
        req.state.pos = Vec2::new(next(), next());
        req.state.heading = Vec2::new(next(), next());
        for n in req.frame.neighbours.iter_mut() {
            n.pos = Vec2::new(next(), next());
        }
        req.frame.bounds = Rect::new(Vec2::new(next(), next()), Vec2::new(next(), next()));
        let mut dev = ant_device::<Fx>();
        open(&mut dev, 1);
        prop_assert_eq!(reply_to(&mut dev, 1, &req), expected(1, req.run(&AntParams::default())));
    }

    #[test]
    fn f32_bee_requests_with_any_numbers_never_panic(
        words in proptest::collection::vec(any::<u32>(), 40),
        seed: u32,
    ) {
        let mut req = bee_request::<f32>(&mut Gen::new(seed));
        let mut next = arbitrary(&words, f32::from_bits);
        req.state.pos = Vec3::new(next(), next(), next());
        req.state.vel = Vec3::new(next(), next(), next());
        req.frame.t = next();
        for n in req.frame.neighbours.iter_mut() {
            n.pos = Vec3::new(next(), next(), next());
            n.density = next();
        }
        let mut dev = bee_device::<f32>();
        open(&mut dev, 1);
        prop_assert_eq!(reply_to(&mut dev, 1, &req), expected(1, req.run(&BeeParams::default())));
    }

    #[test]
    fn fly_requests_with_any_numbers_never_panic(
        words in proptest::collection::vec(any::<u32>(), 60),
        seed: u32,
        fixed: bool,
    ) {
        fn check<S: Scalar + Serialize + DeserializeOwned>(
            mut req: FlyStepRequest<S>,
            mut next: impl FnMut() -> S,
        ) -> bool {
            let mut v = || Vec3::new(next(), next(), next());
            req.state.pos = v();
            req.state.vel = v();
            for n in req.frame.neighbours.iter_mut() {
                n.pos = v();
                n.vel = v();
            }
            if let Some(s) = req.frame.stimulus.as_mut() {
                s.pos = v();
            }
            for s in req.frame.surfaces.iter_mut() {
                s.point = v();
                s.normal = v();
            }
            req.state.escape_theta = next();
            let params = FlyParams::<f32>::escape().cast::<S>();
            let mut dev = fly_device::<S>(params);
            open(&mut dev, 1);
            reply_to(&mut dev, 1, &req) == expected(1, req.run(&params))
        }
        let mut g = Gen::new(seed);
        let ok = if fixed {
            check(fly_request::<Fx>(&mut g), arbitrary(&words, |b| Fx::from_bits(b as i32)))
        } else {
            check(fly_request::<f32>(&mut g), arbitrary(&words, f32::from_bits))
        };
        prop_assert!(ok);
    }
}

// ---- docs/protocol.md kept equal to the code ----

/// Checks that tie `docs/protocol.md` to the code: the parameter tables and hashes of 10.2,
/// and the decoder and device behaviour the spec states (sections 3, 5, 6, 7, 10).
mod spec {
    use super::*;
    use crate::li::density::DensityGrid;
    use crate::li::sampler::Table;
    use crate::li::waypoint::{SAMPLING_MESO, SAMPLING_MH, SAMPLING_RANDOM};
    use crate::li::{
        LiDevice, LiParams, LiState, LiStepReply, LiStepRequest, MAX_LI_FRAME, MAX_LI_PAYLOAD,
        MAX_LI_REPLY_FRAME, MAX_LI_REPLY_PAYLOAD, WIRE_LI_NEIGHBOURS, WIRE_LI_SURFACES,
        WireLiFrame,
    };
    use crate::model::{ModelParams, ParamValue, Range};
    use crate::scalar::i16f16_bits;

    const DOC: &str = include_str!("../../../docs/protocol.md");

    /// The text from the line `start` to the next line starting with `end`.
    fn section(start: &str, end: &str) -> &'static str {
        let from = DOC
            .find(start)
            .unwrap_or_else(|| panic!("no {start:?} in protocol.md"));
        let rest = &DOC[from..];
        let to = rest[start.len()..]
            .find(end)
            .map_or(rest.len(), |i| i + start.len());
        &rest[..to]
    }

    /// The body rows of the first Markdown table in `text` whose header row has `header` as
    /// one of its cells; cells trimmed, backticks removed.
    fn table(text: &str, header: &str) -> Vec<Vec<String>> {
        let cells = |line: &str| -> Vec<String> {
            let line = line.trim().trim_start_matches('|').trim_end_matches('|');
            line.split('|').map(|c| c.trim().replace('`', "")).collect()
        };
        let mut lines = text.lines().skip_while(|l| {
            !(l.starts_with('|') && cells(l).iter().any(|c| c == &header.replace('`', "")))
        });
        assert!(
            lines.next().is_some(),
            "no table with the column {header:?}"
        );
        lines
            .skip(1) // the |---| line
            .take_while(|l| l.starts_with('|'))
            .map(cells)
            .collect()
    }

    /// The header cells of the table [`table`] finds.
    fn table_header(text: &str, header: &str) -> Vec<String> {
        let cells = |line: &str| -> Vec<String> {
            let line = line.trim().trim_start_matches('|').trim_end_matches('|');
            line.split('|').map(|c| c.trim().replace('`', "")).collect()
        };
        text.lines()
            .filter(|l| l.starts_with('|'))
            .map(cells)
            .find(|c| c.iter().any(|c| c == &header.replace('`', "")))
            .unwrap_or_else(|| panic!("no table with the column {header:?}"))
    }

    /// The hex bytes of a dump line: its two-digit hex tokens up to the first other token (a
    /// comment), after an optional leading label ending in `()`.
    fn dump_bytes(line: &str) -> Vec<u8> {
        line.split_whitespace()
            .skip_while(|t| t.ends_with("()"))
            .take_while(|t| t.len() == 2 && t.bytes().all(|b| b.is_ascii_hexdigit()))
            .map(|t| u8::from_str_radix(t, 16).unwrap())
            .collect()
    }

    /// The code blocks of `text`, each as its lines.
    fn code_blocks(text: &str) -> Vec<Vec<&str>> {
        text.split("```")
            .skip(1)
            .step_by(2)
            .map(|b| b.lines().filter(|l| !l.trim().is_empty()).collect())
            .collect()
    }

    /// Bytes per label of a dump block whose entries start with `label()`.
    fn labelled_dumps(block: &[&str]) -> Vec<(String, Vec<u8>)> {
        let mut out: Vec<(String, Vec<u8>)> = Vec::new();
        for line in block {
            let first = line.split_whitespace().next().unwrap_or("");
            if let Some(label) = first.strip_suffix("()") {
                out.push((label.to_string(), Vec::new()));
            }
            out.last_mut()
                .expect("a labelled line first")
                .1
                .extend(dump_bytes(line));
        }
        out
    }

    fn postcard_bytes<T: Serialize>(v: &T) -> Vec<u8> {
        let mut buf = [0u8; 256];
        postcard::to_slice(v, &mut buf).unwrap().to_vec()
    }

    /// Every field of `P` with its wire type (`S`, `u16`, `u8`), in postcard order: the order
    /// in which changing one field at a time changes the first byte of the encoding.
    fn postcard_order<P>() -> Vec<(&'static str, &'static str)>
    where
        P: ModelParams<Scalar = f32> + Serialize + Clone + Default,
    {
        let base = P::default();
        let bytes = postcard_bytes(&base);
        let mut at: Vec<(usize, &'static str, &'static str)> = P::SPECS
            .iter()
            .enumerate()
            .map(|(i, spec)| {
                let mut p = base.clone();
                let (changed, ty) = match p.get(i).unwrap() {
                    ParamValue::Real(v) => (ParamValue::Real(v + 1.0), "S"),
                    ParamValue::Int(n) => {
                        let mut q = base.clone();
                        let ty = if !q.set(i, ParamValue::Int(300)) {
                            "u8"
                        } else if !q.set(i, ParamValue::Int(70_000)) {
                            "u16"
                        } else {
                            "u32"
                        };
                        (ParamValue::Int(n ^ 1), ty)
                    }
                };
                assert!(p.set(i, changed));
                let other = postcard_bytes(&p);
                assert_eq!(other.len(), bytes.len(), "{}", spec.name);
                let first = (0..bytes.len()).find(|&k| bytes[k] != other[k]).unwrap();
                (first, spec.name, ty)
            })
            .collect();
        at.sort_unstable();
        assert!(
            at.windows(2).all(|w| w[0].0 < w[1].0),
            "one offset per field"
        );
        at.into_iter().map(|(_, n, t)| (n, t)).collect()
    }

    /// The value of field `name` of `p` as the tables write it.
    fn value_of<P: ModelParams>(p: &P, name: &str) -> ParamValue<P::Scalar> {
        p.get(P::index_of(name).unwrap()).unwrap()
    }

    /// A documented decimal, as `f32` (decimal → f32, round to nearest).
    fn decimal(cell: &str) -> f32 {
        cell.parse::<f32>()
            .unwrap_or_else(|_| panic!("not a number: {cell:?}"))
    }

    /// Checks the documented fields of `P` (names, order, types) against the code.
    fn check_fields<P>(rows: &[Vec<String>])
    where
        P: ModelParams<Scalar = f32> + Serialize + Clone + Default,
    {
        let documented: Vec<(&str, &str)> = rows
            .iter()
            .map(|r| (r[1].as_str(), r[2].as_str()))
            .collect();
        assert_eq!(documented, postcard_order::<P>());
        let numbers: Vec<String> = rows.iter().map(|r| r[0].clone()).collect();
        let expected: Vec<String> = (1..=rows.len()).map(|i| i.to_string()).collect();
        assert_eq!(numbers, expected);
        // Every field, nothing more (SPECS lists each once, in validation order).
        let mut names: Vec<&str> = P::SPECS.iter().map(|s| s.name).collect();
        let mut doc_names: Vec<&str> = documented.iter().map(|d| d.0).collect();
        names.sort_unstable();
        doc_names.sort_unstable();
        assert_eq!(doc_names, names);
    }

    /// Checks a documented value column against a preset in both scalars.
    fn check_values<P>(rows: &[Vec<String>], column: usize, f32_params: &P, fx_params: &P::Fx)
    where
        P: ModelParams<Scalar = f32> + Castable,
    {
        for row in rows {
            let (name, cell) = (row[1].as_str(), row[column].as_str());
            match value_of(f32_params, name) {
                ParamValue::Real(v) => {
                    let doc = decimal(cell);
                    assert_eq!(doc.to_bits(), v.to_bits(), "{name}: {cell} vs {v}");
                    let ParamValue::Real(x) = value_of(fx_params, name) else {
                        panic!()
                    };
                    assert_eq!(x.to_bits(), i16f16_bits(doc), "{name} in I16F16");
                }
                ParamValue::Int(n) => {
                    assert_eq!(cell.parse::<u32>().unwrap(), n, "{name}");
                    assert_eq!(value_of(fx_params, name), ParamValue::Int(n), "{name}");
                }
            }
        }
    }

    /// Parameters with an `Fx` version.
    trait Castable {
        type Fx: ModelParams<Scalar = Fx> + Serialize;
    }
    impl Castable for AntParams<f32> {
        type Fx = AntParams<Fx>;
    }
    impl Castable for BeeParams<f32> {
        type Fx = BeeParams<Fx>;
    }
    impl Castable for WangParams<f32> {
        type Fx = WangParams<Fx>;
    }
    impl Castable for FlyParams<f32> {
        type Fx = FlyParams<Fx>;
    }
    impl Castable for LiParams<f32> {
        type Fx = LiParams<Fx>;
    }

    /// Checks a documented range column (`(a, b]`, `[a, b]` or `a to b`, optionally followed
    /// by a comma and a rule in words) against the ranges the code validates.
    fn check_ranges<P: ModelParams>(rows: &[Vec<String>], column: usize) {
        for row in rows {
            let (name, cell) = (row[1].as_str(), row[column].as_str());
            let spec = P::SPECS[P::index_of(name).unwrap()];
            let documented = if let Some((lo, hi)) = cell.split_once(" to ") {
                let hi = hi.split(',').next().unwrap().trim();
                Range::int(lo.parse().unwrap(), hi.parse().unwrap())
            } else {
                let close = cell.find(']').unwrap_or_else(|| panic!("{name}: {cell:?}"));
                let (lo, hi) = cell[1..close].split_once(", ").unwrap();
                match &cell[..1] {
                    "(" => Range::above(decimal(lo), decimal(hi)),
                    "[" => Range::closed(decimal(lo), decimal(hi)),
                    _ => panic!("{name}: {cell:?}"),
                }
            };
            assert_eq!(documented, spec.range, "{name}: {cell:?}");
        }
    }

    /// The decimal numbers in a cell of words (`lo 0.002, hi 0.03, cdf [1]` → 0.002, 0.03, 1).
    fn numbers_in(cell: &str) -> Vec<f32> {
        cell.split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .filter(|w| !w.is_empty() && w != &".")
            .map(decimal)
            .collect()
    }

    fn hash_of(cell: &str) -> u64 {
        u64::from_str_radix(cell.trim_start_matches("0x"), 16).unwrap()
    }

    #[test]
    fn params_tables_match_the_code() {
        let text = section("### 10.2", "### 10.3");
        let ant_f32 = AntParams::<f32>::default();
        let ant_fx = ant_f32.cast::<Fx>();

        // AntParams: fields, defaults, f32 bits, I16F16 raw bits.
        let rows = table(text, "`AntParams` field");
        check_fields::<AntParams<f32>>(&rows);
        check_values(&rows, 3, &ant_f32, &ant_fx);
        for row in &rows {
            if let ParamValue::Real(v) = value_of(&ant_f32, &row[1]) {
                assert_eq!(row[4], format!("{:08x}", v.to_bits()), "{}", row[1]);
                let ParamValue::Real(x) = value_of(&ant_fx, &row[1]) else {
                    panic!()
                };
                let bits = x.to_bits();
                assert_eq!(row[5], format!("{bits} (0x{bits:x})"), "{}", row[1]);
            } else {
                assert_eq!((row[4].as_str(), row[5].as_str()), ("", ""), "{}", row[1]);
            }
        }

        // BeeParams: fields and the three presets.
        let rows = table(text, "`BeeParams` field");
        check_fields::<BeeParams<f32>>(&rows);
        let presets = [
            (
                "default",
                BeeParams::<f32>::default(),
                BeeParams::<Fx>::default(),
            ),
            (
                "grassland",
                BeeParams::grassland(),
                BeeParams::<Fx>::grassland(),
            ),
            (
                "around_nest",
                BeeParams::around_nest(),
                BeeParams::<Fx>::around_nest(),
            ),
        ];
        for (column, (_, f, x)) in presets.iter().enumerate() {
            check_values(&rows, 3 + column, f, x);
            assert_eq!(f.cast::<Fx>(), *x, "the Fx preset is the cast f32 preset");
        }

        // The byte dumps: ant f32, ant Fx, bee f32, bee Fx.
        let blocks = code_blocks(text);
        let dump = |b: &[&str]| b.iter().flat_map(|l| dump_bytes(l)).collect::<Vec<u8>>();
        assert_eq!(dump(&blocks[1]), postcard_bytes(&ant_f32));
        assert_eq!(dump(&blocks[2]), postcard_bytes(&ant_fx));
        let bee_f32 = labelled_dumps(&blocks[3]);
        let bee_fx = labelled_dumps(&blocks[4]);
        assert_eq!((bee_f32.len(), bee_fx.len()), (3, 3));
        for (i, (name, f, x)) in presets.iter().enumerate() {
            assert_eq!(bee_f32[i], (name.to_string(), postcard_bytes(f)));
            assert_eq!(bee_fx[i], (name.to_string(), postcard_bytes(x)));
        }

        // WangParams: fields and the four presets.
        let rows = table(text, "`WangParams` field");
        check_fields::<WangParams<f32>>(&rows);
        let wang = [
            (
                "WangParams::default()",
                WangParams::<f32>::default(),
                WangParams::<Fx>::default(),
            ),
            (
                "WangParams::aggregation()",
                WangParams::aggregation(),
                WangParams::<Fx>::aggregation(),
            ),
            (
                "WangParams::phototaxis()",
                WangParams::phototaxis(),
                WangParams::<Fx>::phototaxis(),
            ),
            (
                "WangParams::locusts()",
                WangParams::locusts(),
                WangParams::<Fx>::locusts(),
            ),
        ];
        for (column, (_, f, x)) in wang.iter().enumerate() {
            check_values(&rows, 3 + column, f, x);
            assert_eq!(f.cast::<Fx>(), *x, "the Fx preset is the cast f32 preset");
        }

        // FlyParams: fields and the nine presets (Table 1 columns).
        let rows = table(text, "`FlyParams` field");
        check_fields::<FlyParams<f32>>(&rows);
        type Preset = (&'static str, fn() -> FlyParams<f32>, fn() -> FlyParams<Fx>);
        let fly_presets: [Preset; 9] = [
            ("FlyParams::midge()", FlyParams::midge, FlyParams::midge),
            (
                "FlyParams::aggregation()",
                FlyParams::aggregation,
                FlyParams::aggregation,
            ),
            (
                "FlyParams::fruitfly()",
                FlyParams::fruitfly,
                FlyParams::fruitfly,
            ),
            ("FlyParams::mating()", FlyParams::mating, FlyParams::mating),
            ("FlyParams::escape()", FlyParams::escape, FlyParams::escape),
            ("FlyParams::bats()", FlyParams::bats, FlyParams::bats),
            ("FlyParams::locust()", FlyParams::locust, FlyParams::locust),
            ("FlyParams::phase()", FlyParams::phase, FlyParams::phase),
            (
                "FlyParams::phototaxis()",
                FlyParams::phototaxis,
                FlyParams::phototaxis,
            ),
        ];
        let fly = fly_presets.map(|(name, f, x)| (name, f(), x()));
        for (column, (_, f, x)) in fly.iter().enumerate() {
            check_values(&rows, 3 + column, f, x);
            assert_eq!(f.cast::<Fx>(), *x, "the Fx preset is the cast f32 preset");
        }
        // The column headers name the presets, in order; the default is the midge.
        let header = table_header(text, "`FlyParams` field");
        for (column, (name, _, _)) in fly.iter().enumerate() {
            assert_eq!(
                format!("FlyParams::{}", header[3 + column]),
                *name,
                "column {column}"
            );
        }
        assert_eq!(FlyParams::<f32>::default(), fly[0].1);
        assert_eq!(FlyParams::<Fx>::default(), fly[0].2);
        let range = header.iter().position(|c| c == "range").unwrap();
        check_ranges::<FlyParams<f32>>(&rows, range);

        // LiParams: the 12 numbers (fields, default, ranges), then the learned data.
        let li_f32 = LiParams::<f32>::default();
        let li_fx = li_f32.cast::<Fx>();
        assert_eq!(
            LiParams::<Fx>::default(),
            li_fx,
            "the Fx default is the cast f32 one"
        );
        let rows = table(text, "`LiParams` field");
        let header = table_header(text, "`LiParams` field");
        assert_eq!(header[3..5], ["default()", "range"]);
        let (numbers, data) = rows.split_at(LiParams::<f32>::SPECS.len());
        check_fields::<LiParams<f32>>(numbers);
        check_values(numbers, 3, &li_f32, &li_fx);
        check_ranges::<LiParams<f32>>(numbers, 4);
        let data_fields: Vec<[&str; 3]> = data
            .iter()
            .map(|r| [r[0].as_str(), r[1].as_str(), r[2].as_str()])
            .collect();
        assert_eq!(
            data_fields,
            [
                ["13", "lengths", "LiTable<S>"],
                ["14", "turns", "LiTable<S>"],
                ["15", "density", "DensityGrid<S>"],
            ]
        );
        // The data follow the numbers, in this order.
        let tail = [
            postcard_bytes(&li_f32.lengths),
            postcard_bytes(&li_f32.turns),
            postcard_bytes(&li_f32.density),
        ]
        .concat();
        assert!(postcard_bytes(&li_f32).ends_with(&tail));
        // The data's default cells.
        let table_numbers =
            |t: &Table<f32, { crate::li::BINS }>| [vec![t.lo, t.hi], t.cdf.to_vec()].concat();
        assert_eq!(numbers_in(&data[0][3]), table_numbers(&li_f32.lengths));
        assert_eq!(numbers_in(&data[1][3]), table_numbers(&li_f32.turns));
        let d = &li_f32.density;
        let mut grid = vec![d.origin.x, d.origin.y, d.origin.z, d.cell];
        grid.extend(d.dims.map(f32::from));
        grid.extend(d.weights.iter().map(|&w| f32::from(w)));
        assert_eq!(numbers_in(&data[2][3]), grid);
        // The data's ranges: lengths from 0, turns within ±(f32(π) + 0.001).
        assert_eq!(numbers_in(&data[0][4]), [0.0]);
        let turn_limit = core::f32::consts::PI + 1e-3;
        assert_eq!(numbers_in(&data[1][4]), [turn_limit, turn_limit]);
        assert_eq!(i16f16_bits(turn_limit), 205_953);
        assert_eq!(format!("{:08x}", turn_limit.to_bits()), "4049203d");
        // The li default's dumps (after the ant's and the bee's): f32, Fx.
        let (li_dump_f32, li_dump_fx) = (dump(&blocks[5]), dump(&blocks[6]));
        assert_eq!(
            (li_dump_f32.len(), li_dump_fx.len()),
            (81, 50),
            "the sizes 10.2 states"
        );
        assert_eq!(li_dump_f32, postcard_bytes(&li_f32));
        assert_eq!(li_dump_fx, postcard_bytes(&li_fx));
        assert_eq!(blocks.len(), 7, "no other code block in 10.2");

        // The hash table, both scalars.
        let rows = table(text, "preset");
        let expected = [
            (
                "AntParams::default()",
                params_hash(&ant_f32),
                params_hash(&ant_fx),
            ),
            (
                "BeeParams::default()",
                params_hash(&presets[0].1),
                params_hash(&presets[0].2),
            ),
            (
                "BeeParams::grassland()",
                params_hash(&presets[1].1),
                params_hash(&presets[1].2),
            ),
            (
                "BeeParams::around_nest()",
                params_hash(&presets[2].1),
                params_hash(&presets[2].2),
            ),
            (wang[0].0, params_hash(&wang[0].1), params_hash(&wang[0].2)),
            (wang[1].0, params_hash(&wang[1].1), params_hash(&wang[1].2)),
            (wang[2].0, params_hash(&wang[2].1), params_hash(&wang[2].2)),
            (wang[3].0, params_hash(&wang[3].1), params_hash(&wang[3].2)),
            (fly[0].0, params_hash(&fly[0].1), params_hash(&fly[0].2)),
            (fly[1].0, params_hash(&fly[1].1), params_hash(&fly[1].2)),
            (fly[2].0, params_hash(&fly[2].1), params_hash(&fly[2].2)),
            (fly[3].0, params_hash(&fly[3].1), params_hash(&fly[3].2)),
            (fly[4].0, params_hash(&fly[4].1), params_hash(&fly[4].2)),
            (fly[5].0, params_hash(&fly[5].1), params_hash(&fly[5].2)),
            (fly[6].0, params_hash(&fly[6].1), params_hash(&fly[6].2)),
            (fly[7].0, params_hash(&fly[7].1), params_hash(&fly[7].2)),
            (fly[8].0, params_hash(&fly[8].1), params_hash(&fly[8].2)),
            (
                "LiParams::default()",
                params_hash(&li_f32),
                params_hash(&li_fx),
            ),
        ];
        assert_eq!(rows.len(), expected.len());
        for (row, (name, f, x)) in rows.iter().zip(expected) {
            assert_eq!(row[0], name);
            assert_eq!(Ok(hash_of(&row[1])), f, "{name} f32");
            assert_eq!(Ok(hash_of(&row[2])), x, "{name} I16F16");
        }
        // The fixed-point default is the f32 default converted (10.2).
        assert_eq!(AntParams::<Fx>::default(), ant_fx);
        assert_eq!(ant_fx.theta.to_bits(), 34_315);
    }

    /// 10.2: decimal → f32 (nearest) → I16F16 (nearest, ties to even, saturating).
    #[test]
    fn decimal_to_i16f16_examples() {
        let via = |d: &str| i16f16_bits(d.parse::<f32>().unwrap());
        assert_eq!(via("1000.00001"), 65_536_000); // the f32 is 1000.0
        assert_eq!(via("0.00003814697265625"), 2); // 2.5 raw units: ties to even
        assert_eq!(via("0.00002288818359375"), 2); // 1.5 raw units
        assert_eq!(via("40000"), i32::MAX);
        assert_eq!(via("-40000"), i32::MIN);
        assert_eq!(i16f16_bits(f32::NAN), 0);
        for d in [
            "1000.00001",
            "0.00003814697265625",
            "0.6",
            "0.005",
            "-40000",
        ] {
            assert_eq!(Fx::from_f32(d.parse().unwrap()).to_bits(), via(d), "{d}");
        }
    }

    /// Section 6: non-shortest varints within the maximum length are accepted.
    #[test]
    fn non_shortest_varints_are_accepted() {
        assert_eq!(decode_payload::<u16>(&[0x80, 0x00]), Ok(0));
        assert_eq!(decode_payload::<u16>(&[0x80, 0x80, 0x00]), Ok(0));
        assert_eq!(
            decode_payload::<u16>(&[0x80, 0x80, 0x80, 0x00]),
            Err(Error::Payload)
        );
        assert_eq!(decode_payload::<u16>(&[0xff, 0xff, 0x03]), Ok(u16::MAX));
        assert_eq!(
            decode_payload::<u16>(&[0xff, 0xff, 0x04]),
            Err(Error::Payload)
        );
        assert_eq!(decode_payload::<i32>(&[0x81, 0x00]), Ok(-1));
        assert_eq!(
            decode_payload::<u32>(&[0x80, 0x80, 0x80, 0x80, 0x00]),
            Ok(0)
        );
        assert_eq!(
            decode_payload::<u32>(&[0xff, 0xff, 0xff, 0xff, 0x0f]),
            Ok(u32::MAX)
        );
        assert_eq!(
            decode_payload::<u32>(&[0xff, 0xff, 0xff, 0xff, 0x10]),
            Err(Error::Payload)
        );
        let mut max64 = [0xffu8; 10];
        max64[9] = 0x01;
        assert_eq!(decode_payload::<u64>(&max64), Ok(u64::MAX));
        max64[9] = 0x02;
        assert_eq!(decode_payload::<u64>(&max64), Err(Error::Payload));
        assert_eq!(
            decode_payload::<Fx>(&[0x80, 0x80, 0x80, 0x80, 0x00]),
            Ok(Fx::ZERO)
        );
        assert_eq!(decode_payload::<ant::Label>(&[0x82, 0x00]), Ok(Label::Nest));
        assert_eq!(
            decode_payload::<heapless::Vec<u8, 4>>(&[0x80, 0x00]),
            Ok(heapless::Vec::new())
        );
        // A device serves such a request; its reply is in the shortest form.
        let mut dev = ant_device::<f32>();
        let ping = frame_of_kind(kind::PING, 9, &[0x85u8, 0x80, 0x00]); // nonce 5
        let r = replies(&mut dev, &ping);
        assert_eq!(r, vec![frame_of(9, &Pong { nonce: 5 })]);
    }

    /// Section 3: the optional trailing `01` exists only after a final `FF` block.
    #[test]
    fn cobs_trailing_01_only_after_a_final_ff_block() {
        // A 254-byte raw frame with no zero: version 3, kind 0x85, seq 0x0101, 248 × 0x11, CRC.
        let mut raw = vec![PROTOCOL_VERSION, 0x85, 1, 1];
        raw.extend([0x11u8; 248]);
        raw.extend_from_slice(&CRC16.checksum(&raw).to_le_bytes());
        assert_eq!(raw.len(), 254);
        assert!(!raw.contains(&0));
        let mut shortest = vec![0xffu8];
        shortest.extend_from_slice(&raw);
        let mut padded = shortest.clone();
        padded.push(0x01);
        assert_eq!(frame_of_kind(0x85, 0x0101, &frame::Raw(&[0x11; 248])), {
            let mut l = shortest.clone();
            l.push(0);
            l
        });
        for line in [&shortest, &padded] {
            let mut body = line.clone();
            let f = decode_frame(&mut body).unwrap();
            assert_eq!(
                (f.header, f.payload),
                (Header::new(0x85, 0x0101), &[0x11u8; 248][..])
            );
            let mut acc = Accumulator::<300>::new();
            let mut with_delimiter = line.clone();
            with_delimiter.push(0);
            assert!(matches!(
                acc.feed(&with_delimiter),
                Some((Event::Frame(_), []))
            ));
        }
        // After any other code byte a final 01 encodes a trailing zero: not padding.
        let decode = |enc: &[u8]| {
            let mut b = enc.to_vec();
            cobs::decode_in_place(&mut b).map(|n| b[..n].to_vec())
        };
        assert_eq!(decode(&[0x03, 0x11, 0x22]), Ok(vec![0x11, 0x22]));
        assert_eq!(
            decode(&[0x03, 0x11, 0x22, 0x01]),
            Ok(vec![0x11, 0x22, 0x00])
        );
        assert_eq!(
            decode(&[0x03, 0x11, 0x22, 0x01, 0x01]),
            Ok(vec![0x11, 0x22, 0, 0])
        );
    }

    /// A CRC-valid frame of protocol version `version`.
    fn foreign(version: u8, kind: u8, seq: u16, payload: &[u8]) -> Vec<u8> {
        let mut raw = vec![version, kind];
        raw.extend_from_slice(&seq.to_le_bytes());
        raw.extend_from_slice(payload);
        raw.extend_from_slice(&CRC16.checksum(&raw).to_le_bytes());
        let mut out = vec![0u8; raw.len() + 4];
        let n = cobs::try_encode(&raw, &mut out).unwrap();
        out.truncate(n);
        out.push(0);
        out
    }

    /// The kinds a device never answers, whatever the version: 0x00 and the reply kinds.
    const NEVER_ANSWERED: [u8; 13] = [
        0x00, 0x02, 0x04, 0x06, 0x08, 0x0f, 0x11, 0x13, 0x21, 0x31, 0x33, 0x41, 0x51,
    ];

    /// Sections 5, 10.4, 10.5: a foreign-version frame of kind 0x00 or of a reply kind is
    /// dropped unanswered (counted in `ignored`), one of any other kind is answered with
    /// ErrorReply 10; in this version (3), 0x00 and the reply kinds are dropped the same way.
    #[test]
    fn foreign_version_frames_are_answered_unless_never_answered() {
        assert_eq!(
            (0..=255u8)
                .filter(|&k| kind::never_answered(k))
                .collect::<Vec<_>>(),
            NEVER_ANSWERED
        );
        assert!(NEVER_ANSWERED[1..].iter().all(|&k| kind::is_reply(k)));
        for version in [0u8, 1, 2, 4, 0xff] {
            let mut dev = ant_device::<f32>();
            open(&mut dev, 1);
            let line: Vec<u8> = (0..=255u8)
                .flat_map(|k| foreign(version, k, 0x4200 | u16::from(k), &[]))
                .collect();
            let r = replies(&mut dev, &line);
            let answered: Vec<(u16, u8)> = r.iter().map(|f| error_code(f)).collect();
            let expected: Vec<(u16, u8)> = (0..=255u8)
                .filter(|k| !NEVER_ANSWERED.contains(k))
                .map(|k| (0x4200 | u16::from(k), ErrorReply::VERSION))
                .collect();
            assert_eq!(answered, expected, "version {version}");
            let s = dev.stats();
            assert_eq!((s.link.version_errors, s.errors, s.requests), (256, 243, 0));
            assert_eq!((s.ignored, s.decode_errors, s.replies), (13, 0, 0));
        }
        // The same kinds in this version: dropped, counted in requests and ignored.
        let mut dev = ant_device::<f32>();
        open(&mut dev, 1);
        for k in NEVER_ANSWERED {
            assert!(replies(&mut dev, &frame_of_kind(k, 1, &())).is_empty());
        }
        let s = dev.stats();
        assert_eq!((s.link.frames_ok, s.requests, s.ignored), (13, 13, 13));
        assert_eq!((s.errors, s.decode_errors, s.replies), (0, 0, 0));
    }

    /// Sections 5, 10.1, 10.5, case by case, with every counter: version-3 kind 0x00, a
    /// version-2 Identity, a version-2 kind 0x00 and a version-2 ErrorReply are dropped
    /// unanswered; a version-2 Ping is answered with ErrorReply 10.
    #[test]
    fn a_device_never_answers_a_reply_or_kind_0x00() {
        let mut dev = ant_device::<f32>();
        open(&mut dev, 1);
        assert_eq!(
            dev.stats(),
            DeviceStats {
                session: Some(1),
                ..DeviceStats::default()
            }
        );
        let mut identity = dev.identity();
        identity.protocol = 2;
        let identity = postcard_bytes(&identity);
        // (frame with seq i + 1, the error code it is answered with)
        let cases = [
            (frame_of_kind(0x00, 1, &()), None),
            (foreign(2, kind::IDENTITY, 2, &identity), None),
            (foreign(2, 0x00, 3, &[]), None),
            (foreign(2, kind::PING, 4, &[5]), Some(ErrorReply::VERSION)),
            (foreign(2, kind::ERROR_REPLY, 5, &[1]), None),
        ];
        let mut want = dev.stats();
        for (i, (frame, answer)) in cases.into_iter().enumerate() {
            let r = replies(&mut dev, &frame);
            let seq = u16::try_from(i + 1).unwrap();
            let expected = answer.map(|code| (seq, code));
            assert_eq!(r.iter().map(|f| error_code(f)).next(), expected);
            assert!(r.len() <= 1);
            if frame[1] == PROTOCOL_VERSION {
                want.link.frames_ok += 1;
                want.requests += 1;
            } else {
                want.link.version_errors += 1;
                want.link.bytes_dropped += u32::try_from(frame.len() - 1).unwrap();
            }
            match answer {
                Some(_) => want.errors += 1,
                None => want.ignored += 1,
            }
            assert_eq!(dev.stats(), want, "case {i}");
        }
        assert_eq!(
            (want.link.version_errors, want.ignored, want.errors),
            (4, 4, 1)
        );
    }

    /// 10.1: what `Configure { reset_stats: true }` zeroes, and when.
    #[test]
    fn reset_stats_zeroes_every_counter_with_the_configure() {
        let mut dev = ant_device::<f32>();
        open(&mut dev, 1);
        let mut line = vec![0u8, 0]; // empty frames
        line.extend(frame_of(1, &Ping { nonce: 1 }));
        let mut bad = frame_of(2, &Ping { nonce: 2 });
        bad[3] ^= 0x40;
        line.extend(bad);
        line.extend(foreign(2, kind::PING, 3, &[3]));
        line.extend(frame_of(4, &Pong { nonce: 4 }));
        line.extend(frame_of_kind(0x30, 5, &()));
        assert_eq!(replies(&mut dev, &line).len(), 3);
        let s = dev.stats();
        assert!(s.link.empty > 0 && s.link.crc_errors > 0 && s.link.version_errors > 0);
        assert!(s.ignored > 0 && s.decode_errors > 0 && s.errors > 0 && s.replies > 0);
        // A refused Configure (other hash) resets nothing, and closes the session.
        let hash = dev.identity().params_hash;
        let refused = Configure {
            session: 2,
            params_hash: hash ^ 1,
            reset_stats: true,
        };
        replies(&mut dev, &frame_of(6, &refused));
        assert_eq!(dev.stats().errors, s.errors + 1);
        assert_eq!(dev.stats().session, None);
        // An accepted one zeroes all 13 counters after its reply: neither counts.
        let accepted = Configure {
            session: 3,
            params_hash: hash,
            reset_stats: true,
        };
        let r = replies(&mut dev, &frame_of(7, &accepted));
        assert_eq!(decode::<Configured>(&r[0]).1, Configured { session: 3 });
        let zero = DeviceStats {
            session: Some(3),
            ..DeviceStats::default()
        };
        assert_eq!(dev.stats(), zero);
        // The next StatsRequest counts only itself.
        let r = replies(&mut dev, &frame_of(8, &StatsRequest));
        let mut want = zero;
        want.link.frames_ok = 1;
        want.requests = 1;
        assert_eq!(decode::<DeviceStats>(&r[0]).1, want);
    }

    /// Section 7: a few of the documented checks, at their limits.
    #[test]
    fn request_checks_as_documented() {
        let p = AntParams::<f32>::default();
        let bounds = Rect::new(Vec2::from_f32(0.0, 0.0), Vec2::from_f32(100.0, 100.0));
        let state =
            AntState::<f32>::exploring(0, Vec2::from_f32(5.0, 5.0), Vec2::from_f32(1.0, 0.0));
        let ctx = StepCtx {
            seed: 1,
            agent: 7,
            step: 3,
        };
        let plan = |s: &AntState<f32>, f: &WirePlanFrame<f32>| ant::plan(s, f, &p, ctx);
        let frame = WirePlanFrame::new(bounds);
        assert!(plan(&state, &frame).is_ok());
        let with_heading = |x: f32| AntState {
            heading: Vec2::new(x, 0.0),
            ..state
        };
        let at = |x: f32| AntState {
            pos: Vec2::new(x, 5.0),
            ..state
        };
        for (s, refused) in [
            // heading: x² + y² strictly inside (0.9801, 1.0201).
            (with_heading(0.995), None),
            (with_heading(0.98), Some(("OutOfRange", "state.heading"))),
            (with_heading(f32::NAN), Some(("NonFinite", "state.heading"))),
            // Coordinates: ±16384 included.
            (at(16384.0), None),
            (at(16385.0), Some(("OutOfRange", "state.pos"))),
        ] {
            assert_eq!(refusal(s.validate()), refused, "{s:?}");
        }
        // pos inside bounds: checked by plan (after the frame), not by resolve.
        let outside = at(-1.0);
        assert_eq!(
            refusal(plan(&outside, &frame)),
            Some(("OutOfRange", "state.pos"))
        );
        let resolve_frame = WireResolveFrame::new(bounds);
        let out_plan = AntPlan {
            state: outside,
            predicted: outside.pos,
        };
        assert!(ant::resolve(&out_plan, &resolve_frame, &p).is_ok());
        // A neighbour may not carry ctx.agent.
        let mut f = frame.clone();
        f.neighbours
            .push(AntNeighbor {
                id: 7,
                pos: Vec2::from_f32(5.5, 5.0),
                label: Label::Nothing,
                nest: 0,
                origin: 0,
                arrival: Vec2::from_f32(5.5, 5.0),
            })
            .unwrap();
        assert_eq!(
            refusal(plan(&state, &f)),
            Some(("Inconsistent", "neighbours.id"))
        );
        // Disc radius: from the scalar's smallest step.
        let disc = |radius: f32| {
            let mut f = frame.clone();
            let center = Vec2::from_f32(50.0, 50.0);
            f.objects
                .push(AntObject::Food {
                    id: 1,
                    center,
                    radius,
                })
                .unwrap();
            plan(&state, &f)
        };
        assert!(disc(f32::EPSILON).is_ok());
        assert_eq!(
            refusal(disc(f32::EPSILON / 2.0)),
            Some(("OutOfRange", "objects.radius"))
        );
        // Stop rules.
        let stopped = |motion, stop| AntState {
            motion,
            stop,
            ..state
        };
        let timer = |reason, remaining, place| {
            Some(StopTimer {
                reason,
                remaining,
                place,
            })
        };
        assert!(
            stopped(MotionState::Stop, timer(StopReason::Casual, 1, 99))
                .validate()
                .is_ok()
        );
        assert_eq!(
            refusal(stopped(MotionState::Stop, timer(StopReason::Casual, 0, 0)).validate()),
            Some(("OutOfRange", "state.stop.remaining"))
        );
        assert_eq!(
            refusal(
                stopped(MotionState::BasicMovement, timer(StopReason::Casual, 1, 0)).validate()
            ),
            Some(("Inconsistent", "state.stop"))
        );
        assert_eq!(
            refusal(stopped(MotionState::Stop, timer(StopReason::DroppingFood, 1, 0)).validate()),
            Some(("Inconsistent", "state.stop.reason"))
        );
    }

    /// Section 7 and 10.8: how a bee step reads `forward` (and ignores density, u0, roll,
    /// pitch).
    #[test]
    fn bee_forward_is_replaced_as_documented() {
        let p = BeeParams::<f32>::default();
        let v = Vec3::<f32>::from_f32;
        let hover = BeeState::new(v(1.0, 2.0, 3.0), v(0.0, 0.0, 0.0));
        let step = |s: &BeeState<f32>, goal: Option<Vec3<f32>>| {
            let mut f = WireBeeFrame::<f32>::new(1.0);
            f.goal = goal;
            bee::step(s, &f, &p).unwrap()
        };
        // Hovering: forward normalised; zero forward: toward the goal, else +x.
        let s = BeeState {
            forward: v(0.0, 0.0, -3.0),
            ..hover
        };
        assert_eq!(step(&s, None).1.forward, v(0.0, 0.0, -1.0));
        let s = BeeState {
            forward: Vec3::zero(),
            ..hover
        };
        assert_eq!(step(&s, Some(v(1.0, 2.0, 5.0))).1.forward, v(0.0, 0.0, 1.0));
        assert_eq!(step(&s, None).1.forward, v(1.0, 0.0, 0.0));
        // Moving: forward ignored.
        let moving = BeeState {
            vel: v(0.0, 2.0, 0.0),
            ..hover
        };
        let a = step(
            &BeeState {
                forward: v(5.0, 0.0, 0.0),
                ..moving
            },
            None,
        );
        let b = step(
            &BeeState {
                forward: v(0.0, 0.0, 0.0),
                ..moving
            },
            None,
        );
        assert_eq!(a, b);
        assert_eq!(a.1.forward, v(0.0, 1.0, 0.0));
        // density, u0, roll, pitch: checked, not used.
        let c = step(
            &BeeState {
                density: 7.0,
                u0: v(1.0, 1.0, 1.0),
                roll: 0.5,
                pitch: -0.5,
                ..moving
            },
            None,
        );
        assert_eq!(a, c);
        let bad = BeeState {
            density: -1.0,
            ..moving
        };
        assert_eq!(
            refusal(bad.validate()),
            Some(("OutOfRange", "state.density"))
        );
    }

    /// A postcard encoding of any length (the messages are longer than `postcard_bytes`
    /// takes).
    fn encoded_len<T: Serialize>(v: &T) -> usize {
        let mut buf = vec![0u8; 2 * MAX_FRAME];
        postcard::to_slice(v, &mut buf).unwrap().len()
    }

    /// The widest li request and reply with every scalar `w` (4 bytes in `f32`, 5 in `Fx`
    /// for `i32::MIN`): full lists, every integer at its maximum.
    fn widest_li<S: Scalar + Serialize>(w: S) -> [usize; 2] {
        let v = Vec3::new(w, w, w);
        let state = LiState {
            pos: v,
            vel: v,
            waypoint: v,
            seg_start: v,
            age: u16::MAX,
        };
        let mut frame = WireLiFrame::<S>::new();
        while frame
            .neighbours
            .push(Neighbour {
                id: u32::MAX,
                pos: v,
                vel: v,
            })
            .is_ok()
        {}
        while frame
            .surfaces
            .push(Surface3 {
                point: v,
                normal: v,
            })
            .is_ok()
        {}
        let ctx = StepCtx {
            seed: u32::MAX,
            agent: u32::MAX,
            step: u32::MAX,
        };
        let decision = crate::li::LiDecision {
            pref: v,
            proposals: u8::MAX,
            accepted: true,
            infeasible: true,
        };
        [
            encoded_len(&LiStepRequest { state, frame, ctx }),
            encoded_len(&LiStepReply { decision, state }),
        ]
    }

    /// The first number of a cell (`771 (MAX_LI_FRAME, likewise)` → 771).
    fn first_number(cell: &str) -> usize {
        let digits: String = cell.chars().take_while(char::is_ascii_digit).collect();
        digits
            .parse()
            .unwrap_or_else(|_| panic!("no leading number: {cell:?}"))
    }

    /// Sections 5, 7, 10.1 and 10.7 for the li controller: its kinds, its message sizes, its
    /// capacities and its device's buffers and identity; and the 10.7 buffer table for every
    /// device.
    #[test]
    fn li_sizes_buffers_and_identity_as_documented() {
        // Section 5: the kinds.
        let kinds = table(section("## 5.", "## 6."), "message");
        let row = |k: &str| kinds.iter().find(|r| r[0] == k).unwrap().clone();
        assert_eq!(row("0x50")[1], "LiStepRequest<S>");
        assert_eq!(row("0x51")[1], "LiStepReply<S>");
        assert_eq!(kind::LI_STEP_REQUEST, 0x50);
        assert_eq!(kind::LI_STEP_REPLY, 0x51);
        assert!(kind::is_reply(0x51) && !kind::is_reply(0x50));
        for r in ["0x42-0x4F", "0x52-0x7F"] {
            assert_eq!(row(r)[1], "reserved", "{r}");
        }
        // Section 7: the largest payloads, both scalars.
        let f = widest_li(1.0f32);
        let x = widest_li(Fx::from_bits(i32::MIN));
        let messages = table(section("## 7.", "## 8."), "max payload f32 / Fx");
        let size = |k: &str| messages.iter().find(|r| r[0] == k).unwrap()[3].clone();
        assert_eq!(size("0x50"), format!("{} / {}", f[0], x[0]));
        assert_eq!(size("0x51"), format!("{} / {}", f[1], x[1]));
        assert_eq!((f, x), ([628, 66], [760, 81]));
        assert_eq!(MAX_LI_PAYLOAD, x[0]);
        assert_eq!(MAX_LI_REPLY_PAYLOAD, x[1]);
        assert_eq!(MAX_LI_FRAME, max_frame_len(MAX_LI_PAYLOAD));
        assert_eq!(MAX_LI_REPLY_FRAME, max_frame_len(MAX_LI_REPLY_PAYLOAD));
        const { assert!(MAX_LI_PAYLOAD <= MAX_PAYLOAD) };
        let seven = section("## 7.", "## 8.");
        for said in [
            format!("li messages within {MAX_LI_PAYLOAD}"),
            format!("the longest li frame is {MAX_LI_FRAME} bytes"),
            format!("`LiStepReply<Fx>`, is {MAX_LI_REPLY_PAYLOAD} bytes"),
            format!("li\nneighbours {WIRE_LI_NEIGHBOURS}, li surfaces {WIRE_LI_SURFACES}"),
            format!("The largest payload is {MAX_PAYLOAD}"),
        ] {
            assert!(seven.contains(&said), "section 7 says {said:?}");
        }
        // 10.1: the device's identity.
        let params = LiParams::<f32>::default();
        let dev = LiDevice::<f32>::new(params.clone(), "li-test").unwrap();
        let id = dev.identity();
        assert_eq!(id.controller, ControllerKind::LI);
        assert_eq!(id.controller, ControllerKind(4));
        let c = id.capacities;
        assert_eq!(
            (c.neighbours, c.objects, c.targets, c.surfaces),
            (16, 0, 0, 4)
        );
        assert_eq!(usize::from(c.neighbours), WIRE_LI_NEIGHBOURS);
        assert_eq!(usize::from(c.surfaces), WIRE_LI_SURFACES);
        assert_eq!(usize::from(id.max_frame), MAX_LI_FRAME + 1);
        assert_eq!(id.rx_buffer, 0);
        assert_eq!(id.params_hash, params_hash(&params).unwrap());
        let ten_one = section("### 10.1", "### 10.2");
        for said in [
            "`4` li, `5`-`127` kept".to_string(),
            "4 li, 5-127 reserved".to_string(),
            format!(
                "li `{{{}, {}, {}, {}}}`",
                c.neighbours, c.objects, c.targets, c.surfaces
            ),
            format!(
                "`LiDevice` {} (the longest li frame, {MAX_LI_FRAME}, + 1)",
                id.max_frame
            ),
        ] {
            assert!(ten_one.contains(&said), "10.1 says {said:?}");
        }
        // 10.7: every device's buffers (first number of each cell).
        let buffers = section("### 10.7", "### 10.8");
        let rows = table(buffers, "li device");
        let max_frames = [
            ant_device::<f32>().identity().max_frame,
            bee_device::<f32>().identity().max_frame,
            wang_device::<f32>().identity().max_frame,
            fly_device::<f32>(FlyParams::default()).identity().max_frame,
            id.max_frame,
        ];
        let frames = [
            MAX_ANT_FRAME,
            MAX_BEE_FRAME,
            MAX_WANG_FRAME,
            MAX_FLY_FRAME,
            MAX_LI_FRAME,
        ];
        let reply_frames = [
            MAX_ANT_REPLY_FRAME,
            MAX_BEE_REPLY_FRAME,
            MAX_WANG_REPLY_FRAME,
            MAX_FLY_REPLY_FRAME,
            MAX_LI_REPLY_FRAME,
        ];
        for device in 0..5 {
            let cell = |r: usize| rows[r][1 + device].as_str();
            assert_eq!(first_number(cell(0)), frames[device], "RX, column {device}");
            assert_eq!(first_number(cell(1)), usize::from(max_frames[device]));
            assert_eq!(usize::from(max_frames[device]), frames[device] + 1);
            assert_eq!(first_number(cell(3)), frames[device], "longest request");
            assert_eq!(
                first_number(cell(4)),
                reply_frames[device],
                "TX, column {device}"
            );
        }
        assert!(rows[4][5].contains(&format!("{MAX_LI_REPLY_PAYLOAD} B payload")));
        assert!(buffers.contains("(82, 130, 79, 79 or 89\nbytes)"));
    }

    /// The kinds of every request: the controllers' request kinds known to this build.
    fn request_kinds() -> Vec<u8> {
        (0x10..=0x7fu8)
            .filter(|&k| kind::name(k).is_some() && !kind::is_reply(k))
            .collect()
    }

    /// The error codes a device with an open session answers to an empty frame of each kind.
    fn codes_for<C: Controller, const RX: usize, const TX: usize>(
        mut dev: DeviceEndpoint<C, RX, TX>,
        kinds: &[u8],
    ) -> Vec<u8> {
        open(&mut dev, 1);
        kinds
            .iter()
            .map(|&k| {
                let r = replies(&mut dev, &frame_of_kind(k, u16::from(k), &()));
                assert_eq!(r.len(), 1, "kind {k:#04x}");
                let (seq, code) = error_code(&r[0]);
                assert_eq!(seq, u16::from(k));
                code
            })
            .collect()
    }

    /// 10.4, `UnknownKind`: the other controllers' requests listed for each device, and the
    /// reserved ranges, are exactly the kinds each device answers with code 11.
    #[test]
    fn unknown_kind_lists_as_documented() {
        let text = section("### 10.4", "### 10.5");
        let row = table(text, "the device sends it when")
            .into_iter()
            .find(|r| r[0] == "11")
            .unwrap();
        let cell = row[2].as_str();
        let start = "another controller's requests (";
        let lists = &cell[cell.find(start).unwrap() + start.len()..];
        let lists = &lists[..lists.find("), a reserved kind (").unwrap()];
        let hex = |s: &str| u8::from_str_radix(s.trim().trim_start_matches("0x"), 16).unwrap();
        let mut documented: Vec<(String, Vec<u8>)> = Vec::new();
        for part in lists.split(", ") {
            let (kinds, device) = part.split_once(" to ").unwrap();
            let device = device
                .trim_start_matches("an ")
                .trim_start_matches("a ")
                .trim_end_matches(" device");
            documented.push((
                device.to_string(),
                kinds.split_whitespace().map(hex).collect(),
            ));
        }
        let names: Vec<&str> = documented.iter().map(|d| d.0.as_str()).collect();
        assert_eq!(names, ["ant", "bee", "wang", "fly", "li"]);
        // The reserved ranges: every kind from 0x01 to 0x7F this build does not know.
        let reserved = &cell[cell.find("a reserved kind (").unwrap() + 17..];
        let reserved = &reserved[..reserved.find(')').unwrap()];
        let mut unknown: Vec<u8> = Vec::new();
        for r in reserved.split(", ") {
            let (lo, hi) = r.split_once('-').unwrap();
            unknown.extend(hex(lo)..=hex(hi));
        }
        assert_eq!(
            unknown,
            (0x01..=0x7fu8)
                .filter(|&k| kind::name(k).is_none())
                .collect::<Vec<_>>()
        );
        let requests = request_kinds();
        assert_eq!(requests, [0x10, 0x12, 0x20, 0x30, 0x32, 0x40, 0x50]);
        let all: Vec<u8> = requests.iter().chain(&unknown).copied().collect();
        let got = [
            codes_for(ant_device::<f32>(), &all),
            codes_for(bee_device::<f32>(), &all),
            codes_for(wang_device::<f32>(), &all),
            codes_for(fly_device::<f32>(FlyParams::default()), &all),
            codes_for(
                LiDevice::<f32>::new(LiParams::default(), "li-test").unwrap(),
                &all,
            ),
        ];
        for ((device, listed), codes) in documented.iter().zip(got) {
            for (&k, &code) in all.iter().zip(&codes) {
                // Its own requests with an empty payload do not decode: Payload.
                let expected = if listed.contains(&k) || unknown.contains(&k) {
                    ErrorReply::UNKNOWN_KIND
                } else {
                    ErrorReply::PAYLOAD
                };
                assert_eq!(code, expected, "{device} device, kind {k:#04x}");
            }
            assert!(listed.iter().all(|k| requests.contains(k)), "{device}");
        }
    }

    /// 10.2: the li parameters' rules, in their order, with the field each error names.
    #[test]
    fn li_params_rules_as_documented() {
        let ok = LiParams::<f32>::default();
        assert_eq!(ok.validate(), Ok(()));
        let bad = |p: &LiParams<f32>| match p.validate() {
            Err(Error::BadParam { field }) => Some(field),
            Ok(()) => None,
            Err(e) => panic!("{e:?}"),
        };
        let with_lengths = |lo: f32, hi: f32, cdf: &[f32]| LiParams {
            lengths: Table {
                lo,
                hi,
                cdf: heapless::Vec::from_slice(cdf).unwrap(),
            },
            ..ok.clone()
        };
        let with_turns = |lo: f32, hi: f32| LiParams {
            turns: Table {
                lo,
                hi,
                ..ok.turns.clone()
            },
            ..ok.clone()
        };
        let with_grid = |origin: Vec3<f32>, cell: f32, dims: [u16; 3], n: usize| LiParams {
            density: DensityGrid {
                origin,
                cell,
                dims,
                weights: heapless::Vec::from_slice(&vec![7u8; n]).unwrap(),
            },
            ..ok.clone()
        };
        let limit = core::f32::consts::PI + 1e-3;
        let above = f32::from_bits(limit.to_bits() + 1);
        let origin = Vec3::zero();
        for (p, refused) in [
            // Tables: lo < hi, shares non-decreasing in [0, 1], the last exactly 1.
            (with_lengths(0.0, 0.1, &[0.0, 0.5, 0.5, 1.0]), None),
            (with_lengths(0.1, 0.1, &[1.0]), Some("lengths")),
            (with_lengths(0.0, 0.1, &[]), Some("lengths")),
            (with_lengths(0.0, 0.1, &[0.6, 0.5, 1.0]), Some("lengths")),
            (with_lengths(0.0, 0.1, &[0.5, 0.999_999]), Some("lengths")),
            (with_lengths(0.0, 0.1, &[-0.1, 1.0]), Some("lengths")),
            (with_lengths(0.0, f32::INFINITY, &[1.0]), Some("lengths")),
            (with_lengths(-0.001, 0.1, &[1.0]), Some("lengths")),
            // turns within ±(f32(π) + 0.001), limits included.
            (with_turns(-limit, limit), None),
            (with_turns(-limit, above), Some("turns")),
            (with_turns(-above, 0.0), Some("turns")),
            // Grid: origin a li vector, cell finite and > 0, dims ≥ 1, one weight a cell.
            (with_grid(origin, 0.5, [16, 16, 16], 4096), None),
            (
                with_grid(Vec3::new(16000.0, 0.0, 0.0), 0.5, [1, 1, 1], 1),
                None,
            ),
            (
                with_grid(Vec3::new(16001.0, 0.0, 0.0), 0.5, [1, 1, 1], 1),
                Some("density"),
            ),
            (with_grid(origin, 0.0, [1, 1, 1], 1), Some("density")),
            (with_grid(origin, f32::NAN, [1, 1, 1], 1), Some("density")),
            (with_grid(origin, 0.5, [0, 1, 1], 0), Some("density")),
            (with_grid(origin, 0.5, [2, 2, 2], 7), Some("density")),
            // The numbers come first, in table order; then lengths, turns, density.
            (
                LiParams {
                    fallback: 2,
                    ..with_lengths(0.1, 0.1, &[1.0])
                },
                Some("fallback"),
            ),
            (
                LiParams {
                    turns: with_turns(0.0, 4.0).turns,
                    ..with_lengths(0.1, 0.1, &[1.0])
                },
                Some("lengths"),
            ),
            (
                LiParams {
                    density: with_grid(origin, 0.0, [1, 1, 1], 1).density,
                    ..with_turns(0.0, 4.0)
                },
                Some("turns"),
            ),
        ] {
            assert_eq!(bad(&p), refused, "{p:?}");
        }
        // A device refuses bad parameters at start-up.
        assert!(LiDevice::<f32>::new(with_turns(0.0, 4.0), "x").is_err());
    }

    /// Section 7, "The li step", computed from the text alone (in `f32`): the random numbers,
    /// the table draws, the directions, the grid and the screening give the waypoint, the
    /// segment start, the proposal count and the acceptance of `li::step`, bit for bit; then
    /// the preferred velocity, the age and the move. And the li checks of section 7.
    #[test]
    fn li_step_as_documented() {
        // rand and unit_open, as written in section 7.
        let mix = |mut x: u32| {
            x ^= x >> 16;
            x = x.wrapping_mul(0x7feb_352d);
            x ^= x >> 15;
            x = x.wrapping_mul(0x846c_a68b);
            x ^= x >> 16;
            x
        };
        let u = |ctx: StepCtx, stream: u32| {
            let r = mix(mix(mix(mix(ctx.seed ^ 0x9e37_79b9) ^ ctx.agent) ^ ctx.step) ^ stream);
            ((r >> 8) as f32 + 0.5) * (1.0 / 16_777_216.0)
        };
        assert_eq!(mix(mix(mix(mix(0x9e37_79b9)))), 0x41f3_9e5e);
        let sample = |t: &Table<f32, { crate::li::BINS }>, u: f32| {
            let m = t.cdf.len();
            let k = t.cdf.iter().filter(|&&c| c <= u).count();
            if k == m {
                return t.hi;
            }
            let b = if k == 0 { 0.0 } else { t.cdf[k - 1] };
            t.lo + (k as f32 + (u - b) / (t.cdf[k] - b)) * ((t.hi - t.lo) / m as f32)
        };
        let direction = |h: Vec3<f32>, theta: f32, phi: f32, z: f32| {
            let (s_phi, c_phi) = Scalar::sin_cos(phi);
            let Some(n) = h.normalized() else {
                let r = Scalar::sqrt((1.0 - z * z).max(0.0));
                return Vec3::new(r * c_phi, z, r * s_phi);
            };
            let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
            let a = if ax <= ay && ax <= az {
                Vec3::new(1.0, 0.0, 0.0)
            } else if ay <= az {
                Vec3::new(0.0, 1.0, 0.0)
            } else {
                Vec3::new(0.0, 0.0, 1.0)
            };
            let e1 = n.cross(a).normalized().unwrap();
            let e2 = n.cross(e1);
            let (s_t, c_t) = Scalar::sin_cos(theta.abs());
            n * c_t + (e1 * c_phi + e2 * s_phi) * s_t
        };
        let weight = |g: &DensityGrid<f32>, p: Vec3<f32>| -> Option<u8> {
            let q = [
                (p.x - g.origin.x) / g.cell,
                (p.y - g.origin.y) / g.cell,
                (p.z - g.origin.z) / g.cell,
            ];
            let mut i = [0usize; 3];
            for a in 0..3 {
                if !q[a].is_finite() || q[a] < 0.0 || q[a].floor() >= f32::from(g.dims[a]) {
                    return None;
                }
                i[a] = q[a].floor() as usize;
            }
            let [nx, ny, _] = g.dims.map(usize::from);
            Some(g.weights[i[0] + nx * (i[1] + ny * i[2])])
        };
        // The documented waypoint state: (g, s, proposals, accepted).
        let waypoint = |st: &LiState<f32>, p: &LiParams<f32>, ctx: StepCtx| {
            let x = st.pos;
            let g = if st.age >= p.patience { x } else { st.waypoint };
            let s = st.seg_start;
            if (x - g).length_sq() > p.eps * p.eps {
                return (g, s, 0u8, false);
            }
            let w = |c| weight(&p.density, c).unwrap_or(0);
            let w_x = w(x);
            let came = x - s;
            for a in 0..p.proposals {
                let draw = |k: u32| u(ctx, 0x50 + k + 256 * u32::from(a));
                let c = if p.sampling == SAMPLING_RANDOM {
                    let d = &p.density;
                    let side = |n: u16| d.cell * f32::from(n);
                    let hi =
                        d.origin + Vec3::new(side(d.dims[0]), side(d.dims[1]), side(d.dims[2]));
                    let lo = d.origin;
                    lo + Vec3::new(
                        (hi.x - lo.x) * draw(0),
                        (hi.y - lo.y) * draw(1),
                        (hi.z - lo.z) * draw(2),
                    )
                } else {
                    let l = sample(&p.lengths, draw(0));
                    let theta = sample(&p.turns, draw(1));
                    let phi = (2.0 * draw(2) - 1.0) * core::f32::consts::PI;
                    let z = 2.0 * draw(3) - 1.0;
                    let h = if a.is_multiple_of(2) { came } else { -came };
                    x + direction(h, theta, phi, z) * l
                };
                let accepted = if p.sampling == SAMPLING_MH {
                    let w_c = w(c);
                    w_c > 0 && (w_x <= w_c || draw(4) * f32::from(w_x) < f32::from(w_c))
                } else {
                    weight(&p.density, c).is_some()
                };
                if accepted {
                    return (c, x, a + 1, true);
                }
            }
            let s_held = if p.proposals.is_multiple_of(2) {
                s
            } else {
                x + came
            };
            (x, s_held, p.proposals, false)
        };
        let mut g = Gen::new(2015);
        let weights: Vec<u8> = (0..64)
            .map(|_| [0u8, 1, 5, 40, 200][g.below(5) as usize])
            .collect();
        let mut params = LiParams::<f32> {
            density: DensityGrid::new(Vec3::new(-0.5, 0.0, -0.5), 0.25, [4, 4, 4], &weights)
                .unwrap(),
            lengths: Table::from_counts(0.01, 0.3, &[5, 1, 3, 8, 2]).unwrap(),
            turns: Table::from_counts(-1.0, 2.5, &[1, 4, 9, 4, 1, 1]).unwrap(),
            proposals: 5,
            patience: 20,
            ..LiParams::default()
        };
        let mut seen = [0usize; 4]; // not arrived, accepted first, accepted later, held
        for i in 0..1200 {
            params.sampling = [SAMPLING_MH, SAMPLING_MESO, SAMPLING_RANDOM][i % 3];
            let pos = g.v3::<f32>(-0.6, 1.1);
            let state = LiState {
                pos,
                vel: g.v3(-0.1, 0.1),
                waypoint: if g.chance(0.5) { pos } else { g.v3(-0.6, 1.1) },
                seg_start: if g.chance(0.1) { pos } else { g.v3(-0.6, 1.1) },
                age: g.below(30) as u16,
            };
            let ctx = StepCtx {
                seed: g.u32(),
                agent: g.below(8),
                step: g.u32(),
            };
            let frame = WireLiFrame::<f32>::new();
            let (next, decision) = crate::li::step(&state, &frame, &params, ctx).unwrap();
            let (wp, s, proposals, accepted) = waypoint(&state, &params, ctx);
            let what = format!("case {i}: {state:?} {ctx:?} {params:?}");
            assert_eq!(next.waypoint, wp, "{what}");
            assert_eq!(next.seg_start, s, "{what}");
            assert_eq!(
                (decision.proposals, decision.accepted),
                (proposals, accepted),
                "{what}"
            );
            seen[match (proposals, accepted) {
                (0, _) => 0,
                (1, true) => 1,
                (_, true) => 2,
                _ => 3,
            }] += 1;
            // The preferred velocity, the age, the move.
            let d = wp - pos;
            let reach = params.speed * params.dt;
            let pref = if d.length_sq() <= reach * reach {
                d * (1.0 / params.dt)
            } else {
                d.normalized().map_or(Vec3::zero(), |n| n * params.speed)
            };
            assert_eq!(decision.pref, pref, "{what}");
            let age = if proposals > 0 { 0 } else { state.age + 1 };
            assert_eq!(next.age, age);
            assert_eq!(next.pos, pos + next.vel * params.dt);
        }
        assert!(seen.iter().all(|&n| n > 20), "every branch: {seen:?}");

        // The checks, in order, and what is skipped.
        let p = LiParams::<f32>::default();
        let ctx = StepCtx {
            seed: 1,
            agent: 7,
            step: 3,
        };
        let state = LiState::at(Vec3::new(0.3, 0.3, 0.3));
        let neighbour = |id: u32, x: f32| Neighbour {
            id,
            pos: Vec3::new(x, 0.3, 0.3),
            vel: Vec3::zero(),
        };
        let step = |s: &LiState<f32>, f: &WireLiFrame<f32>| crate::li::step(s, f, &p, ctx);
        let mut frame = WireLiFrame::<f32>::new();
        frame.neighbours.push(neighbour(3, 0.31)).unwrap();
        let reference = step(&state, &frame).unwrap();
        // An entry with ctx.agent is skipped, not refused.
        let mut own = frame.clone();
        own.neighbours.push(neighbour(7, 0.3)).unwrap();
        assert_eq!(step(&state, &own), Ok(reference));
        own.neighbours.push(neighbour(7, 0.5)).unwrap();
        assert_eq!(
            refusal(step(&state, &own)),
            Some(("Inconsistent", "frame.neighbours.id"))
        );
        // age: any u16; at patience or more the waypoint counts as reached.
        let far = LiState {
            waypoint: Vec3::new(0.8, 0.8, 0.8),
            ..state
        };
        assert_eq!(step(&far, &frame).unwrap().1.proposals, 0);
        for age in [p.patience, u16::MAX] {
            let old = LiState { age, ..far };
            let (next, decision) = step(&old, &frame).unwrap();
            assert!(decision.proposals > 0);
            assert_eq!((next.seg_start, next.age), (old.pos, 0));
        }
        // Field names and codes, state before frame, neighbours before surfaces.
        let surface = |len: f32| Surface3 {
            point: Vec3::new(0.0, 0.0, 0.0),
            normal: Vec3::new(0.0, len, 0.0),
        };
        let mut framed = frame.clone();
        framed.surfaces.push(surface(0.99)).unwrap();
        framed.surfaces.push(surface(1.01)).unwrap();
        assert!(step(&state, &framed).is_ok());
        framed.surfaces.push(surface(0.98)).unwrap();
        assert_eq!(
            refusal(step(&state, &framed)),
            Some(("OutOfRange", "frame.surfaces.normal"))
        );
        let mut bad_neighbour = framed.clone();
        bad_neighbour
            .neighbours
            .push(neighbour(4, 16001.0))
            .unwrap();
        assert_eq!(
            refusal(step(&state, &bad_neighbour)),
            Some(("OutOfRange", "frame.neighbours.pos"))
        );
        let v = |x: f32| Vec3::new(x, 0.0, 0.0);
        for (s, refused) in [
            (
                LiState {
                    pos: v(16000.0),
                    waypoint: v(16000.0),
                    seg_start: v(16000.0),
                    ..state
                },
                None,
            ),
            (
                LiState {
                    pos: v(f32::NAN),
                    ..state
                },
                Some(("NonFinite", "state.pos")),
            ),
            (
                LiState {
                    vel: v(16001.0),
                    ..state
                },
                Some(("OutOfRange", "state.vel")),
            ),
            (
                LiState {
                    waypoint: v(f32::INFINITY),
                    ..state
                },
                Some(("NonFinite", "state.waypoint")),
            ),
            (
                LiState {
                    seg_start: v(-16001.0),
                    ..state
                },
                Some(("OutOfRange", "state.seg_start")),
            ),
        ] {
            assert_eq!(
                refusal(step(&s, &framed)),
                refused.or(Some(("OutOfRange", "frame.surfaces.normal"))),
                "{s:?}"
            );
        }
    }
}
