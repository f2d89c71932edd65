//! The machine on a fake clock against a simulated line and device: no transport, no threads.

use std::collections::BTreeMap;

use swarm_core::wire::{Configure, Configured, kind};

use super::*;

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

fn us(n: u64) -> Duration {
    Duration::from_micros(n)
}

/// What the line does with one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Fate {
    Deliver,
    Drop,
    /// Delivered twice.
    Duplicate,
    /// Delivered this much later.
    Delay(Duration),
    /// One byte flipped (the receiver drops it for its CRC or COBS).
    Corrupt,
}

/// Decides a frame's fate from its kind, its seq and how many times that (kind, seq) crossed
/// this way before.
type Script = Box<dyn FnMut(u8, u16, u32) -> Fate>;

/// Rewrites the device's answer (request kind, seq, reply frame).
type Tamper = Box<dyn FnMut(u8, u16, Vec<u8>) -> Vec<u8>>;

/// A line with a fixed one-way delay and a device that answers `Configure` with `Configured`
/// (same session: the answer says which request it is) and `Ping` with `Pong`, one frame after
/// the other, each taking `service`.
struct World {
    m: Machine,
    now: Duration,
    one_way: Duration,
    service: Duration,
    dev_rx: Accumulator<512>,
    to_device: Vec<(Duration, Vec<u8>)>,
    to_host: Vec<(Duration, Vec<u8>)>,
    device_free: Duration,
    up: Script,
    down: Script,
    seen_up: BTreeMap<(u8, u16), u32>,
    seen_down: BTreeMap<(u8, u16), u32>,
    answers: BTreeMap<JobId, Answer>,
    /// Send times of every transmission of each request seq.
    sends: BTreeMap<u16, Vec<Duration>>,
    /// The largest number of requests in flight seen after a poll.
    max_flight: usize,
    /// Frames the device received intact.
    device_frames: u64,
    /// A hook that rewrites the device's answer to a request (kind, seq, reply frame).
    tamper: Option<Tamper>,
    /// A hook that makes the device take this long instead of `service` for a request (kind,
    /// seq).
    slow: Option<Slow>,
}

/// Service time of a request (kind, seq) that differs from the world's.
type Slow = Box<dyn FnMut(u8, u16) -> Option<Duration>>;

fn deliver() -> Script {
    Box::new(|_, _, _| Fate::Deliver)
}

/// A script that gives the frames `picked(kind, seq, nth transmission)` chooses `fate` and
/// delivers the others.
fn only(picked: impl Fn(u8, u16, u32) -> bool + 'static, fate: Fate) -> Script {
    Box::new(move |k, s, n| if picked(k, s, n) { fate } else { Fate::Deliver })
}

impl World {
    fn new(opts: ClientOptions, one_way: Duration, service: Duration) -> Self {
        World {
            m: Machine::new(opts),
            now: Duration::ZERO,
            one_way,
            service,
            dev_rx: Accumulator::new(),
            to_device: Vec::new(),
            to_host: Vec::new(),
            device_free: Duration::ZERO,
            up: deliver(),
            down: deliver(),
            seen_up: BTreeMap::new(),
            seen_down: BTreeMap::new(),
            answers: BTreeMap::new(),
            sends: BTreeMap::new(),
            max_flight: 0,
            device_frames: 0,
            tamper: None,
            slow: None,
        }
    }

    /// Submits `n` `Configure` requests with sessions `0..n`.
    fn submit(&mut self, n: u32) -> Vec<JobId> {
        (0..n)
            .map(|i| {
                let q = Configure {
                    session: i,
                    params_hash: 0,
                    reset_stats: false,
                };
                let payload = postcard::to_allocvec(&q).unwrap();
                self.m
                    .submit(Configure::KIND, payload, Expect::reply::<Configured>())
            })
            .collect()
    }

    /// Runs until the machine is idle or fails, or `limit` of fake time passed.
    fn run(&mut self, limit: Duration) -> Result<()> {
        let end = self.now + limit;
        loop {
            self.m.poll(self.now)?;
            self.max_flight = self.max_flight.max(self.m.flight.len());
            while let Some(frame) = self.m.transmit() {
                self.up(frame);
            }
            while let Some(c) = self.m.completion() {
                assert!(
                    self.answers.insert(c.job, c.answer).is_none(),
                    "answered twice"
                );
            }
            if self.m.is_idle() {
                return Ok(());
            }
            let next = [
                self.m.poll_at(),
                self.to_device.iter().map(|f| f.0).min(),
                self.to_host.iter().map(|f| f.0).min(),
            ]
            .into_iter()
            .flatten()
            .min()
            .expect("something is waiting");
            self.now = self.now.max(next);
            assert!(self.now <= end, "still busy after {limit:?}");
            self.deliver_to_device();
            self.deliver_to_host();
        }
    }

