//! `positions.npy`: every recorded position as a NumPy array, `np.load("positions.npy")`;
//! `attitude.npy`: every recorded body attitude, shape `(frames, agents, 2)`, the roll and the
//! pitch in degrees (bees: the decision's set-points, positive roll = right wing down; ants 0).
//!
//! Format: NPY version 1.0, dtype `<f4` (little-endian f32), shape `(frames, agents, 3)`, C
//! order. The file is byte for byte what `numpy.save` (NumPy ≥ 1.24) writes for such an array:
//!
//! ```text
//! \x93NUMPY \x01 \x00 <u16 LE header length>
//! {'descr': '<f4', 'fortran_order': False, 'shape': (F, A, 3), }<spaces>\n
//! <F·A·3 f32 LE>
//! ```
//!
//! After the dict NumPy adds `21 − len(str(F))` spaces (room to grow the first axis in place),
//! then pads with spaces so that the data starts at a multiple of 64 bytes, and ends the header
//! with `\n`. Because that total does not depend on `F`, [`NpyWriter`] can stream frames and
//! patch the frame count into the header at the end.

use std::fs::File;
use std::io::{Read, Write};
use std::path::Path;

use super::atomic::AtomicFile;
use super::frames::{AgentSample, Frame};
use crate::{Result, SimError};

/// The NPY magic string.
pub const NPY_MAGIC: &[u8; 6] = b"\x93NUMPY";
/// NumPy aligns the start of the data to this many bytes.
const ARRAY_ALIGN: usize = 64;
/// NumPy's spare room for the digits of the growth axis.
const GROWTH_AXIS_MAX_DIGITS: usize = 21;

/// The complete NPY 1.0 header (magic to `\n`) for an `<f4` C-order array of shape
/// `(frames, agents, 3)`.
pub fn npy_header(frames: usize, agents: usize) -> Vec<u8> {
    npy_header_of(frames, agents, 3)
}

