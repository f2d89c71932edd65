//! The fixed 4-byte frame header.

/// The protocol version this build speaks; carried in byte 0 of every frame header.
///
/// A receiver drops frames of any other version with [`Error::Version`](crate::Error::Version).
pub const PROTOCOL_VERSION: u8 = 3;

/// Length of the encoded [`Header`] in bytes.
pub const HEADER_LEN: usize = 4;

/// The header that starts every frame, before the payload.
///
/// On the wire it is always exactly [`HEADER_LEN`] bytes, with no postcard encoding:
///
/// | byte | field     | encoding                 |
/// |------|-----------|--------------------------|
/// | 0    | `version` | u8 ([`PROTOCOL_VERSION`]) |
/// | 1    | `kind`    | u8 (which message)       |
/// | 2..4 | `seq`     | u16, little-endian       |
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Header {
    /// Protocol version of the sender.
    pub version: u8,
    /// Message kind: says which message type the payload holds (see
    /// [`Message::KIND`](super::Message::KIND)).
    pub kind: u8,
    /// Sequence number chosen by the sender; a reply carries the sequence number of its request.
    pub seq: u16,
}

impl Header {
    /// A header of this build's [`PROTOCOL_VERSION`].
    #[inline]
    pub const fn new(kind: u8, seq: u16) -> Self {
        Header {
            version: PROTOCOL_VERSION,
            kind,
            seq,
        }
    }

    /// The header's wire bytes: `[version, kind, seq_lo, seq_hi]`.
    #[inline]
    pub const fn to_bytes(self) -> [u8; HEADER_LEN] {
        let [lo, hi] = self.seq.to_le_bytes();
        [self.version, self.kind, lo, hi]
    }

    /// Reads a header from its wire bytes (any version; [`decode_frame`](super::decode_frame)
    /// checks it).
    #[inline]
    pub const fn from_bytes(bytes: [u8; HEADER_LEN]) -> Self {
        let [version, kind, lo, hi] = bytes;
        Header {
            version,
            kind,
            seq: u16::from_le_bytes([lo, hi]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_are_version_kind_seq_le() {
        let h = Header::new(0x21, 0xBEEF);
        assert_eq!(h.to_bytes(), [PROTOCOL_VERSION, 0x21, 0xEF, 0xBE]);
        assert_eq!(Header::from_bytes(h.to_bytes()), h);
    }
}
