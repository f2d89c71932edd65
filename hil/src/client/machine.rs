//! The host end of the request pipeline as a pure state machine: no transport, no clock.
//!
//! The driver (here [`Client`](super::Client)) submits requests, feeds every received byte to
//! [`Machine::on_bytes`], calls [`Machine::poll`] when something arrived or the time given by
//! [`Machine::poll_at`] has come, sends what [`Machine::transmit`] hands out and collects what
//! [`Machine::completion`] hands out. Time is a [`Duration`] since any epoch the driver picks,
//! passed in with each call, so the tests run on a fake clock.
//!
//! The machine owns the window, the sequence numbers, the retransmissions, the retransmission
//! timeout (adaptive, [`Rto`]) and the link probes (`docs/protocol.md` §10.6):
//!
//! * at most [`ClientOptions::window`] requests are in flight;
//! * a device answers in order, so an answer to a request or probe marks every request sent
//!   before it and still unanswered as lost: it is sent again at once (same `seq`, same bytes,
//!   after a lone `0x00` that ends any damaged partial frame on the device);
//! * a request that is the newest thing in flight while nothing new can follow it (the end of a
//!   batch, or a retransmission) is followed by a small [`Ping`] probe whose answer shows its
//!   fate one round trip later: on a noisy line that is alive, losses are repaired at the pace
//!   of round trips, not timeouts;
//! * otherwise a request is sent again when its timer runs out. One timer runs, the oldest
//!   transmission's (request or probe) still waiting: those behind it wait for it, since the
//!   device answers in order. It starts when that was sent, when the last answer came or when
//!   the last timer ran out, whichever is latest, and lasts the retransmission timeout, which
//!   doubles on every expiry until an unambiguous round trip is measured again (Karn's rule:
//!   never from a request sent more than once). A slow answer thus costs one retransmission,
//!   not the window's;
//! * an answer to a request sent more than once may be any send's: it marks lost only what
//!   was sent before the first send;
//! * a CRC-valid answer that is not a valid answer (wrong kind, payload that does not decode)
//!   is damage that passed the CRC: counted, and the request is sent again at once;
//! * the link is declared dead when nothing intact came for [`ClientOptions::dead_after`]
//!   while requests were waiting, and a request is given up after [`ClientOptions::retries`]
//!   retransmissions.

use std::collections::VecDeque;
use std::time::Duration;

use swarm_core::wire::{
    self, Accumulator, ErrorReply, Event, Message, Ping, Pong, decode_payload, max_frame_len,
};

use super::rto::{Rto, RtoOptions};
use crate::{HilError, Result};

/// The receive buffer: longer than any reply of the protocol.
const RX: usize = 2048;

/// The largest window: half the sequence space, so a fresh `seq` always exists.
const MAX_WINDOW: usize = 1 << 15;

/// How the client paces and retries requests.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClientOptions {
    /// The most requests in flight at once (at least 1). After the handshake the window is
    /// cut to what the device's receive buffer holds ([`Machine::fit_window`]), unless the
    /// line has `flow_control`.
    pub window: usize,
    /// The line holds the sender back while the device's receiver is full (hardware
    /// handshaking, or QEMU's emulated UARTs, which take a byte only when they have room):
    /// then the device's reported receive buffer does not bound the window.
    pub flow_control: bool,
    /// The retransmission timeout's initial value, floor and ceiling.
    pub rto: RtoOptions,
    /// Times a request is sent again before the run fails.
    pub retries: u32,
    /// The link is dead when nothing intact came back for this long.
    pub dead_after: Duration,
}

