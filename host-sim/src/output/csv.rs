//! `trajectories.csv`: one row per agent per recorded step.
//!
//! ```text
//! step,id,group,x,y,z,hx,hy,hz,label,motion,roll_deg,pitch_deg
//! 0,0,0,12.5,3.25,0,1,0,0,0,1,0,0
//! ```
//!
//! `roll_deg` and `pitch_deg` are the body attitude in degrees (bees: the decision's
//! set-points, positive roll = right wing down; ants: 0). Files written before those two
//! columns existed (header [`CSV_HEADER_V1`]) are still read, with roll and pitch 0.
//!
//! Rows are grouped by step (increasing), agents in id order inside a step. Floats are printed
//! with Rust's `{}` for `f32`, the shortest text that parses back to the same `f32`, so reading
//! the file gives back the recorded bits exactly.

use std::fs::File;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};

use super::atomic::AtomicFile;
use super::frames::{AgentSample, Frame};
use crate::{Result, SimError};

/// The header line (without the newline).
pub const CSV_HEADER: &str = "step,id,group,x,y,z,hx,hy,hz,label,motion,roll_deg,pitch_deg";
/// The header of files written before the attitude columns (read with roll and pitch 0).
pub const CSV_HEADER_V1: &str = "step,id,group,x,y,z,hx,hy,hz,label,motion";

/// Streams frames into `trajectories.csv`, atomically: nothing appears at the final path until
/// [`CsvWriter::finish`]; dropping the writer unfinished leaves no file.
#[derive(Debug)]
pub struct CsvWriter {
    file: AtomicFile,
    agents: Option<usize>,
    last_step: Option<u32>,
}

impl CsvWriter {
    /// Starts the file and writes the header.
    pub fn create(path: impl AsRef<Path>) -> Result<Self> {
        let mut file = AtomicFile::create(path)?;
        writeln!(file.writer(), "{CSV_HEADER}")
            .map_err(|e| SimError::io("writing", file.path(), e))?;
        Ok(Self {
            file,
            agents: None,
            last_step: None,
        })
    }

    /// Appends one frame (it must hold as many agents as the first one, at a later step).
    pub fn push(&mut self, frame: &Frame) -> Result<()> {
        let path = self.file.path().to_path_buf();
        match self.agents {
            None => self.agents = Some(frame.agents.len()),
            Some(n) if n != frame.agents.len() => {
                return Err(SimError::CsvFrameAgents {
                    path,
                    step: frame.step,
                    agents: frame.agents.len(),
                    first: n,
                });
            }
            Some(_) => {}
        }
        if let Some(last) = self.last_step
            && frame.step <= last
        {
            return Err(SimError::CsvStepOrder {
                path,
                step: frame.step,
                last,
            });
        }
        self.last_step = Some(frame.step);
        let w = self.file.writer();
        let step = frame.step;
        for a in &frame.agents {
            let [x, y, z] = a.pos;
            let [hx, hy, hz] = a.heading;
            writeln!(
                w,
                "{step},{},{},{x},{y},{z},{hx},{hy},{hz},{},{},{},{}",
                a.id, a.group, a.label, a.motion, a.roll, a.pitch
            )
            .map_err(|e| SimError::io("writing", &path, e))?;
        }
        Ok(())
    }

    /// Completes the file (flush, sync, rename into place).
    pub fn finish(self) -> Result<()> {
        self.file.commit()
    }
}

/// Writes all `frames` to `path` (whole or not at all).
pub fn write_csv(path: impl AsRef<Path>, frames: &[Frame]) -> Result<()> {
    let path = path.as_ref();
    super::frames::check_frames(frames, path)?;
    let mut w = CsvWriter::create(path)?;
    for f in frames {
        w.push(f)?;
    }
    w.finish()
}