/// The complete NPY 1.0 header for an `<f4` C-order array of shape `(frames, agents, width)`.
pub fn npy_header_of(frames: usize, agents: usize, width: usize) -> Vec<u8> {
    let mut dict = format!(
        "{{'descr': '<f4', 'fortran_order': False, 'shape': ({frames}, {agents}, {width}), }}"
    );
    let digits = frames.to_string().len();
    dict.extend(std::iter::repeat_n(
        ' ',
        GROWTH_AXIS_MAX_DIGITS.saturating_sub(digits),
    ));
    let hlen = dict.len() + 1; // + '\n'
    let padlen = ARRAY_ALIGN - ((NPY_MAGIC.len() + 2 + 2 + hlen) % ARRAY_ALIGN);
    let total = hlen + padlen;
    let mut out = Vec::with_capacity(10 + total);
    out.extend_from_slice(NPY_MAGIC);
    out.extend_from_slice(&[1, 0]);
    out.extend_from_slice(&(total as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out.extend(std::iter::repeat_n(b' ', padlen));
    out.push(b'\n');
    out
}

/// What an `.npy` file of frames holds per agent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NpyField {
    /// `positions.npy`: x, y, z.
    Positions,
    /// `attitude.npy`: roll and pitch in degrees.
    Attitude,
}

impl NpyField {
    /// Values per agent (the last axis).
    pub fn width(self) -> usize {
        match self {
            NpyField::Positions => 3,
            NpyField::Attitude => 2,
        }
    }
}

/// Streams frames into `positions.npy` (or `attitude.npy`), atomically (nothing at the final
/// path until [`NpyWriter::finish`]).
#[derive(Debug)]
pub struct NpyWriter {
    file: AtomicFile,
    field: NpyField,
    agents: usize,
    frames: usize,
    header_len: usize,
    buf: Vec<u8>,
}

impl NpyWriter {
    /// Starts a positions file for frames of `agents` agents.
    pub fn create(path: impl AsRef<Path>, agents: usize) -> Result<Self> {
        Self::create_of(path, agents, NpyField::Positions)
    }

    /// Starts a file of `field` for frames of `agents` agents.
    pub fn create_of(path: impl AsRef<Path>, agents: usize, field: NpyField) -> Result<Self> {
        let mut file = AtomicFile::create(path)?;
        let header = npy_header_of(0, agents, field.width());
        file.writer()
            .write_all(&header)
            .map_err(|e| SimError::io("writing", file.path(), e))?;
        Ok(Self {
            file,
            field,
            agents,
            frames: 0,
            header_len: header.len(),
            buf: Vec::new(),
        })
    }

    /// Appends the positions of one frame (it must hold exactly `agents` agents).
    pub fn push(&mut self, frame: &Frame) -> Result<()> {
        self.push_positions(&frame.agents)
    }

    /// Appends the values (positions, or attitudes) of one frame's agents.
    pub fn push_positions(&mut self, agents: &[AgentSample]) -> Result<()> {
        if agents.len() != self.agents {
            return Err(SimError::NpyFrameAgents {
                path: self.file.path().to_path_buf(),
                agents: agents.len(),
                expected: self.agents,
            });
        }
        self.buf.clear();
        self.buf.reserve(agents.len() * 4 * self.field.width());
        for a in agents {
            match self.field {
                NpyField::Positions => {
                    for c in a.pos {
                        self.buf.extend_from_slice(&c.to_le_bytes());
                    }
                }
                NpyField::Attitude => {
                    self.buf.extend_from_slice(&a.roll.to_le_bytes());
                    self.buf.extend_from_slice(&a.pitch.to_le_bytes());
                }
            }
        }
        self.file
            .writer()
            .write_all(&self.buf)
            .map_err(|e| SimError::io("writing", self.file.path(), e))?;
        self.frames += 1;
        Ok(())
    }

    /// Writes the final frame count into the header and moves the file into place.
    pub fn finish(mut self) -> Result<()> {
        let header = npy_header_of(self.frames, self.agents, self.field.width());
        if header.len() != self.header_len {
            return Err(SimError::NpyHeaderGrew {
                path: self.file.path().to_path_buf(),
            });
        }
        self.file.patch(0, &header)?;
        self.file.commit()
    }
}

/// Writes the positions of all `frames` to `path` as an `(F, A, 3)` `<f4` array.
pub fn write_npy(path: impl AsRef<Path>, frames: &[Frame]) -> Result<()> {
    write_npy_of(path, frames, NpyField::Positions)
}

/// Writes `field` of all `frames` to `path` as an `(F, A, width)` `<f4` array.
pub fn write_npy_of(path: impl AsRef<Path>, frames: &[Frame], field: NpyField) -> Result<()> {
    let path = path.as_ref();
    let agents = super::frames::check_frames(frames, path)?;
    let mut w = NpyWriter::create_of(path, agents, field)?;
    for f in frames {
        w.push(f)?;
    }
    w.finish()
}

/// A `(frames, agents, 3)` array of positions read from a `.npy` file.
#[derive(Clone, Debug, PartialEq)]
pub struct Positions {
    /// First axis.
    pub frames: usize,
    /// Second axis.
    pub agents: usize,
    /// `frames · agents · 3` values in C order.
    pub data: Vec<f32>,
}

impl Positions {
    /// The position of agent `a` in frame `f`.
    pub fn get(&self, f: usize, a: usize) -> [f32; 3] {
        let i = (f * self.agents + a) * 3;
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }

    /// Frames with these positions, step = frame index, ids in order, everything else zero
    /// (a `.npy` file holds positions only).
    pub fn to_frames(&self) -> Vec<Frame> {
        (0..self.frames)
            .map(|f| Frame {
                step: f as u32,
                agents: (0..self.agents)
                    .map(|a| AgentSample {
                        id: a as u32,
                        pos: self.get(f, a),
                        ..AgentSample::default()
                    })
                    .collect(),
            })
            .collect()
    }
}

/// Reads an `<f4` C-order array of shape `(F, A, 3)` (NPY version 1, 2 or 3).
pub fn read_npy(path: impl AsRef<Path>) -> Result<Positions> {
    read_npy_of(path, 3)
}

/// Reads `attitude.npy`, an `<f4` C-order array of shape `(F, A, 2)`: the roll and the pitch
/// (degrees) of each agent in each frame, in [`Positions::data`] with 2 values per agent.
pub fn read_attitude_npy(path: impl AsRef<Path>) -> Result<Positions> {
    read_npy_of(path, 2)
}

/// Reads an `<f4` C-order array of shape `(F, A, width)`.
fn read_npy_of(path: impl AsRef<Path>, width: usize) -> Result<Positions> {
    let path = path.as_ref();
    let file = || path.to_path_buf();
    let mut bytes = Vec::new();
    File::open(path)
        .map_err(|e| SimError::io("opening", path, e))?
        .read_to_end(&mut bytes)
        .map_err(|e| SimError::io("reading", path, e))?;
    if bytes.len() < 10 || &bytes[..6] != NPY_MAGIC {
        return Err(SimError::NpyMagic { path: file() });
    }
    let (hlen, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        major => {
            return Err(SimError::NpyVersion {
                path: file(),
                major,
                minor: bytes[7],
            });
        }
    };
    let data_start = start + hlen;
    if bytes.len() < data_start {
        return Err(SimError::NpyTruncated { path: file() });
    }
    let header = std::str::from_utf8(&bytes[start..data_start])
        .map_err(|_| SimError::NpyHeaderText { path: file() })?;
    let key = |key: &'static str| {
        dict_value(header, key).ok_or_else(|| SimError::NpyHeaderKey { path: file(), key })
    };
    let descr = key("descr")?;
    let descr = descr.trim_matches(|c| c == '\'' || c == '"');
    if descr != "<f4" {
        return Err(SimError::NpyDtype {
            path: file(),
            dtype: descr.to_owned(),
        });
    }
    if key("fortran_order")? != "False" {
        return Err(SimError::NpyFortranOrder { path: file() });
    }
    let shape = key("shape")?;
    let dims: Vec<usize> = shape
        .trim_start_matches('(')
        .trim_end_matches(')')
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<usize>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| SimError::NpyShapeSyntax {
            path: file(),
            shape: shape.to_owned(),
        })?;
    let (frames, agents) = match dims[..] {
        [frames, agents, w] if w == width => (frames, agents),
        _ => {
            return Err(SimError::NpyShape {
                path: file(),
                shape: shape.to_owned(),
                width,
            });
        }
    };
    let n = frames
        .checked_mul(agents)
        .and_then(|x| x.checked_mul(4 * width))
        .ok_or_else(|| SimError::NpyTooLarge {
            path: file(),
            shape: shape.to_owned(),
        })?;
    if bytes.len() - data_start != n {
        return Err(SimError::NpyDataLength {
            path: file(),
            bytes: bytes.len() - data_start,
            shape: shape.to_owned(),
            needed: n,
        });
    }
    let data = bytes[data_start..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    Ok(Positions {
        frames,
        agents,
        data,
    })
}

