//! An in-memory duplex link: two ends, each one's sends are the other's receives.

use std::collections::VecDeque;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError, channel};
use std::time::Duration;

use super::Transport;
use crate::{HilError, Result};

/// One end of an in-memory link (see [`memory_pair`]).
#[derive(Debug)]
pub struct MemoryTransport {
    tx: Sender<Vec<u8>>,
    rx: Receiver<Vec<u8>>,
    /// Bytes received but not yet handed out.
    pending: VecDeque<u8>,
}

/// Two connected ends.
pub fn memory_pair() -> (MemoryTransport, MemoryTransport) {
    let (a_tx, b_rx) = channel();
    let (b_tx, a_rx) = channel();
    let end = |tx, rx| MemoryTransport {
        tx,
        rx,
        pending: VecDeque::new(),
    };
    (end(a_tx, a_rx), end(b_tx, b_rx))
}

impl Transport for MemoryTransport {
    fn send(&mut self, bytes: &[u8]) -> Result<()> {
        self.tx
            .send(bytes.to_vec())
            .map_err(|_| HilError::Closed(self.name()))
    }

    fn recv(&mut self, buf: &mut [u8], timeout: Duration) -> Result<usize> {
        if self.pending.is_empty() {
            match self.rx.recv_timeout(timeout) {
                Ok(chunk) => self.pending.extend(chunk),
                Err(RecvTimeoutError::Timeout) => return Ok(0),
                Err(RecvTimeoutError::Disconnected) => return Err(HilError::Closed(self.name())),
            }
        }
        // Take whatever else has already arrived, without waiting.
        while self.pending.len() < buf.len() {
            match self.rx.try_recv() {
                Ok(chunk) => self.pending.extend(chunk),
                Err(TryRecvError::Empty | TryRecvError::Disconnected) => break,
            }
        }
        let n = buf.len().min(self.pending.len());
        for (b, p) in buf.iter_mut().zip(self.pending.drain(..n)) {
            *b = p;
        }
        Ok(n)
    }

    fn name(&self) -> String {
        "memory".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transport::recv_exactly;

    #[test]
    fn bytes_cross_in_order_and_a_quiet_link_times_out() {
        let (mut a, mut b) = memory_pair();
        a.send(b"hello ").unwrap();
        a.send(b"world").unwrap();
        let got = recv_exactly(&mut b, 11, Duration::from_millis(100));
        assert_eq!(got, b"hello world");
        let mut buf = [0u8; 4];
        assert_eq!(b.recv(&mut buf, Duration::from_millis(5)).unwrap(), 0);
        drop(a);
        assert!(matches!(
            b.recv(&mut buf, Duration::from_millis(5)),
            Err(HilError::Closed(_))
        ));
    }
}
