//! The host end of a session: handshake, configure, and pipelined requests matched by sequence
//! number, with timeouts and retries, over any [`Transport`].

use std::collections::{HashMap, VecDeque};
use std::time::{Duration, Instant};

use serde::Serialize;
use serde::de::DeserializeOwned;
use swarm_core::wire::{
    self, Accumulator, Configure, Configured, DeviceStats, ErrorReply, Event, Hello, Identity,
    Message, Ping, Pong, StatsRequest,
};

use crate::transport::Transport;
use crate::{HilError, Result};

/// The receive buffer: longer than any reply of the protocol.
const RX: usize = 2048;

/// How the client paces and retries requests.
#[derive(Clone, Copy, Debug)]
pub struct ClientOptions {
    /// Requests in flight at once.
    pub window: usize,
    /// How long to wait for a reply before sending the request again.
    pub timeout: Duration,
    /// Times a request is sent again before the run fails.
    pub retries: u32,
    /// The link is dead when nothing intact came back for this long.
    pub dead_after: Duration,
}

impl Default for ClientOptions {
    fn default() -> Self {
        ClientOptions {
            window: 8,
            timeout: Duration::from_millis(200),
            retries: 1000,
            dead_after: Duration::from_secs(5),
        }
    }
}

/// What the link went through, host side.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct LinkReport {
    /// Bytes sent.
    pub bytes_tx: u64,
    /// Bytes received.
    pub bytes_rx: u64,
    /// Reply frames dropped for a bad CRC.
    pub crc_errors: u64,
    /// Times the receiver threw bytes away and resynchronised on a delimiter.
    pub resyncs: u64,
    /// Requests whose reply did not come in time (lost requests detected earlier, by a later
    /// reply overtaking them, are counted in `retries` only).
    pub timeouts: u64,
    /// Requests sent again.
    pub retries: u64,
    /// Replies that came for no request in flight (late answers to a retried request).
    pub stale_replies: u64,
    /// [`Ping`] probes sent at the tail of a batch (to detect losses early).
    pub probes: u64,
}

/// The host end of a session with a device.
pub struct Client<T> {
    link: T,
    rx: Accumulator<RX>,
    opts: ClientOptions,
    next_seq: u16,
    report: LinkReport,
    /// Round-trip time of every answered request, in microseconds.
    latencies_us: Vec<u32>,
    buf: Vec<u8>,
}

/// One request in flight.
struct Pending {
    index: usize,
    frame: Vec<u8>,
    sent: Instant,
    first_sent: Instant,
    tries: u32,
    /// Known lost: a later request was answered first.
    lost: bool,
}

impl<T: Transport> Client<T> {
    /// A client on `link`.
    pub fn new(link: T, opts: ClientOptions) -> Self {
        Client {
            link,
            rx: Accumulator::new(),
            opts,
            next_seq: 1,
            report: LinkReport::default(),
            latencies_us: Vec::new(),
            buf: vec![0; RX],
        }
    }

    /// The link's counters so far.
    pub fn report(&self) -> LinkReport {
        let mut r = self.report.clone();
        let s = self.rx.stats();
        r.crc_errors = s.crc_errors.into();
        r.resyncs = s.resyncs().into();
        r
    }

    /// Round-trip times of the answered requests, in microseconds.
    pub fn latencies_us(&self) -> &[u32] {
        &self.latencies_us
    }

    /// The transport.
    pub fn link_mut(&mut self) -> &mut T {
        &mut self.link
    }

    /// Handshake: asks the device who it is and checks the answer against `expected`; a
    /// device that differs is refused with a message naming every difference.
    pub fn handshake(&mut self, expected: &Identity) -> Result<Identity> {
        let device: Identity = self.call(&Hello)?.map_err(|e| refused("Hello", e))?;
        device
            .check(expected)
            .map_err(|m| HilError::Handshake(m.to_string()))?;
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
            return Err(HilError::Protocol(format!(
                "Configure: the device opened session {}, not {session}",
                got.session
            )));
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
            return Err(HilError::Protocol(format!(
                "Ping: nonce {} came back as {}",
                nonce, pong.nonce
            )));
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
        Ok(out.remove(0))
    }