    fn header(frame: &[u8]) -> (u8, u16) {
        let mut f = frame.to_vec();
        let start = f.iter().position(|&b| b != 0).unwrap_or(0);
        let end = f.len() - 1;
        let frame = wire::decode_frame(&mut f[start..end]).unwrap();
        (frame.header.kind, frame.header.seq)
    }

    fn up(&mut self, frame: Vec<u8>) {
        let (k, s) = Self::header(&frame);
        if k == kind::CONFIGURE {
            self.sends.entry(s).or_default().push(self.now);
        }
        let n = self.seen_up.entry((k, s)).or_default();
        let fate = (self.up)(k, s, *n);
        *n += 1;
        let at = self.now + self.one_way;
        push(&mut self.to_device, at, frame, fate);
    }

    fn deliver_to_device(&mut self) {
        let (due, rest) = self
            .to_device
            .drain(..)
            .partition(|(at, _)| *at <= self.now);
        self.to_device = rest;
        let mut due: Vec<(Duration, Vec<u8>)> = due;
        due.sort_by_key(|f| f.0);
        for (at, bytes) in due {
            let mut replies = Vec::new();
            let mut input = &bytes[..];
            while let Some((event, rest)) = self.dev_rx.feed(input) {
                input = rest;
                let Event::Frame(frame) = event else { continue };
                let (k, s) = (frame.header.kind, frame.header.seq);
                let mut out = [0u8; 128];
                let n = match k {
                    kind::CONFIGURE => {
                        let q: Configure = frame.message().unwrap();
                        let r = Configured { session: q.session };
                        wire::encode_message(s, &r, &mut out).unwrap()
                    }
                    kind::PING => {
                        let q: Ping = frame.message().unwrap();
                        wire::encode_message(s, &Pong { nonce: q.nonce }, &mut out).unwrap()
                    }
                    _ => panic!("unexpected kind {k:#04x}"),
                };
                replies.push((k, s, out[..n].to_vec()));
            }
            for (k, s, mut reply) in replies {
                self.device_frames += 1;
                if let Some(t) = self.tamper.as_mut() {
                    reply = t(k, s, reply);
                }
                let service = self.slow.as_mut().and_then(|f| f(k, s));
                let done = at.max(self.device_free) + service.unwrap_or(self.service);
                self.device_free = done;
                let (rk, rs) = Self::header(&reply);
                let n = self.seen_down.entry((rk, rs)).or_default();
                let fate = (self.down)(rk, rs, *n);
                *n += 1;
                push(&mut self.to_host, done + self.one_way, reply, fate);
            }
        }
    }

    fn deliver_to_host(&mut self) {
        let (due, rest) = self.to_host.drain(..).partition(|(at, _)| *at <= self.now);
        self.to_host = rest;
        let mut due: Vec<(Duration, Vec<u8>)> = due;
        due.sort_by_key(|f| f.0);
        for (_, bytes) in due {
            self.m.on_bytes(self.now, &bytes);
        }
    }

    /// Lets every frame still on the line arrive (after the machine went idle).
    fn flush(&mut self) {
        while let Some(at) = self
            .to_device
            .iter()
            .chain(&self.to_host)
            .map(|f| f.0)
            .min()
        {
            self.now = self.now.max(at);
            self.deliver_to_device();
            self.deliver_to_host();
        }
    }

    /// Submits `n` requests, runs until the machine is idle (at most `limit`) and checks that
    /// every one got its own answer.
    fn serve_all(&mut self, n: u32, limit: Duration) {
        let jobs = self.submit(n);
        self.run(limit).unwrap();
        self.assert_all_right(&jobs);
    }

    /// Every job answered with the `Configured` of its own request.
    fn assert_all_right(&self, jobs: &[JobId]) {
        assert_eq!(self.answers.len(), jobs.len());
        for (i, j) in jobs.iter().enumerate() {
            let Some(Answer::Reply(p)) = self.answers.get(j) else {
                panic!("job {j:?}: {:?}", self.answers.get(j));
            };
            let c: Configured = decode_payload(p).unwrap();
            assert_eq!(
                c.session, i as u32,
                "job {j:?} got another request's answer"
            );
        }
    }
}