/// The text of the value of `key` in a Python dict literal: up to the next `,` at bracket
/// depth 0 (so tuples stay whole).
fn dict_value<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let pat1 = format!("'{key}':");
    let pat2 = format!("\"{key}\":");
    let at = header
        .find(&pat1)
        .map(|i| i + pat1.len())
        .or_else(|| header.find(&pat2).map(|i| i + pat2.len()))?;
    let rest = header[at..].trim_start();
    let mut depth = 0i32;
    for (i, c) in rest.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::testing::{read_error, temp_path};

    fn tiny() -> Vec<Frame> {
        // (2, 2, 3): values 0.0, 0.5, ..., 5.5 in C order.
        (0..2)
            .map(|f| Frame {
                step: f,
                agents: (0..2)
                    .map(|a| {
                        let b = ((f * 2 + a) * 3) as f32 * 0.5;
                        AgentSample {
                            id: a,
                            pos: [b, b + 0.5, b + 1.0],
                            ..Default::default()
                        }
                    })
                    .collect(),
            })
            .collect()
    }

    /// What `numpy.save(f, np.arange(12, dtype='<f4').reshape(2, 2, 3) * 0.5)` writes
    /// (NumPy 1.24 ... 2.x), pinned.
    fn pinned_tiny() -> Vec<u8> {
        let mut v = Vec::new();
        v.extend_from_slice(b"\x93NUMPY\x01\x00\x76\x00");
        v.extend_from_slice(b"{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2, 3), }");
        // 20 growth spaces + 35 alignment spaces, then '\n': data starts at byte 128.
        v.extend(std::iter::repeat_n(b' ', 20 + 35));
        v.push(b'\n');
        assert_eq!(v.len(), 128);
        for i in 0..12 {
            v.extend_from_slice(&(i as f32 * 0.5).to_le_bytes());
        }
        v
    }

    #[test]
    fn header_layout() {
        for (f, a) in [(0, 0), (1, 1), (2, 2), (300, 500), (123_456_789, 1_000_000)] {
            let h = npy_header(f, a);
            assert_eq!(h.len() % 64, 0, "{f} {a}");
            assert_eq!(&h[..8], b"\x93NUMPY\x01\x00");
            assert_eq!(u16::from_le_bytes([h[8], h[9]]) as usize, h.len() - 10);
            assert_eq!(*h.last().unwrap(), b'\n');
            // Length independent of the frame count (streaming patch).
            assert_eq!(h.len(), npy_header(0, a).len());
        }
    }

    #[test]
    fn pinned_bytes() {
        let (_dir, p) = temp_path("positions.npy");
        write_npy(&p, &tiny()).unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), pinned_tiny());
    }

    #[test]
    fn round_trip() {
        let (_dir, p) = temp_path("positions.npy");
        let frames = tiny();
        write_npy(&p, &frames).unwrap();
        let back = read_npy(&p).unwrap();
        assert_eq!((back.frames, back.agents), (2, 2));
        assert_eq!(back.get(1, 1), frames[1].agents[1].pos);
        let fr = back.to_frames();
        assert_eq!(fr[1].agents[0].pos, frames[1].agents[0].pos);
    }

    #[test]
    fn attitude_round_trip() {
        let (_dir, p) = temp_path("attitude.npy");
        let mut frames = tiny();
        frames[1].agents[0].roll = -12.5;
        frames[1].agents[0].pitch = 16.25;
        write_npy_of(&p, &frames, NpyField::Attitude).unwrap();
        let b = std::fs::read(&p).unwrap();
        assert!(
            std::str::from_utf8(&b[10..128])
                .unwrap()
                .contains("'shape': (2, 2, 2)")
        );
        assert_eq!(b.len(), 128 + 2 * 2 * 2 * 4);
        let back = read_attitude_npy(&p).unwrap();
        assert_eq!((back.frames, back.agents), (2, 2));
        assert_eq!(back.data[4..6], [-12.5, 16.25]);
        // Not a positions array.
        assert!(
            read_npy(&p)
                .unwrap_err()
                .to_string()
                .contains("(frames, agents, 3)")
        );
    }

    #[test]
    fn empty_array() {
        let (_dir, p) = temp_path("e.npy");
        write_npy(&p, &[]).unwrap();
        let b = std::fs::read(&p).unwrap();
        assert!(
            std::str::from_utf8(&b[10..])
                .unwrap()
                .contains("'shape': (0, 0, 3)")
        );
        let back = read_npy(&p).unwrap();
        assert_eq!((back.frames, back.agents, back.data.len()), (0, 0, 0));
    }

    #[test]
    fn reader_rejects_bad_files() {
        let (_dir, p) = temp_path("bad.npy");
        assert!(read_error(&p, b"hello world", read_npy).contains("bad.npy"));
        let mut t = pinned_tiny();
        t.pop();
        assert!(read_error(&p, &t, read_npy).contains("data bytes"));
        let mut t = pinned_tiny();
        let at = t.windows(3).position(|w| w == b"<f4").unwrap();
        t[at + 2] = b'8';
        assert!(read_error(&p, &t, read_npy).contains("dtype"));
    }

    /// The Python interpreter for the NumPy cross-check: `$SWARM_PYTHON` or `python3`.
    fn python() -> String {
        std::env::var("SWARM_PYTHON").unwrap_or_else(|_| "python3".into())
    }

    fn have_numpy() -> bool {
        std::process::Command::new(python())
            .args(["-c", "import numpy"])
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false)
    }

    #[test]
    fn matches_numpy_when_available() {
        if !have_numpy() {
            eprintln!(
                "note: numpy not importable by `{}`: skipping the NumPy cross-check \
                 (the pinned byte vector test still ran)",
                python()
            );
            return;
        }
        let dir = tempfile::tempdir().unwrap();
        let cases: [(usize, usize); 5] = [(2, 2), (1, 7), (12, 1), (0, 0), (150, 37)];
        for (f, a) in cases {
            let frames: Vec<Frame> = (0..f)
                .map(|fi| Frame {
                    step: fi as u32,
                    agents: (0..a)
                        .map(|ai| {
                            let b = ((fi * a + ai) * 3) as f32 * 0.5;
                            AgentSample {
                                id: ai as u32,
                                pos: [b, b + 0.5, b + 1.0],
                                ..Default::default()
                            }
                        })
                        .collect(),
                })
                .collect();
            let ours = dir.path().join(format!("ours_{f}_{a}.npy"));
            let theirs = dir.path().join(format!("np_{f}_{a}.npy"));
            write_npy(&ours, &frames).unwrap();
            let script = format!(
                "import numpy as np; np.save(r'{}', (np.arange({f}*{a}*3, dtype='<f4')*np.float32(0.5)).reshape({f}, {a}, 3)); \
                 x = np.load(r'{}'); assert x.dtype == np.dtype('<f4') and x.shape == ({f}, {a}, 3)",
                theirs.display(),
                ours.display()
            );
            let out = std::process::Command::new(python())
                .args(["-c", &script])
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "numpy failed: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            assert_eq!(
                std::fs::read(&ours).unwrap(),
                std::fs::read(&theirs).unwrap(),
                "shape ({f}, {a}, 3)"
            );
        }
    }
}
