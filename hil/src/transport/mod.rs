//! Byte links to a device, behind one trait: an in-memory duplex for tests
//! ([`memory_pair`]), a serial port for real boards and pseudo-terminals ([`SerialTransport`]),
//! TCP for QEMU's chardev sockets ([`TcpTransport`]), and a fault-injecting wrapper
//! ([`Faulty`]) that drops, flips, inserts and delays bytes.

mod fault;
mod memory;
mod serial;
mod tcp;

use std::io::ErrorKind;
use std::time::Duration;

pub use fault::{FaultCounts, FaultSpec, Faulty};
pub use memory::{MemoryTransport, memory_pair};
pub use serial::SerialTransport;
#[cfg(unix)]
pub use serial::pty_pair;
pub use tcp::TcpTransport;

use crate::{HilError, Result};

/// A full-duplex byte link. Frames are not its business: it moves bytes.
pub trait Transport: Send {
    /// Sends all of `bytes`.
    fn send(&mut self, bytes: &[u8]) -> Result<()>;
    /// Receives what has arrived into `buf`, waiting up to `timeout` for the first byte;
    /// `Ok(0)` if nothing came in that time.
    fn recv(&mut self, buf: &mut [u8], timeout: Duration) -> Result<usize>;
    /// A short name for messages (`memory`, the port path, the address).
    fn name(&self) -> String;
}

impl<T: Transport + ?Sized> Transport for Box<T> {
    fn send(&mut self, bytes: &[u8]) -> Result<()> {
        (**self).send(bytes)
    }
    fn recv(&mut self, buf: &mut [u8], timeout: Duration) -> Result<usize> {
        (**self).recv(buf, timeout)
    }
    fn name(&self) -> String {
        (**self).name()
    }
}

/// What a read from the link `name` brought, as [`Transport::recv`] reports it: a timeout or
/// an interrupted read is `Ok(0)` (nothing came), another error names the link.
fn received(name: &str, read: std::io::Result<usize>) -> Result<usize> {
    match read {
        Ok(n) => Ok(n),
        Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock) => Ok(0),
        Err(e) if e.kind() == ErrorKind::Interrupted => Ok(0),
        Err(e) => Err(HilError::io(name, "receiving", e)),
    }
}

/// Receives from `link` until `len` bytes have come, in small chunks, each within `timeout`
/// (a test helper: panics when one times out).
#[cfg(test)]
fn recv_exactly(link: &mut impl Transport, len: usize, timeout: Duration) -> Vec<u8> {
    let mut buf = [0u8; 4];
    let mut got = Vec::new();
    while got.len() < len {
        let n = link.recv(&mut buf, timeout).unwrap();
        assert!(n > 0, "timed out after {} bytes", got.len());
        got.extend_from_slice(&buf[..n]);
    }
    got
}
