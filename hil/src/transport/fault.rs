//! Fault injection: a wrapper that damages the bytes crossing a link, in both directions, at
//! given rates, reproducibly (a seeded counter-based generator), and counts what it did.

use std::str::FromStr;
use std::time::Duration;

use super::Transport;
use crate::{HilError, Result};

/// What to damage, as probabilities per byte (per chunk for `delay`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FaultSpec {
    /// A byte is lost.
    pub drop: f64,
    /// A byte has one random bit flipped.
    pub flip: f64,
    /// A random byte is inserted before this one.
    pub insert: f64,
    /// A burst of 8-64 random bytes is inserted before this one.
    pub garbage: f64,
    /// A chunk is held back this long before it goes on (with probability `delay_rate`).
    pub delay: Duration,
    /// Probability that a chunk is delayed.
    pub delay_rate: f64,
}

impl FaultSpec {
    /// Whether it does nothing.
    pub fn is_clean(&self) -> bool {
        self.drop == 0.0
            && self.flip == 0.0
            && self.insert == 0.0
            && self.garbage == 0.0
            && (self.delay.is_zero() || self.delay_rate == 0.0)
    }
}

impl FromStr for FaultSpec {
    type Err = HilError;

    /// `drop=R,flip=R,insert=R,garbage=R,delay=MS@R` (any subset; rates in [0, 1]).
    fn from_str(s: &str) -> Result<Self> {
        let mut spec = FaultSpec::default();
        let bad = |problem: String| HilError::FaultSpec {
            spec: s.to_string(),
            problem,
        };
        let rate = |k: &str, v: &str| -> Result<f64> {
            match v.parse::<f64>() {
                Ok(r) if (0.0..=1.0).contains(&r) => Ok(r),
                _ => Err(bad(format!("`{k}` must be a rate in [0, 1], not `{v}`"))),
            }
        };
        for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let (k, v) = part
                .split_once('=')
                .ok_or_else(|| bad(format!("`{part}` is not key=value")))?;
            match k {
                "drop" => spec.drop = rate(k, v)?,
                "flip" => spec.flip = rate(k, v)?,
                "insert" => spec.insert = rate(k, v)?,
                "garbage" => spec.garbage = rate(k, v)?,
                "delay" => {
                    let (ms, r) = v.split_once('@').ok_or_else(|| {
                        bad(format!("`delay` is MS@RATE (e.g. delay=5@0.01), not `{v}`"))
                    })?;
                    let ms: u64 = ms
                        .parse()
                        .map_err(|_| bad(format!("`{ms}` is not a number of milliseconds")))?;
                    spec.delay = Duration::from_millis(ms);
                    spec.delay_rate = rate(k, r)?;
                }
                _ => {
                    return Err(bad(format!(
                        "unknown fault `{k}` (known: drop, flip, insert, garbage, delay)"
                    )));
                }
            }
        }
        Ok(spec)
    }
}

/// What a [`Faulty`] link did, both directions together.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct FaultCounts {
    /// Bytes that went through the wrapper.
    pub bytes: u64,
    /// Bytes dropped.
    pub dropped: u64,
    /// Bytes with a bit flipped.
    pub flipped: u64,
    /// Single random bytes inserted.
    pub inserted: u64,
    /// Garbage bursts inserted.
    pub bursts: u64,
    /// Chunks delayed.
    pub delayed: u64,
}

/// A link that damages bytes both ways per its [`FaultSpec`].
#[derive(Debug)]
pub struct Faulty<T> {
    inner: T,
    spec: FaultSpec,
    rng: u64,
    counts: FaultCounts,
    /// Received bytes, damaged, waiting to be handed out.
    pending: Vec<u8>,
}

impl<T: Transport> Faulty<T> {
    /// Wraps `inner`; `seed` makes the damage reproducible.
    pub fn new(inner: T, spec: FaultSpec, seed: u64) -> Self {
        Faulty {
            inner,
            spec,
            rng: seed ^ 0x9e37_79b9_7f4a_7c15,
            counts: FaultCounts::default(),
            pending: Vec::new(),
        }
    }

    /// What it did so far.
    pub fn counts(&self) -> FaultCounts {
        self.counts
    }

