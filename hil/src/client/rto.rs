//! The retransmission timeout: estimated from measured round trips as TCP does (RFC 6298),
//! with a floor, a ceiling and exponential backoff on repeated timeouts.

use std::time::Duration;

/// Bounds of the retransmission timeout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RtoOptions {
    /// The timeout before any round trip was measured.
    pub initial: Duration,
    /// The floor: the timeout is never shorter (scheduling jitter of the host and the device).
    pub min: Duration,
    /// The ceiling: the timeout is never longer, backoff included.
    pub max: Duration,
}

impl Default for RtoOptions {
    fn default() -> Self {
        RtoOptions {
            initial: Duration::from_millis(200),
            min: Duration::from_millis(2),
            max: Duration::from_secs(2),
        }
    }
}

/// Doublings at most (2¹⁶ × the floor is far past any sensible ceiling).
const MAX_BACKOFF: u32 = 16;

/// The estimator: smoothed round trip (SRTT) and its variation (RTTVAR), and the backoff.
///
/// * A sample `r` updates `RTTVAR ← ¾·RTTVAR + ¼·|SRTT − r|`, then `SRTT ← ⅞·SRTT + ⅛·r`
///   (the first sets `SRTT = r`, `RTTVAR = r/2`), and clears the backoff.
/// * The timeout is `SRTT + max(G, 4·RTTVAR)` (the initial one before any sample), where the
///   margin `G` (RFC 6298's clock granularity) is the floor: a device whose round trip never
///   varies (an emulator) still gets a margin over it. It is held within
///   [`RtoOptions::min`] and [`RtoOptions::max`], doubled per [`Rto::back_off`] since the last
///   sample, and held below the ceiling again.
///
/// Karn's rule (no sample from a request sent more than once, since its answer may be the
/// first send's or the retry's) is the caller's: it only feeds unambiguous samples.
#[derive(Clone, Debug)]
pub struct Rto {
    opts: RtoOptions,
    srtt: Option<Duration>,
    rttvar: Duration,
    backoff: u32,
}

impl Rto {
    /// An estimator with no sample yet.
    pub fn new(opts: RtoOptions) -> Self {
        Rto {
            opts,
            srtt: None,
            rttvar: Duration::ZERO,
            backoff: 0,
        }
    }

    /// Takes one measured round trip into account and clears the backoff.
    pub fn sample(&mut self, rtt: Duration) {
        match self.srtt {
            None => {
                self.srtt = Some(rtt);
                self.rttvar = rtt / 2;
            }
            Some(srtt) => {
                let err = srtt.abs_diff(rtt);
                self.rttvar = (self.rttvar * 3 + err) / 4;
                self.srtt = Some((srtt * 7 + rtt) / 8);
            }
        }
        self.backoff = 0;
    }

    /// A timeout expired: the next timeouts are twice as long (up to the ceiling) until the
    /// next sample.
    pub fn back_off(&mut self) {
        self.backoff = (self.backoff + 1).min(MAX_BACKOFF);
    }

    /// The current timeout.
    pub fn timeout(&self) -> Duration {
        let (min, max) = (self.opts.min, self.opts.max.max(self.opts.min));
        let base = match self.srtt {
            Some(srtt) => srtt.saturating_add(self.rttvar.saturating_mul(4).max(min)),
            None => self.opts.initial,
        };
        base.clamp(min, max)
            .saturating_mul(1 << self.backoff)
            .min(max)
    }

    /// The smoothed round trip, once measured.
    pub fn srtt(&self) -> Option<Duration> {
        self.srtt
    }

    /// Doublings in force.
    pub fn backoff(&self) -> u32 {
        self.backoff
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn the_first_sample_sets_srtt_and_half_of_it_as_variation() {
        let mut r = Rto::new(RtoOptions::default());
        assert_eq!(r.timeout(), ms(200), "initial");
        r.sample(ms(10));
        assert_eq!(r.srtt(), Some(ms(10)));
        assert_eq!(r.timeout(), ms(30), "10 + 4 × 5");
    }

    #[test]
    fn steady_samples_converge_on_the_round_trip_and_stay_above_it() {
        let mut r = Rto::new(RtoOptions::default());
        for _ in 0..200 {
            r.sample(ms(94));
        }
        assert_eq!(r.srtt(), Some(ms(94)));
        assert_eq!(r.timeout(), ms(96), "94 ms and the 2 ms margin");
    }

    #[test]
    fn floor_ceiling_and_backoff() {
        let opts = RtoOptions {
            initial: ms(200),
            min: ms(2),
            max: ms(1000),
        };
        let mut r = Rto::new(opts);
        r.sample(Duration::from_micros(50));
        let base = Duration::from_micros(2050);
        assert_eq!(r.timeout(), base, "50 µs and the floor as margin");
        r.back_off();
        assert_eq!(r.timeout(), base * 2);
        r.back_off();
        assert_eq!(r.timeout(), base * 4);
        for _ in 0..40 {
            r.back_off();
        }
        assert_eq!(r.timeout(), ms(1000), "ceiling");
        r.sample(Duration::from_micros(50));
        assert_eq!(r.backoff(), 0, "a sample clears the backoff");
        r.sample(ms(5000));
        assert_eq!(r.timeout(), ms(1000), "ceiling without backoff");
    }

    #[test]
    fn a_ceiling_below_the_floor_is_the_floor() {
        let mut r = Rto::new(RtoOptions {
            initial: ms(1),
            min: ms(10),
            max: ms(5),
        });
        assert_eq!(r.timeout(), ms(10));
        r.back_off();
        assert_eq!(r.timeout(), ms(10));
    }
}
