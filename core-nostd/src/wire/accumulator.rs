//! The streaming receiver: bytes in, in chunks of any size; frames and drop reports out.

use super::frame::{Frame, decode_any_version};
use super::header::{Header, PROTOCOL_VERSION};
use crate::Error;

/// What the receiver saw at a `0x00` delimiter that ended a non-empty run of bytes.
///
/// Every such run gives exactly one event; empty runs (consecutive `0x00`) give none and are
/// only counted in [`Stats::empty`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Event<'a> {
    /// A frame that passed every check (COBS, length, CRC, version). Its payload borrows the
    /// accumulator's buffer until the next call that feeds it.
    Frame(Frame<'a>),
    /// The bytes since the previous delimiter were dropped; the receiver is already
    /// resynchronised (it starts a new frame with the next byte).
    Dropped {
        /// Why: [`Error::Oversize`], [`Error::Cobs`], [`Error::Truncated`], [`Error::Crc`] or
        /// [`Error::Version`].
        error: Error,
        /// How many bytes were dropped (the delimiter not counted).
        bytes: usize,
    },
}

/// Receiver counters. Every counter saturates at `u32::MAX` instead of wrapping.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stats {
    /// Frames delivered as [`Event::Frame`].
    pub frames_ok: u32,
    /// Frames dropped for a CRC mismatch.
    pub crc_errors: u32,
    /// Frames dropped for malformed COBS (this includes most line noise).
    pub cobs_errors: u32,
    /// Frames dropped for being shorter than header + CRC.
    pub truncated: u32,
    /// Frames dropped for carrying another protocol version.
    pub version_errors: u32,
    /// Frames dropped for being longer than the receive buffer.
    pub oversize: u32,
    /// Empty frames (a `0x00` right after a `0x00`, or first on the line), ignored.
    pub empty: u32,
    /// Bytes thrown away with dropped frames (delimiters not counted).
    pub bytes_dropped: u32,
}

impl Stats {
    /// All dropped frames: the number of times the receiver resynchronised on a `0x00`.
    pub const fn resyncs(&self) -> u32 {
        self.crc_errors
            .saturating_add(self.cobs_errors)
            .saturating_add(self.truncated)
            .saturating_add(self.version_errors)
            .saturating_add(self.oversize)
    }
}

fn bump(c: &mut u32) {
    *c = c.saturating_add(1);
}

/// A streaming frame receiver with an `N`-byte buffer: feed it the bytes from the line in
/// chunks of any size, get back one [`Event`] per frame. It never panics, never allocates, and
/// its work is bounded: O(1) per byte, plus one O(frame length) decode at each delimiter.
///
/// `N` is the longest encoded frame it accepts, delimiter excluded;
/// [`max_frame_len`](super::max_frame_len)`(payload_len)` is always enough. A longer frame is
/// dropped whole ([`Error::Oversize`]) and reception resumes after its delimiter. Line noise is
/// dropped the same way, up to and including the next `0x00`: so noise that runs straight into
/// a frame costs that one frame, and a sender should send a lone `0x00` before its first frame
/// (empty frames are ignored).
///
/// ```
/// use swarm_core::wire::{Accumulator, Event, encode_frame};
///
/// let mut line = [0u8; 64];
/// let n = encode_frame(0x01, 7, &(1u8, 2u16), &mut line).unwrap();
///
/// let mut acc = Accumulator::<64>::new();
/// let mut chunk: &[u8] = &line[..n];
/// while let Some((event, rest)) = acc.feed(chunk) {
///     chunk = rest;
///     match event {
///         Event::Frame(frame) => {
///             assert_eq!(frame.header.seq, 7);
///             assert_eq!(frame.payload_as::<(u8, u16)>(), Ok((1, 2)));
///         }
///         Event::Dropped { error, bytes } => panic!("dropped {bytes} bytes: {error}"),
///     }
/// }
/// assert_eq!(acc.stats().frames_ok, 1);
/// ```
#[derive(Clone, Debug)]
pub struct Accumulator<const N: usize> {
    buf: [u8; N],
    /// Bytes since the last delimiter (saturating); only the first `N` are stored.
    len: usize,
    stats: Stats,
    /// The header of the frame behind the last event, if it was dropped for its version.
    foreign: Option<Header>,
}