    /// SplitMix64.
    fn next(&mut self) -> u64 {
        self.rng = self.rng.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.rng;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn chance(&mut self, p: f64) -> bool {
        p > 0.0 && (self.next() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }

    /// `bytes` as they come out of the damaged link.
    fn damage(&mut self, bytes: &[u8]) -> Vec<u8> {
        if self.spec.delay_rate > 0.0 && self.chance(self.spec.delay_rate) {
            self.counts.delayed += 1;
            std::thread::sleep(self.spec.delay);
        }
        let mut out = Vec::with_capacity(bytes.len() + 8);
        for &b in bytes {
            self.counts.bytes += 1;
            if self.chance(self.spec.garbage) {
                self.counts.bursts += 1;
                let len = 8 + self.next() % 57;
                for _ in 0..len {
                    out.push(self.next() as u8);
                }
            }
            if self.chance(self.spec.insert) {
                self.counts.inserted += 1;
                out.push(self.next() as u8);
            }
            if self.chance(self.spec.drop) {
                self.counts.dropped += 1;
                continue;
            }
            if self.chance(self.spec.flip) {
                self.counts.flipped += 1;
                out.push(b ^ (1 << (self.next() % 8)));
            } else {
                out.push(b);
            }
        }
        out
    }
}

impl<T: Transport> Transport for Faulty<T> {
    fn send(&mut self, bytes: &[u8]) -> Result<()> {
        let damaged = self.damage(bytes);
        self.inner.send(&damaged)
    }

    fn recv(&mut self, buf: &mut [u8], timeout: Duration) -> Result<usize> {
        if self.pending.is_empty() {
            let mut raw = vec![0u8; buf.len().max(1)];
            let n = self.inner.recv(&mut raw, timeout)?;
            self.pending = self.damage(&raw[..n]);
        }
        let n = buf.len().min(self.pending.len());
        buf[..n].copy_from_slice(&self.pending[..n]);
        self.pending.drain(..n);
        Ok(n)
    }

    fn name(&self) -> String {
        if self.spec.is_clean() {
            self.inner.name()
        } else {
            format!("{} (with faults)", self.inner.name())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transport::memory_pair;

    #[test]
    fn specs_parse_and_bad_ones_say_what_is_wrong() {
        let s: FaultSpec = "drop=0.01, flip=0.02,insert=0.5,garbage=0.001,delay=5@0.1"
            .parse()
            .unwrap();
        assert_eq!(s.drop, 0.01);
        assert_eq!(s.flip, 0.02);
        assert_eq!(s.insert, 0.5);
        assert_eq!(s.garbage, 0.001);
        assert_eq!(s.delay, Duration::from_millis(5));
        assert_eq!(s.delay_rate, 0.1);
        assert!("".parse::<FaultSpec>().unwrap().is_clean());
        for (bad, says) in [
            ("drop=2", "rate in [0, 1]"),
            ("flop=0.1", "unknown fault `flop`"),
            ("drop", "not key=value"),
            ("delay=5", "MS@RATE"),
        ] {
            let e = bad.parse::<FaultSpec>().unwrap_err().to_string();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn damage_follows_the_rates_reproducibly() {
        let spec: FaultSpec = "drop=0.01,flip=0.01,insert=0.01".parse().unwrap();
        let run = || {
            let (a, mut b) = memory_pair();
            let mut a = Faulty::new(a, spec, 7);
            let data: Vec<u8> = (0..100_000u32).map(|i| i as u8).collect();
            for chunk in data.chunks(1000) {
                a.send(chunk).unwrap();
            }
            let mut got = Vec::new();
            let mut buf = [0u8; 4096];
            loop {
                let n = b.recv(&mut buf, Duration::from_millis(20)).unwrap();
                if n == 0 {
                    break;
                }
                got.extend_from_slice(&buf[..n]);
            }
            (a.counts(), got)
        };
        let (c, got) = run();
        assert_eq!(run(), (c, got.clone()));
        assert_eq!(c.bytes, 100_000);
        for n in [c.dropped, c.flipped, c.inserted] {
            assert!((800..1200).contains(&n), "{c:?}");
        }
        assert_eq!(got.len() as u64, 100_000 - c.dropped + c.inserted);
    }

    #[test]
    fn a_clean_spec_changes_nothing() {
        let (a, mut b) = memory_pair();
        let mut a = Faulty::new(a, FaultSpec::default(), 1);
        a.send(b"intact").unwrap();
        let mut buf = [0u8; 16];
        let n = b.recv(&mut buf, Duration::from_millis(100)).unwrap();
        assert_eq!(&buf[..n], b"intact");
        assert_eq!(a.counts().bytes, 6);
    }
}