impl Default for ClientOptions {
    fn default() -> Self {
        ClientOptions {
            window: 8,
            flow_control: false,
            rto: RtoOptions::default(),
            retries: 10_000,
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
    /// Requests whose timer ran out (lost requests detected earlier, by a later answer
    /// overtaking them, are counted in `retries` only).
    pub timeouts: u64,
    /// Requests sent again.
    pub retries: u64,
    /// Answers that came for no request in flight (late answers to a retried request).
    pub stale_replies: u64,
    /// [`Ping`] probes sent (after a batch's last request and after retransmissions).
    pub probes: u64,
    /// CRC-valid answers that were not a valid answer to their request (wrong kind, payload
    /// that does not decode): damage that passed the CRC; the request was sent again.
    pub undecodable: u64,
    /// The smoothed round trip at the end, in microseconds (0 before any was measured).
    pub srtt_us: u64,
    /// The retransmission timeout at the end, in microseconds.
    pub rto_us: u64,
    /// The window used: requests in flight at most.
    pub window: u64,
}

/// A submitted request's handle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct JobId(pub u64);

/// What a good answer to a request is: a frame of kind `kind` whose payload `decodes`, or an
/// [`ErrorReply`].
#[derive(Clone, Copy, Debug)]
pub struct Expect {
    /// The reply's kind.
    pub kind: u8,
    /// Whether a payload is exactly one reply of that kind.
    pub decodes: fn(&[u8]) -> bool,
}

impl Expect {
    /// A reply of type `A`.
    pub fn reply<A: Message>() -> Self {
        Expect {
            kind: A::KIND,
            decodes: decodes::<A>,
        }
    }
}

fn decodes<A: Message>(payload: &[u8]) -> bool {
    decode_payload::<A>(payload).is_ok()
}

/// The answer to a request.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Answer {
    /// The reply's payload (already checked to decode as the expected reply).
    Reply(Vec<u8>),
    /// The device refused the request.
    Error(ErrorReply),
}

/// A request answered.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Completion {
    /// Which.
    pub job: JobId,
    /// Its answer.
    pub answer: Answer,
}

/// A request waiting for its first send.
struct Job {
    id: JobId,
    kind: u8,
    payload: Vec<u8>,
    expect: Expect,
}

/// A request in flight.
struct InFlight {
    id: JobId,
    kind: u8,
    expect: Expect,
    seq: u16,
    /// The frame, delimiter included.
    frame: Vec<u8>,
    first_sent: Duration,
    sent: Duration,
    /// Transmission number of the last send: what "sent before" compares.
    order: u64,
    /// Transmission number of the first send.
    first_order: u64,
    /// Times sent again.
    tries: u32,
    /// Known lost: send again at the next poll.
    lost: bool,
}

/// The probe in flight.
#[derive(Clone, Copy)]
struct Probe {
    seq: u16,
    sent: Duration,
    order: u64,
}

/// The request pipeline of one link (see the module documentation).
pub struct Machine {
    opts: ClientOptions,
    /// Requests in flight at most (see [`Machine::fit_window`]).
    window: usize,
    rx: Accumulator<RX>,
    rto: Rto,
    next_seq: u16,
    next_job: u64,
    /// Transmissions so far (the next one's `order`).
    sends: u64,
    queue: VecDeque<Job>,
    flight: Vec<InFlight>,
    probe: Option<Probe>,
    /// When an intact frame last came (or the link last became busy).
    heard: Duration,
    /// When the last answer to something in flight came: a pipelined request's timer starts
    /// no earlier.
    progress: Duration,
    /// When the last timer ran out: the next one starts no earlier.
    expired: Duration,
    outbox: VecDeque<Vec<u8>>,
    done: VecDeque<Completion>,
    report: LinkReport,
    latencies_us: Vec<u32>,
}

impl Machine {
    /// An idle machine.
    pub fn new(opts: ClientOptions) -> Self {
        Machine {
            opts,
            window: opts.window.clamp(1, MAX_WINDOW),
            rx: Accumulator::new(),
            rto: Rto::new(opts.rto),
            next_seq: 1,
            next_job: 0,
            sends: 0,
            queue: VecDeque::new(),
            flight: Vec::new(),
            probe: None,
            heard: Duration::ZERO,
            progress: Duration::ZERO,
            expired: Duration::ZERO,
            outbox: VecDeque::new(),
            done: VecDeque::new(),
            report: LinkReport::default(),
            latencies_us: Vec::new(),
        }
    }

    /// Queues a request of kind `kind` with postcard `payload`; sent by a later
    /// [`poll`](Self::poll) when the window has room.
    pub fn submit(&mut self, kind: u8, payload: Vec<u8>, expect: Expect) -> JobId {
        let id = JobId(self.next_job);
        self.next_job += 1;
        self.queue.push_back(Job {
            id,
            kind,
            payload,
            expect,
        });
        id
    }

