//! Build-script helpers (feature `std`): run a scenario on the host and write its words as a
//! Rust table for the firmware to `include!`.

use std::fmt::Write as _;
use std::path::Path;

/// A [`Sink`](crate::Sink) that records every word.
#[derive(Default)]
pub struct Recorder(pub Vec<u32>);

impl crate::Sink for Recorder {
    fn put(&mut self, w: u32) {
        self.0.push(w);
    }
}

/// Collects every word a scenario produces.
pub fn collect(run: impl FnOnce(&mut Recorder)) -> Vec<u32> {
    let mut r = Recorder::default();
    run(&mut r);
    r.0
}

/// Writes `pub static <name>: [u32; N] = [...];` to `path` (only if it changed, so cargo does
/// not relink for nothing). `header` becomes a doc comment.
pub fn write_table(path: &Path, name: &str, header: &str, words: &[u32]) {
    let mut s = String::new();
    for line in header.lines() {
        let _ = writeln!(s, "/// {line}");
    }
    let _ = writeln!(s, "pub static {name}: [u32; {}] = [", words.len());
    for chunk in words.chunks(6) {
        s.push_str("   ");
        for w in chunk {
            let _ = write!(s, " {w:#010x},");
        }
        s.push('\n');
    }
    s.push_str("];\n");
    if std::fs::read_to_string(path).ok().as_deref() != Some(s.as_str()) {
        std::fs::write(path, s).unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
    }
}