fn push(q: &mut Vec<(Duration, Vec<u8>)>, at: Duration, mut frame: Vec<u8>, fate: Fate) {
    match fate {
        Fate::Deliver => q.push((at, frame)),
        Fate::Drop => {}
        Fate::Duplicate => {
            q.push((at, frame.clone()));
            q.push((at, frame));
        }
        Fate::Delay(d) => q.push((at + d, frame)),
        Fate::Corrupt => {
            let i = frame.len() / 2;
            frame[i] ^= 0x10;
            q.push((at, frame));
        }
    }
}

/// A pseudo-terminal: ~20 µs each way, ~10 µs of device time.
fn pty() -> World {
    pty_with(ClientOptions::default())
}

/// A pseudo-terminal ([`pty`]) with the client options `opts`.
fn pty_with(opts: ClientOptions) -> World {
    World::new(opts, us(20), us(10))
}

#[test]
fn a_clean_line_needs_no_retry_and_one_probe_per_batch() {
    let mut w = pty();
    w.serve_all(100, ms(100));
    let r = w.m.report();
    assert_eq!((r.retries, r.timeouts, r.stale_replies), (0, 0, 0), "{r:?}");
    assert_eq!(r.probes, 1, "the tail probe");
    assert_eq!(w.max_flight, 8, "the window");
    assert!(r.srtt_us > 0 && (2_000..2_200).contains(&r.rto_us), "{r:?}");
}

#[test]
fn a_lost_request_is_sent_again_when_the_next_answer_overtakes_it() {
    let mut w = pty();
    w.up = only(
        |k, s, n| k == kind::CONFIGURE && s == 3 && n == 0,
        Fate::Drop,
    );
    w.serve_all(20, ms(100));
    let r = w.m.report();
    assert_eq!((r.retries, r.timeouts), (1, 0), "{r:?}");
    let resent = w.sends[&3][1] - w.sends[&3][0];
    assert!(resent < us(200), "at the pace of a round trip: {resent:?}");
}

#[test]
fn a_lost_reply_is_asked_again_and_the_last_of_a_batch_is_caught_by_the_probe() {
    let mut w = pty();
    // Seq 3's reply and the last request's reply, lost once each.
    w.down = only(
        |k, s, n| k == kind::CONFIGURED && (s == 3 || s == 10) && n == 0,
        Fate::Drop,
    );
    w.serve_all(10, ms(100));
    let r = w.m.report();
    assert_eq!((r.retries, r.timeouts), (2, 0), "{r:?}");
    assert!(r.probes >= 2, "{r:?}");
    assert!(w.now < ms(1), "no timer waited out: {:?}", w.now);
}

#[test]
fn duplicated_replies_are_discarded() {
    let mut w = pty();
    w.down = Box::new(|_, _, _| Fate::Duplicate);
    w.serve_all(30, ms(100));
    w.flush();
    let r = w.m.report();
    assert_eq!(r.retries, 0, "{r:?}");
    assert_eq!(
        r.stale_replies, 31,
        "every reply and the probe's, once: {r:?}"
    );
}

#[test]
fn a_reordered_reply_still_answers_its_own_request() {
    let mut w = pty();
    // Seq 3's reply comes 1 ms late, after 4's: 3 is sent again, the retry's reply answers it
    // (Karn: no round trip sampled) and the late one is stale; so is the answer to the tail
    // probe, which the probe after the retry replaced.
    w.down = only(
        |k, s, n| k == kind::CONFIGURED && s == 3 && n == 0,
        Fate::Delay(ms(1)),
    );
    w.serve_all(10, ms(100));
    w.flush();
    let r = w.m.report();
    assert_eq!((r.retries, r.stale_replies, r.probes), (1, 2, 2), "{r:?}");
}

