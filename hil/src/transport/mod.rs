//! Byte links to a device, behind one trait: an in-memory duplex for tests
//! ([`memory_pair`]), a serial port for real boards and pseudo-terminals ([`SerialTransport`]),
//! TCP for QEMU's chardev sockets ([`TcpTransport`]), and a fault-injecting wrapper
//! ([`Faulty`]) that drops, flips, inserts and delays bytes.

mod fault;
mod memory;
mod serial;
mod tcp;

use std::time::Duration;

pub use fault::{FaultCounts, FaultSpec, Faulty};
pub use memory::{MemoryTransport, memory_pair};
pub use serial::SerialTransport;
#[cfg(unix)]
pub use serial::pty_pair;
pub use tcp::TcpTransport;

use crate::Result;

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
