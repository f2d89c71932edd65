//! Serial ports through the `serialport` crate: real boards (`/dev/ttyUSB0`, `COM3`) and
//! pseudo-terminals (QEMU's `-serial pty`, or a pair made by [`pty_pair`]).

use std::io::{ErrorKind, Read, Write};
use std::time::Duration;

use serialport::SerialPort;

use super::{Transport, received};
use crate::{HilError, Result};

/// An open serial port.
pub struct SerialTransport {
    port: Box<dyn SerialPort>,
    path: String,
    timeout: Duration,
}

impl std::fmt::Debug for SerialTransport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SerialTransport")
            .field("path", &self.path)
            .finish()
    }
}

impl SerialTransport {
    /// Opens `path` at `baud` bits/s, 8N1, no flow control, raw.
    pub fn open(path: &str, baud: u32) -> Result<Self> {
        let timeout = Duration::from_millis(10);
        let port = serialport::new(path, baud)
            .data_bits(serialport::DataBits::Eight)
            .parity(serialport::Parity::None)
            .stop_bits(serialport::StopBits::One)
            .flow_control(serialport::FlowControl::None)
            .timeout(timeout)
            .open()
            .map_err(|source| HilError::Serial {
                path: path.to_string(),
                source,
            })?;
        Ok(Self::from_port(port, path.to_string()))
    }

    fn from_port(port: Box<dyn SerialPort>, path: String) -> Self {
        SerialTransport {
            port,
            path,
            timeout: Duration::from_millis(10),
        }
    }
}

impl Transport for SerialTransport {
    fn send(&mut self, bytes: &[u8]) -> Result<()> {
        // A slow reader fills the line's buffer and writes time out: keep going while bytes
        // move, give up after ten seconds without progress.
        let mut rest = bytes;
        let mut stalled = std::time::Instant::now();
        while !rest.is_empty() {
            match self.port.write(rest) {
                Ok(0) => return Err(HilError::Closed(self.path.clone())),
                Ok(n) => {
                    rest = &rest[n..];
                    stalled = std::time::Instant::now();
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted
                    ) && stalled.elapsed() < Duration::from_secs(10) => {}
                Err(e) => return Err(HilError::io(&self.path, "sending", e)),
            }
        }
        self.port
            .flush()
            .map_err(|e| HilError::io(&self.path, "sending", e))
    }

    fn recv(&mut self, buf: &mut [u8], timeout: Duration) -> Result<usize> {
        let t = timeout.max(Duration::from_micros(100));
        if t != self.timeout {
            self.port
                .set_timeout(t)
                .map_err(|source| HilError::Serial {
                    path: self.path.clone(),
                    source,
                })?;
            self.timeout = t;
        }
        received(&self.path, self.port.read(buf))
    }

    fn name(&self) -> String {
        self.path.clone()
    }
}

/// A pseudo-terminal pair: `(device end, host end)`. The device end is the master side (for a
/// soft device); the host end is the terminal, opened by its path with
/// [`SerialTransport::open`] exactly like a real board's port. Unix only.
#[cfg(unix)]
pub fn pty_pair(baud: u32) -> Result<(SerialTransport, SerialTransport)> {
    let (master, slave) = serialport::TTYPort::pair().map_err(|source| HilError::Serial {
        path: "pseudo-terminal".into(),
        source,
    })?;
    let path = slave
        .name()
        .ok_or_else(|| HilError::Unsupported("the pseudo-terminal has no path".into()))?;
    // The pair's own terminal handle holds an exclusive lock: close it, then open the terminal
    // by its path (the master keeps it alive).
    drop(slave);
    let host = SerialTransport::open(&path, baud)?;
    let device = SerialTransport::from_port(Box::new(master), format!("{path} (device end)"));
    Ok((device, host))
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use crate::transport::recv_exactly;

    #[test]
    fn a_pty_pair_carries_raw_bytes_both_ways() {
        let (mut device, mut host) = pty_pair(115_200).unwrap();
        // Every byte value, the frame delimiter and terminal control characters included.
        let all: Vec<u8> = (0..=255u8).collect();
        host.send(&all).unwrap();
        let timeout = Duration::from_secs(2);
        assert_eq!(recv_exactly(&mut device, all.len(), timeout), all);
        device.send(&all).unwrap();
        assert_eq!(recv_exactly(&mut host, all.len(), timeout), all);
    }
}
