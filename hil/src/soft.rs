//! The soft device: the `swarm-core` device endpoint running on the host, on any transport, so
//! a team can try the loop before any hardware exists (and the tests have a device).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

use swarm_core::wire::Endpoint;

use crate::transport::Transport;
use crate::{HilError, Result};

/// Serves `device` (a [`DeviceEndpoint`](swarm_core::wire::DeviceEndpoint) of any model) on
/// `link` until `stop` is set or the link closes; returns the endpoint (with its counters).
pub fn serve<E: Endpoint + ?Sized, T: Transport>(
    mut device: Box<E>,
    mut link: T,
    stop: &AtomicBool,
) -> Result<Box<E>> {
    let mut buf = [0u8; 4096];
    while !stop.load(Ordering::Relaxed) {
        let n = match link.recv(&mut buf, Duration::from_millis(20)) {
            Ok(n) => n,
            Err(HilError::Closed(_)) => break,
            Err(e) => return Err(e),
        };
        let mut out = Vec::new();
        device.serve_all(&buf[..n], &mut |reply| out.extend_from_slice(reply));
        if !out.is_empty() {
            match link.send(&out) {
                Ok(()) => {}
                Err(HilError::Closed(_)) => break,
                Err(e) => return Err(e),
            }
        }
    }
    Ok(device)
}

/// A soft device serving on its own thread; stopped (and joined) on drop.
pub struct SoftDevice<E: Send + 'static> {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<Result<E>>>,
}

impl<E: Send + 'static> SoftDevice<E> {
    /// Starts `run(stop)` on a thread.
    pub fn spawn(run: impl FnOnce(&AtomicBool) -> Result<E> + Send + 'static) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::spawn(move || run(&flag));
        SoftDevice {
            stop,
            thread: Some(thread),
        }
    }

    /// Stops the device and returns what its thread returned.
    pub fn stop(mut self) -> Result<E> {
        self.stop.store(true, Ordering::Relaxed);
        match self.thread.take().map(JoinHandle::join) {
            Some(Ok(r)) => r,
            _ => Err(HilError::SoftDevicePanicked),
        }
    }
}

impl<E: Send + 'static> Drop for SoftDevice<E> {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}