    /// Whether nothing is queued or in flight.
    pub fn is_idle(&self) -> bool {
        self.queue.is_empty() && self.flight.is_empty()
    }

    /// Forgets every queued and in-flight request, the probe, what was to be sent and what was
    /// answered but not collected (after a failure). The counters, the round-trip estimate and
    /// the receiver stay.
    pub fn abort(&mut self) {
        self.queue.clear();
        self.flight.clear();
        self.probe = None;
        self.outbox.clear();
        self.done.clear();
    }

    /// The next frame to send, if any.
    pub fn transmit(&mut self) -> Option<Vec<u8>> {
        self.outbox.pop_front()
    }

    /// The next answered request, if any.
    pub fn completion(&mut self) -> Option<Completion> {
        self.done.pop_front()
    }

    /// The link's counters so far.
    pub fn report(&self) -> LinkReport {
        let mut r = self.report.clone();
        let s = self.rx.stats();
        r.crc_errors = s.crc_errors.into();
        r.resyncs = s.resyncs().into();
        r.srtt_us = self.rto.srtt().map_or(0, |d| micros(d).into());
        r.rto_us = micros(self.rto()).into();
        r.window = self.window as u64;
        r
    }

    /// Cuts the window to `device` requests, what the device can take in without loss
    /// ([`Identity::window`](swarm_core::wire::Identity::window) of its handshake), unless the
    /// line has [`ClientOptions::flow_control`]. Never above [`ClientOptions::window`], never
    /// below 1.
    pub fn fit_window(&mut self, device: usize) {
        let most = self.opts.window.clamp(1, MAX_WINDOW);
        self.window = if self.opts.flow_control {
            most
        } else {
            device.clamp(1, most)
        };
    }

    /// Requests in flight at most, now.
    pub fn window(&self) -> usize {
        self.window
    }

    /// Round-trip times of the answered requests (first send to answer), in microseconds.
    pub fn latencies_us(&self) -> &[u32] {
        &self.latencies_us
    }

    /// The current retransmission timeout: the estimator's, and never more than an eighth of
    /// [`ClientOptions::dead_after`], so a line that damages much but lives is tried at least
    /// eight times before it is declared dead.
    pub fn rto(&self) -> Duration {
        self.rto.timeout().min(self.opts.dead_after / 8)
    }

    /// Bytes received at `now`.
    pub fn on_bytes(&mut self, now: Duration, bytes: &[u8]) {
        self.report.bytes_rx += bytes.len() as u64;
        let mut input = bytes;
        while let Some((event, rest)) = self.rx.feed(input) {
            input = rest;
            let Event::Frame(frame) = event else {
                continue;
            };
            let (kind, seq) = (frame.header.kind, frame.header.seq);
            let payload = frame.payload.to_vec();
            self.on_frame(now, kind, seq, &payload);
        }
    }

    /// An intact frame.
    fn on_frame(&mut self, now: Duration, kind: u8, seq: u16, payload: &[u8]) {
        self.heard = now;
        if let Some(i) = self.flight.iter().position(|p| p.seq == seq) {
            let expect = self.flight[i].expect;
            let answer = if kind == expect.kind && (expect.decodes)(payload) {
                Some(Answer::Reply(payload.to_vec()))
            } else if kind == ErrorReply::KIND {
                decode_payload::<ErrorReply>(payload)
                    .ok()
                    .map(Answer::Error)
            } else {
                None
            };
            let Some(answer) = answer else {
                self.report.undecodable += 1;
                self.flight[i].lost = true;
                return;
            };
            let p = self.flight.remove(i);
            if p.tries == 0 {
                self.rto
                    .sample(now.saturating_sub(p.sent.max(self.progress)));
            }
            self.latencies_us
                .push(micros(now.saturating_sub(p.first_sent)));
            self.progress = now;
            // An answer after a retry may be the first send's (Karn): only what was sent
            // before that one is surely lost.
            self.lost_before(if p.tries == 0 { p.order } else { p.first_order });
            self.done.push_back(Completion { job: p.id, answer });
        } else if let Some(q) = self.probe.filter(|q| q.seq == seq) {
            self.probe = None;
            let pong = (kind == Pong::KIND)
                .then(|| decode_payload::<Pong>(payload).ok())
                .flatten();
            if pong.is_some_and(|p| p.nonce == u32::from(seq)) {
                self.rto
                    .sample(now.saturating_sub(q.sent.max(self.progress)));
                self.progress = now;
                self.lost_before(q.order);
            } else {
                self.report.undecodable += 1;
            }
        } else {
            self.report.stale_replies += 1;
        }
    }

