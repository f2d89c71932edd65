//! The host end of a session: handshake, configure, and pipelined requests matched by sequence
//! number, with retransmissions, over any [`Transport`].
//!
//! [`machine`] holds the logic as a pure state machine (no transport, no clock);
//! [`Client`] is the thin driver that reads the transport, feeds the machine, writes what it
//! says and decodes the answers into their types. [`rto`] estimates the retransmission
//! timeout.

pub mod machine;
pub mod rto;

use std::time::{Duration, Instant};

use serde::Serialize;
use serde::de::DeserializeOwned;
use swarm_core::wire::{
    Configure, Configured, DeviceStats, ErrorReply, Hello, Identity, Message, Ping, Pong,
    StatsRequest, decode_payload,
};

pub use machine::{Answer, ClientOptions, Completion, Expect, JobId, LinkReport, Machine};
pub use rto::{Rto, RtoOptions};

use crate::transport::Transport;
use crate::{HilError, Result};

use machine::kind_name;

/// The longest the driver waits in one `recv` when the machine has no deadline.
const IDLE_WAIT: Duration = Duration::from_millis(50);

/// The host end of a session with a device: a [`Machine`] driven over a transport, on the
/// wall clock.
pub struct Client<T> {
    link: T,
    machine: Machine,
    epoch: Instant,
    buf: Vec<u8>,
}

impl<T: Transport> Client<T> {
    /// A client on `link`.
    pub fn new(link: T, opts: ClientOptions) -> Self {
        Client {
            link,
            machine: Machine::new(opts),
            epoch: Instant::now(),
            buf: vec![0; 4096],
        }
    }

    /// The link's counters so far.
    pub fn report(&self) -> LinkReport {
        self.machine.report()
    }

    /// Round-trip times of the answered requests, in microseconds.
    pub fn latencies_us(&self) -> &[u32] {
        self.machine.latencies_us()
    }

    /// The transport.
    pub fn link_mut(&mut self) -> &mut T {
        &mut self.link
    }

    /// The state machine (its counters and timeout).
    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// Handshake: asks the device who it is and checks the answer against `expected`; a
    /// device that differs is refused with a message naming every difference. The window is
    /// then fitted to the device's receive buffer for requests of up to `expected.max_frame`
    /// bytes ([`Machine::fit_window`]).
    pub fn handshake(&mut self, expected: &Identity) -> Result<Identity> {
        let device: Identity = self.call(&Hello)?.map_err(|e| refused("Hello", e))?;
        device
            .check(expected)
            .map_err(|m| HilError::Handshake(m.to_string()))?;
        self.machine
            .fit_window(device.window(usize::from(expected.max_frame)));
        Ok(device)
    }

    /// Opens a session `session` for parameters hashing to `params_hash`.
    pub fn configure(&mut self, session: u32, params_hash: u64) -> Result<()> {
        let msg = Configure {
            session,
            params_hash,
            reset_stats: true,
        };
        let got: Configured = self.call(&msg)?.map_err(|e| refused("Configure", e))?;
        if got.session != session {
            return Err(HilError::WrongSession {
                asked: session,
                got: got.session,
            });
        }
        Ok(())
    }

    /// Ping with `nonce`: the round trip.
    pub fn ping(&mut self, nonce: u32) -> Result<Duration> {
        let t0 = Instant::now();
        let pong: Pong = self
            .call(&Ping { nonce })?
            .map_err(|e| refused("Ping", e))?;
        if pong.nonce != nonce {
            return Err(HilError::PingNonce {
                sent: nonce,
                got: pong.nonce,
            });
        }
        Ok(t0.elapsed())
    }

    /// The device's counters.
    pub fn device_stats(&mut self) -> Result<DeviceStats> {
        self.call(&StatsRequest)?
            .map_err(|e| refused("StatsRequest", e))
    }

    /// One request and its reply (or the device's error reply).
    pub fn call<Q: Message + Serialize, A: Message + DeserializeOwned>(
        &mut self,
        request: &Q,
    ) -> Result<std::result::Result<A, ErrorReply>> {
        let mut out = self.call_all::<Q, A>(std::slice::from_ref(request))?;
        out.pop().ok_or(HilError::LinkDead {
            waiting_for: kind_name(Q::KIND),
            unanswered: 1,
            silent: Duration::ZERO,
        })
    }

    /// Sends every request, at most [`ClientOptions::window`] in flight, and returns the
    /// replies in request order. The [`Machine`] decides what goes when (see its module for
    /// the retransmission rules); this loop only moves bytes and time.
    ///
    /// # Errors
    ///
    /// The transport's, [`HilError::LinkDead`], [`HilError::GaveUp`], [`HilError::Encode`];
    /// the requests of this call are then forgotten.
    pub fn call_all<Q: Message + Serialize, A: Message + DeserializeOwned>(
        &mut self,
        requests: &[Q],
    ) -> Result<Vec<std::result::Result<A, ErrorReply>>> {
        let Partial { replies, error } = self.call_all_partial::<Q, A>(requests);
        match error {
            Some(e) => Err(e),
            None => Ok(replies.into_iter().flatten().collect()),
        }
    }