impl<const N: usize> Default for Accumulator<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Accumulator<N> {
    /// An empty receiver.
    pub const fn new() -> Self {
        Accumulator {
            buf: [0; N],
            len: 0,
            stats: Stats {
                frames_ok: 0,
                crc_errors: 0,
                cobs_errors: 0,
                truncated: 0,
                version_errors: 0,
                oversize: 0,
                empty: 0,
                bytes_dropped: 0,
            },
            foreign: None,
        }
    }

    /// Feeds bytes until the first event. Returns `None` when every byte was absorbed without
    /// completing a frame, or the event and the bytes not yet fed: call again with those.
    ///
    /// ```
    /// # use swarm_core::wire::{Accumulator, Event};
    /// # let mut acc = Accumulator::<64>::new();
    /// # let mut chunk: &[u8] = &[0, 1, 2, 0];
    /// while let Some((event, rest)) = acc.feed(chunk) {
    ///     chunk = rest;
    ///     // handle `event` (its payload borrows `acc` until the next `feed`)
    /// #   let _ = event;
    /// }
    /// ```
    pub fn feed<'a, 'b>(&'a mut self, bytes: &'b [u8]) -> Option<(Event<'a>, &'b [u8])> {
        // `absorb` is O(1); `position` stops at the byte that completes a frame.
        let at = bytes.iter().position(|&b| self.absorb(b))?;
        let rest = bytes
            .get(at..)
            .and_then(<[u8]>::split_first)
            .map_or(&[][..], |(_, r)| r);
        Some((self.finish(), rest))
    }

