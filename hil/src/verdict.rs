//! What a mirror run concluded, and the exit status that says it.

use serde::{Serialize, Serializer};

/// Where a mismatch was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct MismatchAt {
    /// Simulation step.
    pub step: u32,
    /// Agent id.
    pub agent: u32,
    /// `plan`, `resolve` (ants) or `step` (bees).
    pub phase: &'static str,
}

/// The outcome of a run: any combination of three findings, none meaning a pass.
///
/// Serialized as `"pass"` or the findings joined by `+`, e.g. `"mismatch+link-failure"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Verdict {
    /// The device decided differently from the host, and repeated it when asked again (or
    /// could not be asked again).
    pub mismatch: bool,
    /// The device answered wrong, then right when asked the same again: a flaky device (or,
    /// far less likely, line damage that passed the CRC: see `docs/hil.md`).
    pub flaky: bool,
    /// The run did not complete: the link or the protocol failed (the counters are partial).
    pub link_failure: bool,
}

impl Verdict {
    /// Exit status bit of an incomplete run.
    pub const EXIT_LINK_FAILURE: u8 = 1;
    /// Exit status bit of a mismatch.
    pub const EXIT_MISMATCH: u8 = 2;
    /// Exit status bit of a flaky device.
    pub const EXIT_FLAKY: u8 = 4;
    /// Exit status of a command line that could not be used (nothing was run).
    pub const EXIT_USAGE: u8 = 64;

    /// Whether nothing was found and the run completed.
    pub fn passed(&self) -> bool {
        *self == Verdict::default()
    }

    /// The exit status: 0 for a pass, else the sum of the bits of the findings (1 link
    /// failure, 2 mismatch, 4 flaky), so 3 is a mismatch found before the link failed.
    pub fn exit_code(&self) -> u8 {
        u8::from(self.link_failure) * Self::EXIT_LINK_FAILURE
            + u8::from(self.mismatch) * Self::EXIT_MISMATCH
            + u8::from(self.flaky) * Self::EXIT_FLAKY
    }

    /// `pass`, or the findings joined by `+`.
    pub fn name(&self) -> String {
        let parts: Vec<&str> = [
            (self.mismatch, "mismatch"),
            (self.flaky, "flaky"),
            (self.link_failure, "link-failure"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect();
        if parts.is_empty() {
            "pass".into()
        } else {
            parts.join("+")
        }
    }
}

impl Serialize for Verdict {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(&self.name())
    }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

/// Whether `reasked` answers that were wrong, then right when asked again, make a flaky
/// device, on a line where receivers dropped `damaged` frames.
///
/// A CRC-16 lets about one damaged frame in 65,536 through, so a line that damaged `damaged`
/// frames is expected to pass `λ = damaged / 65536` damaged ones (fewer decode as a plausible
/// answer: the bound is generous to the line). The device is called flaky when seeing
/// `reasked` or more such answers from the line alone has a Poisson probability below 0.1 %.
/// On a clean line (`λ = 0`) one such answer is enough.
pub fn flaky(reasked: u64, damaged: u64) -> bool {
    if reasked == 0 {
        return false;
    }
    let lambda = damaged as f64 / 65_536.0;
    // P(X ≥ reasked) = 1 − Σ_{k < reasked} e^−λ λ^k / k!
    let mut term = (-lambda).exp();
    let mut below = 0.0;
    for k in 0..reasked.min(10_000) {
        below += term;
        term *= lambda / (k + 1) as f64;
    }
    1.0 - below < 1e-3
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wrong_then_right_answer_is_flaky_unless_the_line_explains_it() {
        assert!(!flaky(0, 0));
        assert!(flaky(1, 0), "a clean line explains nothing");
        assert!(
            flaky(1, 60),
            "60 damaged frames: 0.09 % chance of one escape"
        );
        assert!(!flaky(1, 10_000), "15 % chance of one escape");
        assert!(!flaky(2, 10_000));
        assert!(flaky(3, 10_000), "0.06 %");
        assert!(
            flaky(u64::MAX, u64::MAX) || !flaky(u64::MAX, u64::MAX),
            "no panic"
        );
    }

    #[test]
    fn names_and_exit_codes_of_every_combination() {
        let v = |mismatch, flaky, link_failure| Verdict {
            mismatch,
            flaky,
            link_failure,
        };
        for (verdict, name, code) in [
            (v(false, false, false), "pass", 0),
            (v(false, false, true), "link-failure", 1),
            (v(true, false, false), "mismatch", 2),
            (v(true, false, true), "mismatch+link-failure", 3),
            (v(false, true, false), "flaky", 4),
            (v(false, true, true), "flaky+link-failure", 5),
            (v(true, true, false), "mismatch+flaky", 6),
            (v(true, true, true), "mismatch+flaky+link-failure", 7),
        ] {
            assert_eq!((verdict.name(), verdict.exit_code()), (name.into(), code));
            assert_eq!(verdict.passed(), code == 0);
            assert_eq!(
                serde_json::to_value(verdict).unwrap(),
                serde_json::json!(name)
            );
        }
        const { assert!(Verdict::EXIT_USAGE > 7) };
    }
}