    /// Sends every request, at most [`ClientOptions::window`] in flight, and returns the
    /// replies in request order.
    ///
    /// Losses are repaired by sending the same frame again (same sequence number: requests
    /// are pure, a device may answer twice): at once when a later request's reply overtakes it
    /// (a device answers in order), or when the window has nothing new to send and a small
    /// [`Ping`] probe's answer overtakes it, else after [`ClientOptions::timeout`]. The call
    /// fails with [`HilError::Timeout`] when a request was sent [`ClientOptions::retries`]
    /// times more, or when nothing intact came back for [`ClientOptions::dead_after`].
    pub fn call_all<Q: Message + Serialize, A: Message + DeserializeOwned>(
        &mut self,
        requests: &[Q],
    ) -> Result<Vec<std::result::Result<A, ErrorReply>>> {
        let mut replies: Vec<Option<std::result::Result<A, ErrorReply>>> =
            (0..requests.len()).map(|_| None).collect();
        let mut queue: VecDeque<usize> = (0..requests.len()).collect();
        let mut flight: HashMap<u16, Pending> = HashMap::new();
        // The tail probe in flight: its sequence number and when it went.
        let mut probe: Option<(u16, Instant)> = None;
        let mut rxbuf = [0u8; 4096];
        let mut done = 0;
        let mut heard = Instant::now();
        while done < requests.len() {
            // Fill the window.
            while flight.len() < self.opts.window.max(1) {
                let Some(index) = queue.pop_front() else {
                    break;
                };
                let seq = self.take_seq();
                let n =
                    wire::encode_message(seq, &requests[index], &mut self.buf).map_err(|e| {
                        HilError::Protocol(format!("encoding {}: {e}", kind_name(Q::KIND)))
                    })?;
                let frame = self.buf[..n].to_vec();
                self.send(&frame)?;
                let now = Instant::now();
                flight.insert(
                    seq,
                    Pending {
                        index,
                        frame,
                        sent: now,
                        first_sent: now,
                        tries: 0,
                        lost: false,
                    },
                );
            }
            // Nothing new to send: probe, so a loss shows without waiting for its timeout.
            let probe_late = probe.is_some_and(|(_, t)| t.elapsed() >= self.opts.timeout);
            if queue.is_empty() && !flight.is_empty() && (probe.is_none() || probe_late) {
                let seq = self.take_seq();
                let n = wire::encode_message(seq, &Ping { nonce: seq.into() }, &mut self.buf)
                    .map_err(|e| HilError::Protocol(format!("encoding Ping: {e}")))?;
                let frame = self.buf[..n].to_vec();
                self.send(&frame)?;
                self.report.probes += 1;
                probe = Some((seq, Instant::now()));
            }
            // Wait for bytes until the oldest request's deadline.
            let deadline = flight
                .values()
                .map(|p| p.sent + self.opts.timeout)
                .chain(probe.map(|(_, t)| t + self.opts.timeout))
                .min()
                .unwrap_or_else(Instant::now);
            let wait = deadline.saturating_duration_since(Instant::now());
            let n = self.link.recv(&mut rxbuf, wait)?;
            self.report.bytes_rx += n as u64;
            let mut input = &rxbuf[..n];
            while let Some((event, rest)) = self.rx.feed(input) {
                input = rest;
                let Event::Frame(frame) = event else {
                    continue;
                };
                heard = Instant::now();
                let seq = frame.header.seq;
                // What was sent before the request (or probe) this frame answers.
                let answered_sent = if let Some(p) = flight.remove(&seq) {
                    let reply = if frame.header.kind == A::KIND {
                        frame.message::<A>().map(Ok)
                    } else {
                        frame.message::<ErrorReply>().map(Err)
                    };
                    let reply = reply.map_err(|e| {
                        HilError::Protocol(format!(
                            "reply {} (kind {:#04x}) to {} #{seq}: {e}",
                            kind_name(frame.header.kind),
                            frame.header.kind,
                            kind_name(Q::KIND),
                        ))
                    })?;
                    let us = p.first_sent.elapsed().as_micros().min(u32::MAX as u128) as u32;
                    self.latencies_us.push(us);
                    replies[p.index] = Some(reply);
                    done += 1;
                    p.sent
                } else if let Some((_, t)) = probe.filter(|&(p, _)| p == seq) {
                    probe = None;
                    t
                } else {
                    self.report.stale_replies += 1;
                    continue;
                };
                // A device answers in order: a request sent before and still unanswered was
                // lost (or its reply was); it goes again now rather than at its timeout.
                for q in flight.values_mut().filter(|q| q.sent < answered_sent) {
                    q.lost = true;
                }
            }
            if heard.elapsed() >= self.opts.dead_after {
                return Err(HilError::Timeout {
                    what: format!(
                        "{} ({} of {} answered; the device sent nothing intact)",
                        kind_name(Q::KIND),
                        done,
                        requests.len()
                    ),
                    timeout: self.opts.dead_after,
                });
            }
            // Send again what was lost or timed out.
            let now = Instant::now();
            let late: Vec<u16> = flight
                .iter()
                .filter(|(_, p)| p.lost || now >= p.sent + self.opts.timeout)
                .map(|(&s, _)| s)
                .collect();
            for seq in late {
                let Some(p) = flight.get_mut(&seq) else {
                    continue;
                };
                if !std::mem::take(&mut p.lost) {
                    self.report.timeouts += 1;
                }
                if p.tries >= self.opts.retries {
                    return Err(HilError::Timeout {
                        what: format!("{} #{seq} (sent {} times)", kind_name(Q::KIND), p.tries + 1),
                        timeout: self.opts.timeout,
                    });
                }
                p.tries += 1;
                p.sent = now;
                self.report.retries += 1;
                // A leading delimiter ends whatever partial frame the device may hold (the
                // damaged rest of a lost one), so the retry starts on a clean frame; the
                // device counts an empty frame and ignores it.
                let mut frame = Vec::with_capacity(p.frame.len() + 1);
                frame.push(0);
                frame.extend_from_slice(&p.frame);
                self.send(&frame)?;
            }
        }
        Ok(replies.into_iter().flatten().collect())
    }

    fn send(&mut self, frame: &[u8]) -> Result<()> {
        self.report.bytes_tx += frame.len() as u64;
        self.link.send(frame)
    }

    fn take_seq(&mut self) -> u16 {
        let s = self.next_seq;
        self.next_seq = self.next_seq.wrapping_add(1);
        s
    }
}

fn kind_name(kind: u8) -> &'static str {
    wire::kind::name(kind).unwrap_or("message")
}

fn refused(what: &str, e: ErrorReply) -> HilError {
    HilError::Protocol(format!(
        "{what}: the device answered with error {} (code {})",
        e.name(),
        e.code
    ))
}
