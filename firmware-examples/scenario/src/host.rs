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

/// A [`Meter`](crate::Meter) that counts calls (one tick each): the cost runs' host tests.
#[cfg(test)]
pub(crate) struct Calls;

#[cfg(test)]
impl crate::Meter for Calls {
    fn measure<I, R>(&mut self, input: I, f: impl FnOnce(I) -> R) -> (R, u32) {
        (f(input), 1)
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

/// The build script of a node image: passes its `memory.x` to the linker (`-Tlink.x`) and writes
/// the expected-decision tables `expected_f32.rs` and, when given, `expected_fixed.rs` to
/// `OUT_DIR`. `what` names the scenario in the tables' doc comments.
pub fn node_build_script(what: &str, f32_words: &[u32], fixed_words: Option<&[u32]>) {
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::copy("memory.x", out.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    let header =
        |scalar: &str| format!("Host-computed decision words of the {what}, scalar {scalar}.");
    write_table(
        &out.join("expected_f32.rs"),
        "EXPECTED",
        &header("f32 (libm)"),
        f32_words,
    );
    if let Some(words) = fixed_words {
        write_table(
            &out.join("expected_fixed.rs"),
            "EXPECTED",
            &header("Fx (I16F16)"),
            words,
        );
    }
}

/// Writes a node's `build.rs` `main`: runs `fw_scenario::$model::run` (`$model`: `ant`, `bee` or
/// `fly`) here on the host in `f32` and, with the node's feature `fixed`, in `Fx`, and passes the
/// words to [`node_build_script`] (`$what` names the scenario in the tables' doc comments).
#[macro_export]
macro_rules! node_build_script {
    ($model:ident, $what:literal) => {
        fn main() {
            let f32_words = $crate::host::collect(|s| $crate::$model::run::<f32>(s));
            #[cfg(feature = "fixed")]
            let fixed_words = Some($crate::host::collect(|s| {
                $crate::$model::run::<$crate::swarm_core::Fx>(s)
            }));
            #[cfg(not(feature = "fixed"))]
            let fixed_words: Option<Vec<u32>> = None;
            $crate::host::node_build_script($what, &f32_words, fixed_words.as_deref());
        }
    };
}
