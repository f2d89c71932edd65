//! Writes a session transcript for a serial node: every request frame a host would send and
//! the exact reply frame the node must answer, computed here on the host by the same
//! `swarm-core` endpoint with the node's parameters. `scripts/qemu-serial.sh --replay` sends
//! the requests to an image in QEMU and checks every reply byte for byte, without the
//! `swarm-hil` harness.
//!
//! ```text
//! cargo run -p fw-node --example transcript -- ant|bee|fly f32|fixed STEPS > transcript.txt
//! ```
//!
//! One line per request: `<request hex> <reply hex>` (whole frames, delimiter included; the
//! first line starts with a lone `00`). The session: `Hello` → `Identity`, `Configure` →
//! `Configured`, then STEPS ticks of a small world driven by the node's own replies:
//!
//! * ants: 12 ants of one colony around a nest, a food source, a rock and a disturbance in a
//!   40 × 40 arena; each tick an `AntPlanRequest` per ant, then an `AntResolveRequest` per ant
//!   with the neighbours' predictions (2 requests per ant and tick);
//! * bees: 10 bees near a flower (8 target particles), a rock and a goal; one `BeeStepRequest`
//!   per bee and step;
//! * flies: 10 midges in a cloud against a wall of the self-check scenario's box
//!   (`fw_scenario::fly::sense`: the nearest neighbours within r_att, the walls within reach as
//!   ORCA surfaces); one `FlyStepRequest` per insect and step.
//!
//! The last two lines are a `Ping` and a `StatsRequest` (whose reply counts the whole session).

use std::io::Write as _;

use fw_node::swarm_core::ant::{AntObject, AntParams, AntPlan, AntState, PlanFrame, Surface};
use fw_node::swarm_core::bee::BeeNeighbor;
use fw_node::swarm_core::bee::{BeeParams, BeeState, ObstacleSense};
use fw_node::swarm_core::fly::{
    FlyDevice, FlyParams, FlyState, FlyStepReply, FlyStepRequest, WIRE_FLY_NEIGHBOURS,
    WIRE_FLY_SURFACES,
};
use fw_node::swarm_core::wire::{
    self, AntDevice, AntPlanReply, AntPlanRequest, AntResolveReply, AntResolveRequest, BeeDevice,
    BeeStepReply, BeeStepRequest, Configure, Controller, DeviceEndpoint, Hello, Identity, Message,
    Ping, StatsRequest, WireBeeFrame, WireResolveFrame,
};
use fw_node::swarm_core::{Fx, Rect, Scalar, StepCtx, Vec2, Vec3, rand::rand};
use fw_node::{NodeScalar, ant_device, bee_device, fly_device};
use fw_scenario::ant::neighbour as ant_neighbour;

const SEED: u32 = 5;

/// Deterministic value in [lo, hi).
fn uniform(key: u32, salt: u32, lo: f32, hi: f32) -> f32 {
    let u = (rand(0x7a4e_5c11, key, salt, 0) >> 8) as f32 / (1u32 << 24) as f32;
    lo + u * (hi - lo)
}

/// A scalar the messages carry (serde).
trait WireScalar: Scalar + serde::Serialize + serde::de::DeserializeOwned {}

impl<S: Scalar + serde::Serialize + serde::de::DeserializeOwned> WireScalar for S {}

struct Session<C, const RX: usize, const TX: usize> {
    device: DeviceEndpoint<C, RX, TX>,
    seq: u16,
    lines: Vec<String>,
}

fn hex(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02x}")).collect()
}

impl<C: Controller, const RX: usize, const TX: usize> Session<C, RX, TX> {
    /// Sends `msg` (with `prefix` bytes before it), records the exchange, returns the reply.
    fn send<M: Message>(&mut self, prefix: &[u8], msg: &M) -> Vec<u8> {
        self.seq = self.seq.wrapping_add(1);
        let mut line = prefix.to_vec();
        let mut buf = vec![0u8; 1024];
        let n = wire::encode_message(self.seq, msg, &mut buf).expect("request fits");
        line.extend_from_slice(&buf[..n]);
        let mut replies = Vec::new();
        self.device
            .serve(&line, |r| {
                replies.push(r.to_vec());
                Ok::<_, ()>(())
            })
            .unwrap();
        assert_eq!(replies.len(), 1, "one reply per request");
        let reply = replies.pop().unwrap();
        self.lines.push(format!("{} {}", hex(&line), hex(&reply)));
        reply
    }

    /// A session with `device`, opened: `Hello` (after a lone `00`), then `Configure`.
    fn open(device: DeviceEndpoint<C, RX, TX>) -> Self {
        let mut session = Session {
            device,
            seq: 0,
            lines: Vec::new(),
        };
        let id = decode::<Identity>(&session.send(&[0], &Hello)).expect("an Identity");
        let configure = Configure {
            session: 0x5e55,
            params_hash: id.params_hash,
            reset_stats: true,
        };
        session.send(&[], &configure);
        session
    }

