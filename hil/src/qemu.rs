//! QEMU: start a firmware image on its emulated board with the UART on a pseudo-terminal, so
//! the mirror talks to it through the same serial-port transport a real board uses; reset the
//! board through QEMU's monitor; read an image's flash and RAM from its ELF. QEMU is stopped
//! whatever happens: when [`Qemu`] is dropped (errors included), and on Linux when the harness
//! itself dies (the child gets `SIGKILL`); Ctrl-C reaches QEMU with the harness, as both are in
//! the terminal's foreground process group.

use std::io::{BufRead, BufReader, Write};
use std::os::unix::net::UnixStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use object::{Object, ObjectSection};

use crate::mirror::ImageSize;
use crate::{HilError, Result};

/// A QEMU board a firmware image runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Board {
    /// `-machine`.
    pub machine: &'static str,
    /// `-cpu`.
    pub cpu: &'static str,
    /// The Rust target the image is built for.
    pub triple: &'static str,
}

/// The board of a node image: `ant-node*` on `lm3s6965evb`, `bee-node*` and `fly-node*` on
/// `mps2-an386`.
pub fn board_of(image: &str) -> Option<Board> {
    if image.starts_with("ant-node") {
        Some(Board {
            machine: "lm3s6965evb",
            cpu: "cortex-m3",
            triple: "thumbv7m-none-eabi",
        })
    } else if image.starts_with("bee-node") || image.starts_with("fly-node") {
        Some(Board {
            machine: "mps2-an386",
            cpu: "cortex-m4",
            triple: "thumbv7em-none-eabihf",
        })
    } else {
        None
    }
}

/// Reads [`ImageSize`] from the ELF at `path`.
pub fn image_size(path: &Path) -> Result<ImageSize> {
    let bytes =
        std::fs::read(path).map_err(|e| HilError::io(&path.display().to_string(), "reading", e))?;
    let elf = object::File::parse(&*bytes).map_err(|e| HilError::Image {
        path: path.to_path_buf(),
        problem: format!("not an ELF file: {e}"),
    })?;
    let size = |name: &str| elf.section_by_name(name).map_or(0, |s| s.size());
    Ok(ImageSize {
        flash: size(".vector_table") + size(".text") + size(".rodata") + size(".data"),
        ram: size(".data") + size(".bss") + size(".uninit"),
    })
}

/// A running QEMU.
pub struct Qemu {
    child: Child,
    /// The pseudo-terminal of the board's UART.
    pub pty: String,
    monitor: PathBuf,
    _dir: tempfile::TempDir,
}

impl Qemu {
    /// Starts `elf` on `board` with UART0 on a new pseudo-terminal and the monitor on a Unix
    /// socket; returns once QEMU has said which terminal it is.
    pub fn start(elf: &Path, board: &Board) -> Result<Qemu> {
        if !elf.is_file() {
            return Err(HilError::Image {
                path: elf.to_path_buf(),
                problem: "no such image (build it with firmware-examples/build.sh)".into(),
            });
        }
        let dir = tempfile::tempdir().map_err(|e| HilError::io("qemu", "making a folder", e))?;
        let monitor = dir.path().join("monitor.sock");
        let mut cmd = Command::new("qemu-system-arm");
        cmd.args(["-machine", board.machine, "-cpu", board.cpu, "-nographic"])
            .args(["-serial", "pty"])
            .arg("-monitor")
            .arg(format!("unix:{},server=on,wait=off", monitor.display()))
            .arg("-kernel")
            .arg(elf)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        #[cfg(target_os = "linux")]
        {
            use std::os::unix::process::CommandExt;
            // SAFETY: prctl is async-signal-safe; nothing else runs between fork and exec.
            #[allow(unsafe_code)]
            unsafe {
                cmd.pre_exec(|| {
                    libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL);
                    Ok(())
                });
            }
        }
        let mut child = cmd.spawn().map_err(|e| {
            HilError::io(
                "qemu-system-arm",
                "starting (is it installed? apt-get install qemu-system-arm)",
                e,
            )
        })?;
        // QEMU names the terminal on stdout or stderr: "char device redirected to /dev/pts/N".
        let (tx, rx) = mpsc::channel();
        for pipe in [
            child
                .stdout
                .take()
                .map(|p| Box::new(p) as Box<dyn std::io::Read + Send>),
            child
                .stderr
                .take()
                .map(|p| Box::new(p) as Box<dyn std::io::Read + Send>),
        ]
        .into_iter()
        .flatten()
        {
            let tx = tx.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(pipe).lines().map_while(|l| l.ok()) {
                    if tx.send(line).is_err() {
                        // Nobody listens any more: keep draining so QEMU never blocks.
                        continue;
                    }
                }
            });
        }
        drop(tx);
        let mut seen = Vec::new();
        let pty = loop {
            match rx.recv_timeout(Duration::from_secs(10)) {
                Ok(line) => {
                    if let Some(p) = line
                        .split("redirected to ")
                        .nth(1)
                        .and_then(|r| r.split_whitespace().next())
                    {
                        break p.to_string();
                    }
                    seen.push(line);
                }
                Err(_) => {
                    let _ = child.kill();
                    let _ = child.wait();
                    return Err(HilError::Qemu(seen.join(" | ")));
                }
            }
        };
        Ok(Qemu {
            child,
            pty,
            monitor,
            _dir: dir,
        })
    }

    /// Resets the emulated board (the monitor's `system_reset`).
    pub fn reset(&self) -> Result<()> {
        let io = |op, e| HilError::io("qemu monitor", op, e);
        let mut s = UnixStream::connect(&self.monitor).map_err(|e| io("connecting", e))?;
        s.write_all(b"system_reset\n")
            .map_err(|e| io("sending", e))?;
        // Give the monitor time to act before the socket closes.
        std::thread::sleep(Duration::from_millis(50));
        Ok(())
    }

    /// Whether QEMU is still running.
    pub fn running(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }
}

