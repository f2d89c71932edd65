//! Helpers shared by the wire module's tests: hex test vectors, COBS code bytes, whole frames
//! of a message and the round trip through an [`Accumulator`].

use serde::Serialize;

use super::{Accumulator, Event, Header, MAX_FRAME, MAX_PAYLOAD, Message, encode_message};

/// The bytes of a hex string such as `"03 02 81"` (white space ignored), as the pinned
/// vectors of `docs/protocol.md` write them.
pub(crate) fn hex(s: &str) -> Vec<u8> {
    let s: String = s.split_whitespace().collect();
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&s[i..i + 2], 16).unwrap())
        .collect()
}

/// Indices of the COBS code bytes of an encoded frame body (without its delimiter).
pub(crate) fn code_bytes(body: &[u8]) -> Vec<usize> {
    let mut v = Vec::new();
    let mut i = 0;
    while i < body.len() {
        v.push(i);
        i += body[i] as usize;
    }
    v
}

/// The whole frame of `msg` (sequence number `seq`), delimiter included.
pub(crate) fn frame_of<M: Message>(seq: u16, msg: &M) -> Vec<u8> {
    let mut out = vec![0u8; 2 * MAX_FRAME];
    let n = encode_message(seq, msg, &mut out).unwrap();
    out.truncate(n);
    out
}

/// Encodes `msg`, receives it through an accumulator, checks the header and decodes it back.
pub(crate) fn through_the_wire<M: Message + PartialEq + core::fmt::Debug>(seq: u16, msg: &M) -> M {
    let line = frame_of(seq, msg);
    assert!(line.len() <= MAX_FRAME);
    let mut rx = Accumulator::<MAX_FRAME>::new();
    let (ev, rest) = rx.feed(&line).unwrap();
    assert!(rest.is_empty());
    let Event::Frame(frame) = ev else {
        panic!("{ev:?}")
    };
    assert_eq!(frame.header, Header::new(M::KIND, seq));
    frame.message::<M>().unwrap()
}

/// The length of `msg`'s postcard encoding.
pub(crate) fn payload_len<T: Serialize>(msg: &T) -> usize {
    let mut buf = [0u8; 2 * MAX_PAYLOAD];
    postcard::to_slice(msg, &mut buf).unwrap().len()
}