    /// Marks what was sent before transmission `order` and is still unanswered as lost (a
    /// device answers in order).
    fn lost_before(&mut self, order: u64) {
        for p in self.flight.iter_mut().filter(|p| p.order < order) {
            p.lost = true;
        }
        if self.probe.is_some_and(|q| q.order < order) {
            self.probe = None;
        }
    }

    /// Advances to `now`: declares a silent link dead, runs the timers, queues the
    /// retransmissions, fills the window and sends a probe where one is due.
    ///
    /// # Errors
    ///
    /// [`HilError::LinkDead`], [`HilError::GaveUp`], [`HilError::Encode`]; the machine keeps
    /// its state (call [`abort`](Self::abort) to start afresh).
    pub fn poll(&mut self, now: Duration) -> Result<()> {
        if self.flight.is_empty() {
            // Idle until now: the silence starts with the first send.
            self.heard = now;
            self.progress = self.progress.max(now);
        } else if now.saturating_sub(self.heard) >= self.opts.dead_after {
            let oldest = self.flight.iter().min_by_key(|p| p.order);
            return Err(HilError::LinkDead {
                waiting_for: kind_name(oldest.map_or(0, |p| p.kind)),
                unanswered: self.flight.len() + self.queue.len(),
                silent: now.saturating_sub(self.heard),
            });
        }
        self.expire(now);
        self.retransmit(now)?;
        self.fill(now)?;
        self.probe_if_due(now)
    }

    /// The one timer (see the module documentation): the oldest transmission still waiting
    /// (`None`: the probe) and when its timer runs out.
    fn timer(&self) -> Option<(Option<usize>, Duration)> {
        let requests = self.flight.iter().enumerate().filter(|(_, p)| !p.lost);
        let (oldest, _, sent) = requests
            .map(|(i, p)| (Some(i), p.order, p.sent))
            .chain(self.probe.map(|q| (None, q.order, q.sent)))
            .min_by_key(|t| t.1)?;
        let start = sent.max(self.progress).max(self.expired);
        Some((oldest, start.saturating_add(self.rto())))
    }

    /// Runs the timer: the oldest request (or probe) waiting past it is taken as lost.
    fn expire(&mut self, now: Duration) {
        let Some((oldest, deadline)) = self.timer() else {
            return;
        };
        if now < deadline {
            return;
        }
        match oldest {
            Some(i) => {
                self.flight[i].lost = true;
                self.report.timeouts += 1;
            }
            None => self.probe = None,
        }
        self.expired = now;
        self.rto.back_off();
    }

    /// Sends the lost requests again, oldest first.
    fn retransmit(&mut self, now: Duration) -> Result<()> {
        let mut lost: Vec<usize> = (0..self.flight.len())
            .filter(|&i| self.flight[i].lost)
            .collect();
        lost.sort_by_key(|&i| self.flight[i].order);
        if !lost.is_empty() {
            // The probe that follows the retransmissions replaces one sent before them.
            self.probe = None;
        }
        for i in lost {
            let order = self.take_order();
            let p = &mut self.flight[i];
            if p.tries >= self.opts.retries {
                return Err(HilError::GaveUp {
                    request: kind_name(p.kind),
                    seq: p.seq,
                    sends: p.tries.saturating_add(1),
                });
            }
            p.tries += 1;
            p.sent = now;
            p.order = order;
            p.lost = false;
            // A leading delimiter ends whatever partial frame the device may hold (the
            // damaged rest of a lost one), so the retry starts on a clean frame; the device
            // counts an empty frame and ignores it.
            let mut frame = Vec::with_capacity(p.frame.len() + 1);
            frame.push(0);
            frame.extend_from_slice(&p.frame);
            self.report.retries += 1;
            self.send(frame);
        }
        Ok(())
    }