    /// [`call_all`](Self::call_all), keeping the answers that came before a failure: a
    /// mirror must count a wrong answer even when the link dies right after it.
    pub fn call_all_partial<Q: Message + Serialize, A: Message + DeserializeOwned>(
        &mut self,
        requests: &[Q],
    ) -> Partial<A> {
        let mut raw = Vec::with_capacity(requests.len());
        for q in requests {
            match postcard::to_allocvec(q) {
                Ok(payload) => raw.push(RawRequest {
                    kind: Q::KIND,
                    payload,
                    expect: Expect::reply::<A>(),
                }),
                Err(_) => {
                    return Partial {
                        replies: (0..requests.len()).map(|_| None).collect(),
                        error: Some(HilError::Encode {
                            message: kind_name(Q::KIND),
                            source: swarm_core::Error::Payload,
                        }),
                    };
                }
            }
        }
        let Partial { replies, mut error } = self.call_raw(&raw);
        let replies = replies
            .into_iter()
            .map(|r| {
                r.and_then(|r| match r {
                    Ok(p) => match decode_payload::<A>(&p) {
                        Ok(a) => Some(Ok(a)),
                        // Unreachable: the machine answers only payloads that decode.
                        Err(source) => {
                            error.get_or_insert(HilError::Decode {
                                reply: kind_name(A::KIND),
                                request: kind_name(Q::KIND),
                                source,
                            });
                            None
                        }
                    },
                    Err(e) => Some(Err(e)),
                })
            })
            .collect();
        Partial { replies, error }
    }

    /// Sends every request already encoded, at most [`ClientOptions::window`] in flight, and
    /// returns the reply payloads (each checked to decode as its [`Expect`]) in request order,
    /// keeping the answers that came before a failure. The [`Machine`] decides what goes
    /// when (see its module for the retransmission rules); this loop only moves bytes and
    /// time.
    pub fn call_raw(&mut self, requests: &[RawRequest]) -> Partial<Vec<u8>> {
        let mut replies: Vec<Option<std::result::Result<Vec<u8>, ErrorReply>>> =
            (0..requests.len()).map(|_| None).collect();
        let error = self.drive(requests, &mut replies).err();
        if error.is_some() {
            self.machine.abort();
        }
        Partial { replies, error }
    }

    fn drive(
        &mut self,
        requests: &[RawRequest],
        replies: &mut [Option<std::result::Result<Vec<u8>, ErrorReply>>],
    ) -> Result<()> {
        let mut jobs = Vec::with_capacity(requests.len());
        for q in requests {
            jobs.push(self.machine.submit(q.kind, q.payload.clone(), q.expect));
        }
        let first = jobs.first().map_or(0, |j| j.0);
        let mut done = 0;
        while done < requests.len() {
            self.machine.poll(self.now())?;
            while let Some(frame) = self.machine.transmit() {
                self.link.send(&frame)?;
            }
            while let Some(c) = self.machine.completion() {
                let Some(slot) = c
                    .job
                    .0
                    .checked_sub(first)
                    .and_then(|i| replies.get_mut(usize::try_from(i).ok()?))
                else {
                    continue;
                };
                if slot.is_none() {
                    done += 1;
                }
                *slot = Some(match c.answer {
                    Answer::Reply(p) => Ok(p),
                    Answer::Error(e) => Err(e),
                });
            }
            if done == requests.len() {
                break;
            }
            let now = self.now();
            let wait = self
                .machine
                .poll_at()
                .map_or(IDLE_WAIT, |at| at.saturating_sub(now));
            let n = self.link.recv(&mut self.buf, wait)?;
            let now = self.now();
            self.machine.on_bytes(now, &self.buf[..n]);
        }
        Ok(())
    }

    /// The machine's clock: time since the client was made.
    fn now(&self) -> Duration {
        self.epoch.elapsed()
    }
}

/// A request already encoded: its kind, its payload and the reply it expects.
#[derive(Clone, Debug)]
pub struct RawRequest {
    /// The request's kind.
    pub kind: u8,
    /// Its postcard payload.
    pub payload: Vec<u8>,
    /// The reply it expects.
    pub expect: Expect,
}

/// The answers of [`Client::call_all_partial`]: in request order, `None` for a request not
/// answered when `error` stopped the call.
pub struct Partial<A> {
    /// The answers.
    pub replies: Vec<Option<std::result::Result<A, ErrorReply>>>,
    /// What stopped the call, if anything.
    pub error: Option<HilError>,
}

fn refused(request: &'static str, e: ErrorReply) -> HilError {
    HilError::Refused {
        request,
        name: e.name(),
        code: e.code,
    }
}