impl Drop for Qemu {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodes_map_to_their_boards() {
        assert_eq!(board_of("ant-node-fixed").unwrap().machine, "lm3s6965evb");
        assert_eq!(
            board_of("bee-node").unwrap().triple,
            "thumbv7em-none-eabihf"
        );
        assert_eq!(board_of("fly-node-fixed").unwrap().machine, "mps2-an386");
        assert_eq!(board_of("fly-node").unwrap().cpu, "cortex-m4");
        assert!(board_of("wasp-node").is_none());
    }

    #[test]
    fn a_missing_image_is_named() {
        let b = board_of("ant-node").unwrap();
        let e = Qemu::start(Path::new("/nonexistent/ant-node"), &b)
            .err()
            .unwrap();
        assert!(e.to_string().contains("/nonexistent/ant-node"), "{e}");
    }
}

/// A mirror run against a firmware image in QEMU.
#[derive(Clone, Debug)]
pub struct QemuRun {
    /// The image name (`ant-node`, `ant-node-fixed`, `bee-node`, `bee-node-fixed`, `fly-node`,
    /// `fly-node-fixed`).
    pub image: String,
    /// Its ELF file.
    pub elf: PathBuf,
    /// Random bytes sent to the board's UART before the session (it must survive them).
    pub garbage: usize,
    /// Reset the board through the monitor before this step.
    pub reset_at: Option<u32>,
    /// Faults injected on the link to the board (both directions).
    pub faults: crate::transport::FaultSpec,
    /// Seed of the injected faults.
    pub fault_seed: u64,
}

impl QemuRun {
    /// The default ELF of `image`, under `root` (the repository).
    pub fn elf_of(root: &Path, image: &str) -> Option<PathBuf> {
        board_of(image).map(|b| {
            root.join("firmware-examples/target")
                .join(b.triple)
                .join("release")
                .join(image)
        })
    }
}

/// Starts the image in QEMU, sends the garbage, then runs `mirror` on a client over the
/// board's pseudo-terminal (opened like a real board's port), resetting the board at the
/// step asked; stops QEMU; adds the image's size to the report.
pub fn mirror_in_qemu(
    run: &QemuRun,
    client: crate::ClientOptions,
    mirror: impl FnOnce(
        &mut crate::Client<crate::transport::Faulty<crate::transport::SerialTransport>>,
        &mut dyn FnMut(u32) -> Result<()>,
    ) -> Result<crate::mirror::MirrorReport>,
) -> Result<crate::mirror::MirrorReport> {
    use crate::Transport;
    let board = board_of(&run.image).ok_or_else(|| HilError::UnknownFirmware(run.image.clone()))?;
    let size = image_size(&run.elf)?;
    let qemu = Qemu::start(&run.elf, &board)?;
    let mut link = crate::transport::SerialTransport::open(&qemu.pty, 115_200)?;
    if run.garbage > 0 {
        // Reproducible noise, sent in UART-sized chunks.
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let noise: Vec<u8> = (0..run.garbage)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 24) as u8
            })
            .collect();
        for chunk in noise.chunks(256) {
            link.send(chunk)?;
        }
    }
    let link = crate::transport::Faulty::new(link, run.faults, run.fault_seed);
    let mut client = crate::Client::new(link, client);
    let reset_at = run.reset_at;
    let mut hook = |step: u32| {
        if Some(step) == reset_at {
            qemu.reset()?;
        }
        Ok(())
    };
    let result = mirror(&mut client, &mut hook);
    let faults = (!run.faults.is_clean()).then(|| client.link_mut().counts());
    let transport = format!("{} ({} in QEMU {})", qemu.pty, run.image, board.machine);
    let add = |r: &mut crate::mirror::MirrorReport| {
        r.image = Some(size);
        r.transport = transport.clone();
        r.faults = faults;
    };
    match result {
        Ok(mut r) => {
            add(&mut r);
            Ok(r)
        }
        Err(e) => Err(e.with_report(add)),
    }
}