    /// Feeds one byte: `Some` when it was a delimiter that ended a non-empty frame.
    pub fn push(&mut self, byte: u8) -> Option<Event<'_>> {
        if self.absorb(byte) {
            Some(self.finish())
        } else {
            None
        }
    }

    /// The counters so far.
    pub const fn stats(&self) -> Stats {
        self.stats
    }

    /// Zeroes the counters.
    pub fn reset_stats(&mut self) {
        self.stats = Stats::default();
    }

    /// Bytes received since the last delimiter (a frame in progress, or noise).
    pub const fn pending(&self) -> usize {
        self.len
    }

    /// Forgets the frame in progress (e.g. after a line reset); it is not counted as dropped.
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// The header of the frame behind the last event, when that event was
    /// [`Event::Dropped`] with [`Error::Version`]: such a frame passed its COBS, length and CRC
    /// checks, so its header is trustworthy and its `seq` can be answered (the device endpoint
    /// answers it with an [`ErrorReply`](super::ErrorReply) of code
    /// [`VERSION`](super::ErrorReply::VERSION), unless its kind is one a device never answers:
    /// [`kind::never_answered`](super::kind::never_answered)). `None` after any other event.
    pub const fn foreign_header(&self) -> Option<Header> {
        self.foreign
    }

    /// Takes one byte; `true` if it completed a non-empty frame (then call `finish`).
    fn absorb(&mut self, byte: u8) -> bool {
        if byte == 0 {
            if self.len == 0 {
                bump(&mut self.stats.empty);
                return false;
            }
            return true;
        }
        if let Some(slot) = self.buf.get_mut(self.len) {
            *slot = byte;
        }
        self.len = self.len.saturating_add(1);
        false
    }

    /// Decodes the completed frame and resets for the next one.
    fn finish(&mut self) -> Event<'_> {
        let len = core::mem::take(&mut self.len);
        let stats = &mut self.stats;
        let foreign = &mut self.foreign;
        *foreign = None;
        let result = match self.buf.get_mut(..len) {
            Some(frame) => match decode_any_version(frame) {
                Ok((header, payload)) if header.version == PROTOCOL_VERSION => {
                    Ok(Frame { header, payload })
                }
                Ok((header, _)) => {
                    *foreign = Some(header);
                    Err(Error::Version {
                        got: header.version,
                    })
                }
                Err(e) => Err(e),
            },
            None => Err(Error::Oversize),
        };
        match result {
            Ok(frame) => {
                bump(&mut stats.frames_ok);
                Event::Frame(frame)
            }
            Err(error) => {
                bump(match error {
                    Error::Crc { .. } => &mut stats.crc_errors,
                    Error::Truncated => &mut stats.truncated,
                    Error::Version { .. } => &mut stats.version_errors,
                    Error::Oversize => &mut stats.oversize,
                    _ => &mut stats.cobs_errors,
                });
                let dropped = u32::try_from(len).unwrap_or(u32::MAX);
                stats.bytes_dropped = stats.bytes_dropped.saturating_add(dropped);
                Event::Dropped { error, bytes: len }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::frame::Raw;
    use crate::wire::{Header, encode_frame};
    use proptest::prelude::*;

    fn frame(kind: u8, seq: u16, msg: &impl serde::Serialize) -> Vec<u8> {
        let mut out = vec![0u8; 1024];
        let n = encode_frame(kind, seq, msg, &mut out).unwrap();
        out.truncate(n);
        out
    }

    /// What an event says, owned: `Ok((kind, seq, payload))` or `Err((error, bytes))`.
    type Seen = core::result::Result<(u8, u16, Vec<u8>), (Error, usize)>;

    fn own(ev: Event<'_>) -> Seen {
        match ev {
            Event::Frame(f) => Ok((f.header.kind, f.header.seq, f.payload.to_vec())),
            Event::Dropped { error, bytes } => Err((error, bytes)),
        }
    }

    /// Feeds `chunks` in order, collecting every event.
    fn run<const N: usize>(acc: &mut Accumulator<N>, chunks: &[&[u8]]) -> Vec<Seen> {
        let mut seen = Vec::new();
        for &chunk in chunks {
            let mut rest = chunk;
            while let Some((ev, r)) = acc.feed(rest) {
                rest = r;
                seen.push(own(ev));
            }
        }
        seen
    }

    fn ok(kind: u8, seq: u16, payload: &[u8]) -> Seen {
        Ok((kind, seq, payload.to_vec()))
    }

    #[test]
    fn one_frame() {
        let f = frame(1, 2, &3u8);
        let mut acc = Accumulator::<32>::new();
        assert_eq!(run(&mut acc, &[&f]), vec![ok(1, 2, &[3])]);
        assert_eq!(
            acc.stats(),
            Stats {
                frames_ok: 1,
                ..Stats::default()
            }
        );
        assert_eq!(acc.pending(), 0);
    }

    #[test]
    fn byte_by_byte_with_push() {
        let f = frame(9, 0xABCD, &(1u32, -1i64, true));
        let mut acc = Accumulator::<32>::new();
        let mut seen = Vec::new();
        for &b in &f {
            if let Some(ev) = acc.push(b) {
                seen.push(own(ev));
            }
        }
        assert_eq!(seen, vec![ok(9, 0xABCD, &[1, 1, 1])]);
    }

    #[test]
    fn split_byte_by_byte_with_feed() {
        let f = frame(9, 0xABCD, &(1u32, -1i64, true));
        let chunks: Vec<&[u8]> = f.chunks(1).collect();
        let mut acc = Accumulator::<32>::new();
        assert_eq!(run(&mut acc, &chunks), vec![ok(9, 0xABCD, &[1, 1, 1])]);
    }

    #[test]
    fn two_frames_in_one_chunk_and_empty_frames() {
        let mut line = vec![0, 0];
        line.extend(frame(1, 1, &10u8));
        line.push(0);
        line.extend(frame(2, 2, &20u8));
        let mut acc = Accumulator::<32>::new();
        assert_eq!(
            run(&mut acc, &[&line]),
            vec![ok(1, 1, &[10]), ok(2, 2, &[20])]
        );
        assert_eq!(acc.stats().empty, 3);
        assert_eq!(acc.stats().frames_ok, 2);
        assert_eq!(acc.stats().resyncs(), 0);
    }

    #[test]
    fn bad_crc_is_counted_and_dropped() {
        let mut bad = frame(1, 1, &0x1234_5678u32);
        bad[6] ^= 0x40;
        let good = frame(1, 2, &5u8);
        let mut acc = Accumulator::<32>::new();
        let seen = run(&mut acc, &[&bad, &good]);
        assert!(matches!(seen[0], Err((Error::Crc { .. }, n)) if n == bad.len() - 1));
        assert_eq!(seen[1], ok(1, 2, &[5]));
        assert_eq!(acc.stats().crc_errors, 1);
        assert_eq!(acc.stats().bytes_dropped as usize, bad.len() - 1);
    }

    #[test]
    fn oversize_frame_then_good_frame() {
        let big = frame(1, 1, &Raw(&[7u8; 40]));
        let good = frame(1, 2, &Raw(&[7u8; 10]));
        let mut acc = Accumulator::<20>::new();
        assert_eq!(
            run(&mut acc, &[&big[..13], &big[13..], &good]),
            vec![Err((Error::Oversize, big.len() - 1)), ok(1, 2, &[7; 10])]
        );
        assert_eq!(acc.stats().oversize, 1);
        // The boundary: a frame of exactly N bytes (plus delimiter) fits.
        let exact = frame(1, 3, &Raw(&[7u8; 13]));
        assert_eq!(exact.len(), 21);
        assert_eq!(run(&mut acc, &[&exact]), vec![ok(1, 3, &[7; 13])]);
        let over = frame(1, 3, &Raw(&[7u8; 14]));
        assert_eq!(run(&mut acc, &[&over]), vec![Err((Error::Oversize, 21))]);
    }

    #[test]
    fn garbage_before_a_frame_is_skipped() {
        let good = frame(3, 4, &(1u8, 2u8));
        let mut acc = Accumulator::<64>::new();
        // Noise ended by a 0x00, then the frame: only the noise is lost.
        let seen = run(&mut acc, &[b"\x7f boot log\r\n\0", &good]);
        assert_eq!(seen, vec![Err((Error::Cobs, 12)), ok(3, 4, &[1, 2])]);
        // Noise running straight into a frame costs that frame, and only that frame.
        let seen = run(&mut acc, &[b"\xff\xfe", &good, &good]);
        assert_eq!(seen.len(), 2);
        assert!(seen[0].is_err());
        assert_eq!(seen[1], ok(3, 4, &[1, 2]));
        assert_eq!(acc.stats().frames_ok, 2);
        assert_eq!(acc.stats().resyncs(), 2);
    }

    #[test]
    fn version_and_truncated() {
        // 0x02 0x01: one raw byte; then a CRC-valid frame of version 1 (an old release).
        let mut v1 = vec![0u8; 16];
        let mut raw = vec![1, 1, 0, 0];
        raw.extend_from_slice(&crate::wire::CRC16.checksum(&raw).to_le_bytes());
        let n = cobs::try_encode(&raw, &mut v1).unwrap();
        v1.truncate(n);
        v1.push(0);
        let mut acc = Accumulator::<32>::new();
        let seen = run(&mut acc, &[&[2, 1, 0], &v1]);
        assert_eq!(
            seen,
            vec![
                Err((Error::Truncated, 2)),
                Err((Error::Version { got: 1 }, 7))
            ]
        );
        let s = acc.stats();
        assert_eq!((s.truncated, s.version_errors, s.bytes_dropped), (1, 1, 9));
        // The version-1 frame's header is trustworthy (CRC good): its seq can be answered.
        assert_eq!(
            acc.foreign_header(),
            Some(Header {
                version: 1,
                kind: 1,
                seq: 0
            })
        );
        // Any other event forgets it.
        let f = frame(1, 1, &());
        run(&mut acc, &[&f]);
        assert_eq!(acc.foreign_header(), None);
        run(&mut acc, &[&v1]);
        assert!(acc.foreign_header().is_some());
        run(&mut acc, &[b"\x05\x00"]);
        assert_eq!(acc.foreign_header(), None);
    }

    #[test]
    fn zero_capacity_drops_everything() {
        let mut acc = Accumulator::<0>::new();
        let f = frame(1, 1, &());
        assert_eq!(
            run(&mut acc, &[&f]),
            vec![Err((Error::Oversize, f.len() - 1))]
        );
    }

    #[test]
    fn clear_forgets_partial_frame() {
        let f = frame(1, 1, &());
        let mut acc = Accumulator::<32>::new();
        assert!(acc.feed(&f[..3]).is_none());
        assert_eq!(acc.pending(), 3);
        acc.clear();
        assert_eq!(run(&mut acc, &[&f]), vec![ok(1, 1, &[])]);
    }

    #[test]
    fn stats_serialize() {
        let s = Stats {
            frames_ok: 300,
            crc_errors: 1,
            ..Stats::default()
        };
        let mut buf = [0u8; 32];
        let n = postcard::to_slice(&s, &mut buf).unwrap().len();
        assert_eq!(&buf[..n], &[0xac, 0x02, 1, 0, 0, 0, 0, 0, 0]);
        assert_eq!(postcard::from_bytes::<Stats>(&buf[..n]).unwrap(), s);
    }

    #[test]
    fn header_in_event() {
        let f = frame(0x42, 0x0102, &());
        let mut acc = Accumulator::<32>::new();
        let (ev, rest) = acc.feed(&f).unwrap();
        assert!(rest.is_empty());
        let Event::Frame(fr) = ev else { panic!() };
        assert_eq!(fr.header, Header::new(0x42, 0x0102));
    }

    fn frames_strategy() -> impl Strategy<Value = Vec<(u8, u16, Vec<u8>)>> {
        proptest::collection::vec(
            (
                any::<u8>(),
                any::<u16>(),
                proptest::collection::vec(any::<u8>(), 0..80),
            ),
            0..6,
        )
    }

    proptest! {
        #[test]
        fn never_panics_and_accounts_for_every_byte(
            chunks in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..80), 0..10)
        ) {
            let mut acc = Accumulator::<48>::new();
            let refs: Vec<&[u8]> = chunks.iter().map(|c| c.as_slice()).collect();
            let seen = run(&mut acc, &refs);
            let all: Vec<u8> = chunks.concat();
            // One event per non-empty run ended by a 0x00; nothing else.
            let runs = all.split(|&b| b == 0).count() - 1;
            let empties = all.split(|&b| b == 0).take(runs).filter(|r| r.is_empty()).count();
            prop_assert_eq!(seen.len(), runs - empties);
            let s = acc.stats();
            prop_assert_eq!(s.empty as usize, empties);
            prop_assert_eq!((s.frames_ok + s.resyncs()) as usize, seen.len());
            let tail = all.split(|&b| b == 0).next_back().map_or(0, |t| t.len());
            prop_assert_eq!(acc.pending(), tail);
        }

        #[test]
        fn chopped_stream_gives_the_same_frames(
            frames in frames_strategy(),
            cuts in proptest::collection::vec(any::<prop::sample::Index>(), 0..12),
        ) {
            let mut line = Vec::new();
            let mut expect = Vec::new();
            for (kind, seq, payload) in &frames {
                line.extend(frame(*kind, *seq, &Raw(payload)));
                expect.push(ok(*kind, *seq, payload));
            }
            let mut cuts: Vec<usize> = cuts.iter().map(|i| i.index(line.len() + 1)).collect();
            cuts.push(0);
            cuts.push(line.len());
            cuts.sort_unstable();
            let chunks: Vec<&[u8]> = cuts.windows(2).map(|w| &line[w[0]..w[1]]).collect();
            let mut acc = Accumulator::<128>::new();
            prop_assert_eq!(run(&mut acc, &chunks), expect);
            prop_assert_eq!(acc.stats().frames_ok as usize, frames.len());
        }

        #[test]
        fn noise_then_frames(noise in proptest::collection::vec(any::<u8>(), 0..100),
                             frames in frames_strategy()) {
            // After noise and one 0x00, every frame arrives intact.
            let mut line = noise.clone();
            line.push(0);
            for (kind, seq, payload) in &frames {
                line.extend(frame(*kind, *seq, &Raw(payload)));
            }
            let mut acc = Accumulator::<128>::new();
            let seen = run(&mut acc, &[&line]);
            let good: Vec<Seen> = seen.into_iter().filter(|s| s.is_ok()).collect();
            // Noise could by chance be a valid frame (p < 2^-16); all real frames come last.
            let expect: Vec<Seen> = frames.iter().map(|(k, s, p)| ok(*k, *s, p)).collect();
            prop_assert!(good.len() >= expect.len());
            prop_assert_eq!(&good[good.len() - expect.len()..], &expect[..]);
        }
    }
}