    fn close(mut self) -> Vec<String> {
        self.send(&[], &Ping { nonce: 0xfeed_beef });
        self.send(&[], &StatsRequest);
        self.lines
    }
}

/// The reply's message, or `None` for an `ErrorReply`.
fn decode<M: Message>(reply: &[u8]) -> Option<M> {
    let mut raw = reply[..reply.len() - 1].to_vec();
    wire::decode_message::<M>(&mut raw).ok().map(|(_, m)| m)
}

fn ants<S: NodeScalar + WireScalar>(device: AntDevice<S>, steps: u32) -> Vec<String>
where
    AntParams<S>: Controller,
{
    const N: usize = 12;
    let v = Vec2::<S>::from_f32;
    let s = S::from_f32;
    let bounds = Rect::new(v(0.0, 0.0), v(40.0, 40.0));
    let (nest, food, rock, danger) = (
        (v(10.0, 10.0), 3.0),
        (v(30.0, 28.0), 3.0),
        (v(20.0, 19.0), 2.5),
        (v(9.0, 31.0), 3.0),
    );
    let mut ants: Vec<AntState<S>> = (0..N as u32)
        .map(|i| {
            let a = uniform(i, 1, 0.0, std::f32::consts::TAU);
            let r = uniform(i, 2, 0.0, 5.0);
            let pos = v(10.0 + r * a.cos(), 10.0 + r * a.sin());
            let h = v(a.cos(), a.sin());
            match i % 4 {
                // a few start far out, exploring or laden, so every branch runs early
                1 => {
                    AntState::exploring(0, v(uniform(i, 3, 2.0, 38.0), uniform(i, 4, 2.0, 38.0)), h)
                }
                2 => AntState::at_nest(0, v(29.0 + r * 0.2, 27.0), h),
                _ => AntState::at_nest(0, pos, h),
            }
        })
        .collect();
    let mut session = Session::open(device);
    let hear = s(3.0);
    for step in 0..steps {
        let mut plans: Vec<Option<AntPlan<S>>> = Vec::with_capacity(N);
        for i in 0..N {
            let me = ants[i].pos;
            let mut frame = PlanFrame::new(bounds);
            for (j, a) in ants.iter().enumerate() {
                if j != i && (a.pos - me).length() <= hear {
                    let _ = frame.neighbours.push(ant_neighbour(j, a));
                }
            }
            let sense = s(8.0);
            let near = |c: Vec2<S>, r: f32| (c - me).length() <= sense + s(r);
            if near(nest.0, nest.1) {
                let _ = frame.objects.push(AntObject::Nest {
                    id: 0,
                    center: nest.0,
                    radius: s(nest.1),
                });
            }
            if near(food.0, food.1) {
                let _ = frame.objects.push(AntObject::Food {
                    id: 1,
                    center: food.0,
                    radius: s(food.1),
                });
            }
            if let Some(u) = (me - rock.0).normalized() {
                let closest = rock.0 + u * s(rock.1);
                if (closest - me).length() <= sense
                    && let Some(surface) = Surface::seen_from(me, closest)
                {
                    let _ = frame.objects.push(AntObject::Obstacle(surface));
                }
            }
            if near(danger.0, danger.1) {
                let _ = frame.objects.push(AntObject::Disturbance {
                    center: danger.0,
                    radius: s(danger.1),
                });
            }
            let req = AntPlanRequest {
                state: ants[i],
                frame,
                ctx: StepCtx {
                    seed: SEED,
                    agent: i as u32,
                    step,
                },
            };
            let reply = session.send(&[], &req);
            plans.push(decode::<AntPlanReply<S>>(&reply).map(|r| r.plan));
        }
        for i in 0..N {
            let Some(plan) = plans[i] else { continue };
            let mut frame = WireResolveFrame::new(bounds);
            for (j, p) in plans.iter().enumerate() {
                if let Some(p) = p
                    && j != i
                    && (p.predicted - plan.predicted).length() <= hear
                {
                    let _ = frame.neighbours.push(p.predicted);
                }
            }
            let reply = session.send(&[], &AntResolveRequest { plan, frame });
            if let Some(r) = decode::<AntResolveReply<S>>(&reply) {
                ants[i] = r.state;
            }
        }
    }
    session.close()
}

