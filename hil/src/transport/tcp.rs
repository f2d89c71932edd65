//! TCP: QEMU's `-serial tcp:HOST:PORT,server` chardev, or any socket bridge to a device.

use std::io::{Read, Write};
use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;

use super::{Transport, received};
use crate::{HilError, Result};

/// A TCP connection to a device.
#[derive(Debug)]
pub struct TcpTransport {
    stream: TcpStream,
    addr: String,
}

impl TcpTransport {
    /// Connects to `addr` (`host:port`), waiting at most `timeout`.
    pub fn connect(addr: &str, timeout: Duration) -> Result<Self> {
        let io = |op, e| HilError::io(addr, op, e);
        let sock = addr
            .to_socket_addrs()
            .map_err(|e| io("resolving", e))?
            .next()
            .ok_or_else(|| HilError::Unsupported(format!("{addr}: no address")))?;
        let stream = TcpStream::connect_timeout(&sock, timeout).map_err(|e| io("connecting", e))?;
        stream.set_nodelay(true).map_err(|e| io("setting up", e))?;
        Ok(TcpTransport {
            stream,
            addr: addr.to_string(),
        })
    }

    /// Wraps a connected stream.
    pub fn from_stream(stream: TcpStream) -> Result<Self> {
        let addr = stream
            .peer_addr()
            .map(|a| a.to_string())
            .unwrap_or_else(|_| "tcp".into());
        stream
            .set_nodelay(true)
            .map_err(|e| HilError::io(&addr, "setting up", e))?;
        Ok(TcpTransport { stream, addr })
    }
}

impl Transport for TcpTransport {
    fn send(&mut self, bytes: &[u8]) -> Result<()> {
        self.stream
            .write_all(bytes)
            .map_err(|e| HilError::io(&self.addr, "sending", e))
    }

    fn recv(&mut self, buf: &mut [u8], timeout: Duration) -> Result<usize> {
        // A zero timeout means "block forever" to the socket: wait at least a microsecond.
        let t = timeout.max(Duration::from_micros(1));
        self.stream
            .set_read_timeout(Some(t))
            .map_err(|e| HilError::io(&self.addr, "setting up", e))?;
        match self.stream.read(buf) {
            Ok(0) if !buf.is_empty() => Err(HilError::Closed(self.addr.clone())),
            read => received(&self.addr, read),
        }
    }

    fn name(&self) -> String {
        self.addr.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transport::recv_exactly;
    use std::net::TcpListener;

    #[test]
    fn bytes_cross_a_socket_and_a_quiet_one_times_out() {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = listener.local_addr().unwrap().to_string();
        let server = std::thread::spawn(move || {
            let (s, _) = listener.accept().unwrap();
            let mut t = TcpTransport::from_stream(s).unwrap();
            t.send(b"ping").unwrap();
            let mut buf = [0u8; 8];
            let n = t.recv(&mut buf, Duration::from_secs(5)).unwrap();
            assert_eq!(&buf[..n], b"pong");
        });
        let mut c = TcpTransport::connect(&addr, Duration::from_secs(5)).unwrap();
        assert_eq!(recv_exactly(&mut c, 4, Duration::from_secs(5)), b"ping");
        c.send(b"pong").unwrap();
        server.join().unwrap();
        let mut buf = [0u8; 8];
        assert!(matches!(
            c.recv(&mut buf, Duration::from_millis(200)),
            Err(HilError::Closed(_)) | Ok(0)
        ));
    }
}
