//! The adapter and device the GPU backend runs on.

use std::collections::HashMap;
use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use serde::Serialize;

use crate::error::{Result, SimError};

/// What a user needs to know of the adapter a run used: printed by `swarm`, written in the
/// summary and the benchmark reports.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct AdapterSummary {
    /// The adapter's name (`NVIDIA H200`, `llvmpipe (LLVM 15.0.6, 256 bits)`).
    pub name: String,
    /// The graphics API wgpu drives it through (`Vulkan`, `Metal`, `Dx12`).
    pub backend: String,
    /// Discrete, integrated, virtual GPU, or a CPU (lavapipe).
    pub device_type: String,
    /// The driver and its version.
    pub driver: String,
}

impl fmt::Display for AdapterSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ({}, {}, {})",
            self.name, self.backend, self.device_type, self.driver
        )
    }
}

/// A wgpu device and its queue, on the adapter wgpu prefers (high performance first).
///
/// One device serves the whole process ([`Gpu::shared`]): every engine, test and kernel
/// clones it, and a kernel is compiled once per device (`Gpu::compiled`). A device per
/// engine cost each engine a new instance and a new compilation of every kernel (20-35 s on
/// lavapipe), and the driver's per-device memory with it.
#[derive(Clone)]
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    info: AdapterSummary,
    timestamps: bool,
    /// Set by the device-lost callback: [`Gpu::shared`] opens a new device in its place.
    lost: Arc<AtomicBool>,
    /// Pipelines compiled on this device, by composed source and entry point.
    kernels: Arc<Mutex<HashMap<KernelKey, Compiled>>>,
}

/// A composed WGSL source and one of its entry points.
type KernelKey = (String, String);

/// A compiled entry point: its pipeline and the bindings of group 0 it uses.
#[derive(Clone)]
pub(crate) struct Compiled {
    pub(crate) pipeline: wgpu::ComputePipeline,
    pub(crate) bindings: Arc<[u32]>,
}

/// The process's device, once opened.
static SHARED: Mutex<Option<Gpu>> = Mutex::new(None);

/// What to install when wgpu finds no adapter.
const INSTALL_HINT: &str = "install a Vulkan driver: on Debian or Ubuntu `apt-get install \
     mesa-vulkan-drivers libvulkan1` (Mesa's lavapipe runs the GPU backend on the CPU when \
     there is no GPU), elsewhere your GPU vendor's driver; WGPU_BACKEND=vulkan|metal|dx12|gl \
     picks an API";

impl Gpu {
    /// The process's device: opened by the first call on the preferred adapter, with the
    /// adapter's own limits (so the largest swarms fit) and timestamp queries where the
    /// adapter has them; shared by every later call (a clone: the same device, queue and
    /// compiled kernels); opened anew only if the device was lost. An error is not kept: the
    /// next call tries again. wgpu's environment variables apply (`WGPU_BACKEND`,
    /// `WGPU_ADAPTER_NAME`, `WGPU_POWER_PREF`); without `WGPU_BACKEND` only the primary APIs
    /// are tried (Vulkan, Metal, DX12).
    ///
    /// # Errors
    ///
    /// [`SimError::NoGpu`] naming what to install when there is no adapter,
    /// [`SimError::GpuDevice`] when the adapter refuses a device.
    pub fn shared() -> Result<Gpu> {
        let mut shared = SHARED.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(gpu) = shared.as_ref().filter(|g| !g.lost.load(Ordering::Acquire)) {
            return Ok(gpu.clone());
        }
        let gpu = Gpu::open()?;
        *shared = Some(gpu.clone());
        Ok(gpu)
    }

    /// A new device on the preferred adapter ([`Gpu::shared`] says how it is chosen).
    fn open() -> Result<Gpu> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        if std::env::var_os("WGPU_BACKEND").is_none() {
            desc.backends = wgpu::Backends::PRIMARY;
        }
        let instance = wgpu::Instance::new(desc);
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::from_env()
                .unwrap_or(wgpu::PowerPreference::HighPerformance),
            ..Default::default()
        };
        let adapter = pollster::block_on(instance.request_adapter(&options)).map_err(|source| {
            SimError::NoGpu {
                source,
                hint: INSTALL_HINT,
            }
        })?;
        let a = adapter.get_info();
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let required_features = if timestamps {
            wgpu::Features::TIMESTAMP_QUERY
        } else {
            wgpu::Features::empty()
        };
        let device_desc = wgpu::DeviceDescriptor {
            label: Some("swarm-sim"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        };
        let (device, queue) =
            pollster::block_on(adapter.request_device(&device_desc)).map_err(|source| {
                SimError::GpuDevice {
                    adapter: a.name.clone(),
                    source,
                }
            })?;
        let lost = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&lost);
        device.set_device_lost_callback(move |_, _| flag.store(true, Ordering::Release));
        Ok(Gpu {
            device,
            queue,
            lost,
            kernels: Arc::default(),
            info: AdapterSummary {
                name: a.name,
                backend: format!("{:?}", a.backend),
                device_type: format!("{:?}", a.device_type),
                driver: [a.driver, a.driver_info]
                    .into_iter()
                    .filter(|s| !s.is_empty())
                    .collect::<Vec<_>>()
                    .join(" "),
            },
            timestamps,
        })
    }

    /// The pipeline of entry point `entry` of the composed source `source`: compiled by
    /// `compile` the first time this device sees them, the same pipeline afterwards. Two
    /// threads asking at once may both compile; one result is kept.
    ///
    /// # Errors
    ///
    /// What `compile` returns (a failure is not kept).
    pub(crate) fn compiled(
        &self,
        source: &str,
        entry: &str,
        compile: impl FnOnce() -> Result<Compiled>,
    ) -> Result<Compiled> {
        let key = (source.to_owned(), entry.to_owned());
        let cache = || self.kernels.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(c) = cache().get(&key) {
            return Ok(c.clone());
        }
        let c = compile()?;
        Ok(cache().entry(key).or_insert(c).clone())
    }

    /// The adapter.
    pub fn info(&self) -> &AdapterSummary {
        &self.info
    }

    /// Whether kernels can be timed with timestamp queries.
    pub fn has_timestamps(&self) -> bool {
        self.timestamps
    }

    /// The largest storage buffer one binding may hold, in bytes.
    pub fn max_binding(&self) -> u64 {
        self.device.limits().max_storage_buffer_binding_size
    }

    /// Waits until the GPU has finished everything submitted.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuLost`] if the device was lost or the wait timed out.
    pub fn wait(&self) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|source| SimError::GpuLost { source })
    }
}