/// Reads `trajectories.csv` back into frames, checking the header, every field, and that every
/// step holds the same agents in the same order. Errors name the file and line.
pub fn read_csv(path: impl AsRef<Path>) -> Result<Vec<Frame>> {
    let path = path.as_ref();
    let file = File::open(path).map_err(|e| SimError::io("opening", path, e))?;
    let mut rd = BufReader::with_capacity(256 * 1024, file);
    let mut line = String::new();
    let mut lineno = 0usize;
    let read = |rd: &mut BufReader<File>, line: &mut String| -> Result<usize> {
        line.clear();
        rd.read_line(line)
            .map_err(|e| SimError::io("reading", path, e))
    };
    if read(&mut rd, &mut line)? == 0 {
        return Err(SimError::CsvEmpty {
            path: path.to_path_buf(),
        });
    }
    lineno += 1;
    let header = line.trim_end_matches(['\n', '\r']);
    let attitude = header == CSV_HEADER;
    if !attitude && header != CSV_HEADER_V1 {
        return Err(SimError::CsvHeader {
            path: path.to_path_buf(),
            header: header.to_owned(),
            expected: CSV_HEADER,
        });
    }
    let mut frames: Vec<Frame> = Vec::new();
    let mut agents_per_frame: Option<usize> = None;
    loop {
        if read(&mut rd, &mut line)? == 0 {
            break;
        }
        lineno += 1;
        let row = line.trim_end_matches(['\n', '\r']);
        if row.is_empty() {
            continue;
        }
        let (step, sample) = parse_row(row, attitude, path, lineno)?;
        let new_frame = frames.last().is_none_or(|f| f.step != step);
        if new_frame {
            if let Some(prev) = frames.last() {
                if step < prev.step {
                    return Err(SimError::CsvRowOrder {
                        path: path.to_path_buf(),
                        line: lineno,
                        step,
                        previous: prev.step,
                    });
                }
                let n = prev.agents.len();
                match agents_per_frame {
                    None => agents_per_frame = Some(n),
                    Some(m) if m != n => {
                        return Err(SimError::CsvStepAgents {
                            path: path.to_path_buf(),
                            line: lineno - 1,
                            step: prev.step,
                            agents: n,
                            first: m,
                        });
                    }
                    Some(_) => {}
                }
            }
            let cap = agents_per_frame.unwrap_or(0);
            frames.push(Frame {
                step,
                agents: Vec::with_capacity(cap),
            });
        }
        let nf = frames.len();
        let idx = frames[nf - 1].agents.len();
        if nf > 1 {
            let expect = frames[0].agents.get(idx).map(|a| a.id);
            if expect != Some(sample.id) {
                let path = path.to_path_buf();
                return Err(match expect {
                    Some(first) => SimError::CsvAgentId {
                        path,
                        line: lineno,
                        id: sample.id,
                        position: idx,
                        step,
                        first,
                    },
                    None => SimError::CsvExtraAgent {
                        path,
                        line: lineno,
                        step,
                        first: frames[0].agents.len(),
                    },
                });
            }
        }
        frames[nf - 1].agents.push(sample);
    }
    if let (Some(m), Some(last)) = (agents_per_frame, frames.last())
        && last.agents.len() != m
    {
        return Err(SimError::CsvStepAgents {
            path: path.to_path_buf(),
            line: lineno,
            step: last.step,
            agents: last.agents.len(),
            first: m,
        });
    }
    Ok(frames)
}

/// The fields of one data row at `line` of `path`, read in order.
struct Row<'a> {
    fields: std::str::Split<'a, char>,
    /// How many fields a row has.
    count: usize,
    path: &'a Path,
    line: usize,
}

impl Row<'_> {
    /// The next field, `name`, parsed.
    fn field<T: std::str::FromStr>(&mut self, name: &'static str) -> Result<T> {
        let text = self
            .fields
            .next()
            .map(str::trim)
            .ok_or_else(|| SimError::CsvMissingField {
                path: self.path.to_path_buf(),
                line: self.line,
                field: name,
                fields: self.count,
            })?;
        text.parse().map_err(|_| SimError::CsvNumber {
            path: self.path.to_path_buf(),
            line: self.line,
            field: name,
            value: text.to_owned(),
        })
    }
}