    /// Sends queued requests while the window has room.
    fn fill(&mut self, now: Duration) -> Result<()> {
        while self.flight.len() < self.window {
            let Some(job) = self.queue.pop_front() else {
                break;
            };
            let seq = self.fresh_seq();
            let mut frame = vec![0; max_frame_len(job.payload.len())];
            let n = wire::encode_frame(job.kind, seq, &RawPayload(&job.payload), &mut frame)
                .map_err(|source| HilError::Encode {
                    message: kind_name(job.kind),
                    source,
                })?;
            frame.truncate(n);
            let order = self.take_order();
            self.send(frame.clone());
            self.flight.push(InFlight {
                id: job.id,
                kind: job.kind,
                expect: job.expect,
                seq,
                frame,
                first_sent: now,
                sent: now,
                order,
                first_order: order,
                tries: 0,
                lost: false,
            });
        }
        Ok(())
    }

    /// A probe when the newest thing in flight is a request nothing new can follow: the last
    /// one of the batch, or a retransmission.
    fn probe_if_due(&mut self, now: Duration) -> Result<()> {
        if self.probe.is_some() {
            return Ok(());
        }
        let Some(newest) = self.flight.iter().max_by_key(|p| p.order) else {
            return Ok(());
        };
        if newest.tries == 0 && !self.queue.is_empty() {
            return Ok(());
        }
        let seq = self.fresh_seq();
        let mut frame = vec![0; max_frame_len(5)];
        let n = wire::encode_message(seq, &Ping { nonce: seq.into() }, &mut frame).map_err(
            |source| HilError::Encode {
                message: "Ping",
                source,
            },
        )?;
        frame.truncate(n);
        let order = self.take_order();
        self.probe = Some(Probe {
            seq,
            sent: now,
            order,
        });
        self.report.probes += 1;
        self.send(frame);
        Ok(())
    }

    /// When [`poll`](Self::poll) next has something to do (a timer, the silence limit), if
    /// anything is waiting; a time already past means now.
    pub fn poll_at(&self) -> Option<Duration> {
        if self.flight.is_empty() {
            return (!self.queue.is_empty()).then_some(Duration::ZERO);
        }
        if self.flight.iter().any(|p| p.lost) || !self.outbox.is_empty() {
            return Some(Duration::ZERO);
        }
        let silence = self.heard.saturating_add(self.opts.dead_after);
        Some(self.timer().map_or(silence, |(_, at)| at.min(silence)))
    }

    fn send(&mut self, frame: Vec<u8>) {
        self.report.bytes_tx += frame.len() as u64;
        self.outbox.push_back(frame);
    }

    fn take_order(&mut self) -> u64 {
        let o = self.sends;
        self.sends += 1;
        o
    }

    /// The next sequence number not in flight.
    fn fresh_seq(&mut self) -> u16 {
        loop {
            let s = self.next_seq;
            self.next_seq = self.next_seq.wrapping_add(1);
            let busy =
                self.flight.iter().any(|p| p.seq == s) || self.probe.is_some_and(|q| q.seq == s);
            if !busy {
                return s;
            }
        }
    }
}

/// A payload already in postcard bytes, written through unchanged (postcard writes a tuple of
/// `u8` byte for byte): what [`wire::encode_frame`] takes to frame a payload it already holds
/// encoded, as the machine does when it sends a request again.
#[derive(Clone, Copy, Debug)]
pub struct RawPayload<'a>(pub &'a [u8]);

impl serde::Serialize for RawPayload<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(self.0.len())?;
        for b in self.0 {
            t.serialize_element(b)?;
        }
        t.end()
    }
}

/// The name of a message kind, for errors and reports.
pub(crate) fn kind_name(kind: u8) -> &'static str {
    wire::kind::name(kind).unwrap_or("message")
}

fn micros(d: Duration) -> u32 {
    d.as_micros().min(u32::MAX.into()) as u32
}

#[cfg(test)]
mod tests;