#[test]
fn timeouts_back_off_exponentially_until_the_line_answers_again() {
    let mut w = pty_with(ClientOptions {
        dead_after: ms(20_000),
        ..ClientOptions::default()
    });
    // One request; nothing comes back for its first five sends, probes included.
    w.down = only(|k, _, _| k != kind::CONFIGURED, Fate::Drop);
    w.up = {
        let mut n_up = 0;
        Box::new(move |k, _, _| {
            if k != kind::CONFIGURE {
                return Fate::Drop;
            }
            n_up += 1;
            if n_up <= 5 { Fate::Drop } else { Fate::Deliver }
        })
    };
    w.serve_all(1, ms(10_000));
    let sends = &w.sends[&1];
    assert_eq!(sends.len(), 6);
    let gaps: Vec<Duration> = sends.windows(2).map(|p| p[1] - p[0]).collect();
    // No round trip measured yet: 200 ms, then doubled at each expiry.
    assert_eq!(
        gaps,
        [ms(200), ms(400), ms(800), ms(1600), ms(2000)],
        "capped at 2 s"
    );
    let r = w.m.report();
    assert_eq!((r.timeouts, r.retries), (5, 5), "{r:?}");
    // Karn: the answer to a retried request measures nothing, so the backoff stays.
    assert_eq!(w.m.rto.backoff(), 5);
    assert_eq!(r.srtt_us, 0);
}

#[test]
fn a_dead_link_is_declared_after_dead_after_and_the_machine_recovers() {
    let mut w = pty_with(ClientOptions {
        dead_after: ms(3000),
        ..ClientOptions::default()
    });
    w.down = Box::new(|_, _, _| Fate::Drop);
    w.submit(16);
    let err = w.run(ms(10_000)).unwrap_err();
    let HilError::LinkDead {
        waiting_for,
        unanswered,
        silent,
    } = err
    else {
        panic!("{err}");
    };
    assert_eq!((waiting_for, unanswered), ("Configure", 16));
    assert!(silent >= ms(3000) && silent < ms(3100), "{silent:?}");
    assert!(w.m.report().timeouts >= 8);
    // After abort the machine serves a new batch on a repaired line.
    w.m.abort();
    w.to_host.clear();
    w.down = deliver();
    let jobs = w.submit(4);
    w.answers.clear();
    w.run(ms(10_000)).unwrap();
    w.assert_all_right(&jobs);
}

#[test]
fn the_window_bounds_what_is_in_flight() {
    for window in [1, 3, 8, 32] {
        let opts = ClientOptions {
            window,
            ..ClientOptions::default()
        };
        let mut w = World::new(opts, us(50), us(10));
        w.serve_all(100, ms(1000));
        assert_eq!(w.max_flight, window, "window {window}");
        assert_eq!(w.m.report().retries, 0);
    }
    // A window of 0 is taken as 1.
    let mut w = World::new(
        ClientOptions {
            window: 0,
            ..ClientOptions::default()
        },
        us(50),
        us(10),
    );
    w.serve_all(5, ms(1000));
    assert_eq!(w.max_flight, 1);
}

#[test]
fn the_window_is_cut_to_what_the_device_buffers_unless_the_line_has_flow_control() {
    // (host window, device window, flow control) → window used
    for (window, device, flow_control, used) in [
        (8, 1, false, 1),
        (8, 3, false, 3),
        (8, 100, false, 8),
        (8, 0, false, 1),
        (8, 1, true, 8),
        (2, 5, true, 2),
    ] {
        let opts = ClientOptions {
            window,
            flow_control,
            ..ClientOptions::default()
        };
        let mut w = World::new(opts, us(50), us(10));
        w.m.fit_window(device);
        assert_eq!(w.m.window(), used, "{window} {device} {flow_control}");
        w.serve_all(40, ms(1000));
        assert_eq!(w.max_flight, used, "{window} {device} {flow_control}");
        assert_eq!(w.m.report().window, used as u64);
    }
}

#[test]
fn a_slow_device_with_a_94_ms_round_trip_is_never_asked_twice() {
    // bee-node in QEMU: about 94 ms per request, 8 in flight, so the last of a window waits
    // 8 × 94 ms for its answer. Timers start at the previous answer and the timeout follows
    // the measured round trip: no retry at all.
    let mut w = World::new(ClientOptions::default(), ms(2), ms(90));
    w.serve_all(200, ms(60_000));
    let r = w.m.report();
    assert_eq!((r.retries, r.timeouts), (0, 0), "{r:?}");
    assert!((85_000..100_000).contains(&r.srtt_us), "{r:?}");
    assert_eq!(
        w.device_frames, 201,
        "every request once, and the tail probe"
    );
}