/// One data row at `line` of `path`: 13 fields, or the 11 of [`CSV_HEADER_V1`] when
/// `attitude` is false.
fn parse_row(row: &str, attitude: bool, path: &Path, line: usize) -> Result<(u32, AgentSample)> {
    let count = if attitude { 13 } else { 11 };
    let mut r = Row {
        fields: row.split(','),
        count,
        path,
        line,
    };
    let step: u32 = r.field("step")?;
    let id: u32 = r.field("id")?;
    let group: u16 = r.field("group")?;
    let pos: [f32; 3] = [r.field("x")?, r.field("y")?, r.field("z")?];
    let heading: [f32; 3] = [r.field("hx")?, r.field("hy")?, r.field("hz")?];
    let label: u8 = r.field("label")?;
    let motion: u8 = r.field("motion")?;
    let (roll, pitch): (f32, f32) = if attitude {
        (r.field("roll_deg")?, r.field("pitch_deg")?)
    } else {
        (0.0, 0.0)
    };
    if r.fields.next().is_some() {
        return Err(SimError::CsvExtraFields {
            path: path.to_path_buf(),
            line,
            fields: count,
        });
    }
    Ok((
        step,
        AgentSample {
            id,
            pos,
            heading,
            group,
            label,
            motion,
            roll,
            pitch,
        },
    ))
}