fn bees<S: WireScalar>(device: BeeDevice<S>, steps: u32) -> Vec<String>
where
    BeeParams<S>: Controller,
{
    const N: usize = 10;
    let v = Vec3::<S>::from_f32;
    let p = fw_node::bee_params::<S>();
    let flower = v(6.0, 1.0, 0.0);
    let petals: Vec<Vec3<S>> = (0..8)
        .map(|k| {
            let a = k as f32 * std::f32::consts::TAU / 8.0;
            flower + v(0.8 * a.cos(), 0.0, 0.8 * a.sin())
        })
        .collect();
    let (rock, rock_r) = (v(3.0, 1.0, -1.3), 1.0);
    let mut bees: Vec<BeeState<S>> = (0..N as u32)
        .map(|i| {
            BeeState::new(
                v(
                    uniform(i, 5, -1.5, 1.5),
                    uniform(i, 6, 0.5, 2.0),
                    uniform(i, 7, -2.5, 1.5),
                ),
                v(uniform(i, 8, 0.3, 1.0), 0.0, uniform(i, 9, -0.2, 0.4)),
            )
        })
        .collect();
    let mut session = Session::open(device);
    for step in 0..steps {
        let prev = bees.clone();
        for i in 0..N {
            let me = prev[i].pos;
            let mut frame = WireBeeFrame::new(S::from_i32(step as i32) * p.dt);
            for (j, b) in prev.iter().enumerate() {
                if j != i && (b.pos - me).length() < p.h {
                    let _ = frame.neighbours.push(BeeNeighbor {
                        pos: b.pos,
                        vel: b.vel,
                        density: b.density,
                    });
                }
            }
            for &q in &petals {
                if (q - me).length() < p.h {
                    let _ = frame.targets.push(q);
                }
            }
            if i != N - 1 {
                frame.goal = Some(flower);
            }
            let away = me - rock;
            if let Some(n) = away.normalized()
                && away.length() - S::from_f32(rock_r) < S::from_f32(4.0)
            {
                frame.obstacle = Some(ObstacleSense {
                    point: rock + n * S::from_f32(rock_r),
                    normal: n,
                });
            }
            let reply = session.send(
                &[],
                &BeeStepRequest {
                    state: prev[i],
                    frame,
                },
            );
            if let Some(r) = decode::<BeeStepReply<S>>(&reply) {
                bees[i] = r.state;
            }
        }
    }
    session.close()
}

fn flies<S: WireScalar>(device: FlyDevice<S>, steps: u32) -> Vec<String>
where
    FlyParams<S>: Controller,
{
    const N: usize = 10;
    let v = Vec3::<S>::from_f32;
    let p = fw_node::fly_params::<S>();
    let mut flies: Vec<FlyState<S>> = (0..N as u32)
        .map(|i| {
            FlyState::new(
                v(
                    uniform(i, 10, 8.0, 11.5),
                    uniform(i, 11, -1.5, 1.5),
                    uniform(i, 12, -1.5, 1.5),
                ),
                v(
                    uniform(i, 13, -0.5, 1.5),
                    uniform(i, 14, -0.5, 0.5),
                    uniform(i, 15, -0.5, 0.5),
                ),
            )
        })
        .collect();
    let mut session = Session::open(device);
    for step in 0..steps {
        let prev = flies.clone();
        for i in 0..N {
            let frame =
                fw_scenario::fly::sense::<S, WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES>(&prev, i, &p);
            let req = FlyStepRequest {
                state: prev[i],
                frame,
                ctx: StepCtx {
                    seed: SEED,
                    agent: i as u32,
                    step,
                },
            };
            let reply = session.send(&[], &req);
            if let Some(r) = decode::<FlyStepReply<S>>(&reply) {
                flies[i] = r.state;
            }
        }
    }
    session.close()
}

/// `device` reporting a receive buffer of `fifo` bytes.
fn on<C: Controller, const RX: usize, const TX: usize>(
    mut device: DeviceEndpoint<C, RX, TX>,
    fifo: u32,
) -> DeviceEndpoint<C, RX, TX> {
    device.set_rx_buffer(fifo);
    device
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: transcript ant|bee|fly f32|fixed STEPS";
    let [model, scalar, steps] = args.as_slice() else {
        eprintln!("{usage}");
        std::process::exit(2);
    };
    let steps: u32 = steps.parse().expect(usage);
    // The images report their board's UART receive FIFO (`fw_support::uart::RX_FIFO`): 16
    // bytes on the ant nodes' PL011, 1 on the bee and fly nodes' CMSDK UART.
    // `qemu-serial.sh --check` compares the images' Identity with these.
    let lines = match (model.as_str(), scalar.as_str()) {
        ("ant", "f32") => ants(on(ant_device::<f32>("ant-node").unwrap(), 16), steps),
        ("ant", "fixed") => ants(on(ant_device::<Fx>("ant-node-fixed").unwrap(), 16), steps),
        ("bee", "f32") => bees(on(bee_device::<f32>("bee-node").unwrap(), 1), steps),
        ("bee", "fixed") => bees(on(bee_device::<Fx>("bee-node-fixed").unwrap(), 1), steps),
        ("fly", "f32") => flies(on(fly_device::<f32>("fly-node").unwrap(), 1), steps),
        ("fly", "fixed") => flies(on(fly_device::<Fx>("fly-node-fixed").unwrap(), 1), steps),
        _ => {
            eprintln!("{usage}");
            std::process::exit(2);
        }
    };
    let mut out = std::io::stdout().lock();
    for l in lines {
        writeln!(out, "{l}").unwrap();
    }
}