#[test]
fn a_slow_answer_costs_a_retry_or_two_not_the_windows() {
    // A device that takes ten times as long over every tenth request (a QEMU guest
    // descheduled on a busy host): the answer outlives the timeout. Only the oldest request
    // runs a timer (the seven behind it wait for it), so each slow answer costs a retry or
    // two (the next request's timer, backed off, may run out before the slow answer comes),
    // not the window's eight.
    let mut w = World::new(ClientOptions::default(), us(20), ms(1));
    let mut served = std::collections::BTreeSet::new();
    w.slow = Some(Box::new(move |k, s| {
        (k == kind::CONFIGURE && s % 10 == 0 && served.insert(s)).then_some(ms(10))
    }));
    w.serve_all(200, ms(60_000));
    let r = w.m.report();
    assert!(
        r.timeouts >= 20,
        "the slow answers outlive the timeout: {r:?}"
    );
    assert!(
        r.retries <= 40,
        "two retries per slow answer at most: {r:?}"
    );
}

#[test]
fn a_crc_valid_answer_that_does_not_decode_is_asked_again() {
    let mut w = pty();
    // The device's first answer to seq 2 comes as a `Pong`, and its first
    // answer to seq 4 as a `Configured` whose payload has a byte too many: both pass the CRC.
    w.tamper = Some(Box::new({
        let mut done = std::collections::BTreeSet::new();
        move |k, s, reply| {
            if k != kind::CONFIGURE || !(s == 2 || s == 4) || !done.insert(s) {
                return reply;
            }
            let mut out = [0u8; 128];
            let len = if s == 2 {
                wire::encode_message(s, &Pong { nonce: 1 }, &mut out).unwrap()
            } else {
                wire::encode_frame(kind::CONFIGURED, s, &(7u8, 9u8), &mut out).unwrap()
            };
            out[..len].to_vec()
        }
    }));
    w.serve_all(6, ms(100));
    let r = w.m.report();
    assert_eq!((r.undecodable, r.retries), (2, 2), "{r:?}");
}

#[test]
fn a_request_that_never_gets_through_is_given_up() {
    let mut w = pty_with(ClientOptions {
        retries: 50,
        ..ClientOptions::default()
    });
    // Seq 2 never reaches the device; everything else does (the probes show the line lives).
    w.up = only(|k, s, _| k == kind::CONFIGURE && s == 2, Fate::Corrupt);
    w.submit(5);
    let err = w.run(ms(10_000)).unwrap_err();
    assert!(
        matches!(
            err,
            HilError::GaveUp {
                request: "Configure",
                seq: 2,
                sends: 51
            }
        ),
        "{err}"
    );
    assert!(w.now < ms(50), "at the pace of probes: {:?}", w.now);
}

/// A generator of `true` one time in three (xorshift).
fn third(mut x: u64) -> impl FnMut() -> bool {
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x.is_multiple_of(3)
    }
}

#[test]
fn a_noisy_line_is_repaired_at_the_pace_of_round_trips() {
    // A third of the frames each way damaged: every request answered, right, and no timer
    // ever at its ceiling.
    let mut w = pty();
    let (mut rand, mut rand2) = (third(0x2545_f491_4f6c_dd1d), third(0x9e37_79b9_7f4a_7c15));
    w.up = Box::new(move |_, _, _| if rand() { Fate::Corrupt } else { Fate::Deliver });
    w.down = Box::new(move |_, _, _| if rand2() { Fate::Drop } else { Fate::Deliver });
    w.serve_all(500, ms(60_000));
    let r = w.m.report();
    assert!(r.retries > 300, "{r:?}");
    assert!(w.now < ms(2000), "took {:?}: {r:?}", w.now);
}

#[test]
fn sequence_numbers_wrap_and_skip_what_is_in_flight() {
    // More requests than sequence numbers: the counter wraps and every answer still finds
    // its own request.
    let mut w = World::new(ClientOptions::default(), us(1), us(1));
    let jobs = w.submit(70_000);
    w.run(ms(60_000)).unwrap();
    assert_eq!(w.answers.len(), jobs.len());
    for (i, j) in jobs.iter().enumerate() {
        let Some(Answer::Reply(p)) = w.answers.get(j) else {
            panic!()
        };
        let c: Configured = decode_payload(p).unwrap();
        assert_eq!(c.session, i as u32);
    }
    let mut m = Machine::new(ClientOptions::default());
    m.next_seq = 7;
    m.probe = Some(Probe {
        seq: 7,
        sent: Duration::ZERO,
        order: 0,
    });
    assert_eq!(m.fresh_seq(), 8, "the probe's seq is busy");
    m.next_seq = u16::MAX;
    assert_eq!((m.fresh_seq(), m.fresh_seq()), (u16::MAX, 0));
}