/// Default file name inside a run folder.
pub fn csv_path(dir: &Path) -> PathBuf {
    dir.join(super::TRAJECTORIES_CSV)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::testing::{read_error, temp_path};

    pub(crate) fn sample_frames(frames: usize, agents: usize) -> Vec<Frame> {
        let mut s = 0x1234_5678_u32;
        let mut rnd = move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            // Awkward floats: full mantissa, various exponents, signs.
            f32::from_bits((s & 0x807f_ffff) | (((s >> 23) % 40 + 107) << 23))
        };
        (0..frames)
            .map(|f| Frame {
                step: (f * 3) as u32,
                agents: (0..agents)
                    .map(|i| AgentSample {
                        id: i as u32,
                        group: (i % 3) as u16,
                        pos: [rnd(), rnd(), rnd()],
                        heading: [rnd(), rnd(), 0.0],
                        label: (i % 3) as u8,
                        motion: ((i + f) % 4) as u8,
                        roll: rnd(),
                        pitch: rnd(),
                    })
                    .collect(),
            })
            .collect()
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let dir = tempfile::tempdir().unwrap();
        let p = csv_path(dir.path());
        let mut frames = sample_frames(7, 13);
        frames[2].agents[4].pos = [f32::MIN_POSITIVE, -0.0, f32::MAX];
        frames[3].agents[0].heading = [1e-45, -3.4028235e38, 0.1];
        write_csv(&p, &frames).unwrap();
        let back = read_csv(&p).unwrap();
        assert_eq!(back.len(), frames.len());
        for (a, b) in frames.iter().zip(&back) {
            assert_eq!(a.step, b.step);
            for (x, y) in a.agents.iter().zip(&b.agents) {
                assert_eq!(x.id, y.id);
                assert_eq!(x.group, y.group);
                assert_eq!(x.label, y.label);
                assert_eq!(x.motion, y.motion);
                for k in 0..3 {
                    assert_eq!(x.pos[k].to_bits(), y.pos[k].to_bits());
                    assert_eq!(x.heading[k].to_bits(), y.heading[k].to_bits());
                }
                assert_eq!(x.roll.to_bits(), y.roll.to_bits());
                assert_eq!(x.pitch.to_bits(), y.pitch.to_bits());
            }
        }
        let text = std::fs::read_to_string(&p).unwrap();
        assert!(text.starts_with("step,id,group,x,y,z,hx,hy,hz,label,motion,roll_deg,pitch_deg\n"));
        assert_eq!(text.lines().count(), 1 + 7 * 13);
    }

    #[test]
    fn exact_text() {
        let (_dir, p) = temp_path("t.csv");
        let frames = vec![Frame {
            step: 4,
            agents: vec![AgentSample {
                id: 2,
                group: 1,
                pos: [0.1, -2.5, 0.0],
                heading: [1.0, 0.0, 0.0],
                label: 1,
                motion: 3,
                roll: -12.5,
                pitch: 16.25,
            }],
        }];
        write_csv(&p, &frames).unwrap();
        assert_eq!(
            std::fs::read_to_string(&p).unwrap(),
            "step,id,group,x,y,z,hx,hy,hz,label,motion,roll_deg,pitch_deg\n\
             4,2,1,0.1,-2.5,0,1,0,0,1,3,-12.5,16.25\n"
        );
    }

    #[test]
    fn files_without_the_attitude_columns_read_with_level_attitude() {
        let (_dir, p) = temp_path("v1.csv");
        std::fs::write(&p, format!("{CSV_HEADER_V1}\n4,2,1,0.1,-2.5,0,1,0,0,1,3\n")).unwrap();
        let f = read_csv(&p).unwrap();
        assert_eq!(f[0].agents[0].pos, [0.1, -2.5, 0.0]);
        assert_eq!((f[0].agents[0].roll, f[0].agents[0].pitch), (0.0, 0.0));
        // The new header wants the two columns.
        let msg = read_error(
            &p,
            format!("{CSV_HEADER}\n4,2,1,0.1,-2.5,0,1,0,0,1,3\n"),
            read_csv,
        );
        assert!(msg.contains("roll_deg"), "{msg}");
    }

    #[test]
    fn empty_frames_give_header_only() {
        let (_dir, p) = temp_path("e.csv");
        write_csv(&p, &[]).unwrap();
        assert!(read_csv(&p).unwrap().is_empty());
    }

    #[test]
    fn reader_errors_name_file_and_line() {
        let (dir, p) = temp_path("bad.csv");
        let bad_y = format!("{CSV_HEADER}\n0,0,0,1,2,3,1,0,0,0,1,0,0\n0,1,0,1,x,3,1,0,0,0,1,0,0\n");
        let msg = read_error(&p, bad_y, read_csv);
        assert!(msg.contains("bad.csv:3") && msg.contains("\"y\""), "{msg}");

        let msg = read_error(&p, "a,b\n", read_csv);
        assert!(msg.contains("bad.csv:1") && msg.contains("header"), "{msg}");

        // Second step lacks an agent.
        let short = format!(
            "{CSV_HEADER}\n0,0,0,1,2,3,1,0,0,0,1,0,0\n0,1,0,1,2,3,1,0,0,0,1,0,0\n\
             1,0,0,1,2,3,1,0,0,0,1,0,0\n"
        );
        let msg = read_error(&p, short, read_csv);
        assert!(msg.contains("step 1 has 1 agents"), "{msg}");

        // Too many fields.
        let long = format!("{CSV_HEADER}\n0,0,0,1,2,3,1,0,0,0,1,0,0,9\n");
        let msg = read_error(&p, long, read_csv);
        assert!(msg.contains("too many fields"), "{msg}");

        let msg = read_csv(dir.path().join("none.csv"))
            .unwrap_err()
            .to_string();
        assert!(msg.contains("none.csv"), "{msg}");
    }

    #[test]
    fn writer_rejects_inconsistent_frames() {
        let (_dir, p) = temp_path("w.csv");
        let mut frames = sample_frames(3, 4);
        frames[2].agents.pop();
        assert!(write_csv(&p, &frames).is_err());
        assert!(!p.exists());
    }
}
