//! The adapter and device the GPU backend runs on.

use std::fmt;

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
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    info: AdapterSummary,
    timestamps: bool,
}

/// What to install when wgpu finds no adapter.
const INSTALL_HINT: &str = "install a Vulkan driver: on Debian or Ubuntu `apt-get install \
     mesa-vulkan-drivers libvulkan1` (Mesa's lavapipe runs the GPU backend on the CPU when \
     there is no GPU), elsewhere your GPU vendor's driver; WGPU_BACKEND=vulkan|metal|dx12|gl \
     picks an API";

impl Gpu {
    /// The preferred adapter's device, with the adapter's own limits (so the largest
    /// swarms fit) and timestamp queries where the adapter has them. wgpu's environment
    /// variables apply (`WGPU_BACKEND`, `WGPU_ADAPTER_NAME`, `WGPU_POWER_PREF`); without
    /// `WGPU_BACKEND` only the primary APIs are tried (Vulkan, Metal, DX12).
    ///
    /// # Errors
    ///
    /// [`SimError::NoGpu`] naming what to install when there is no adapter,
    /// [`SimError::GpuDevice`] when the adapter refuses a device.
    pub fn new() -> Result<Gpu> {
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
        Ok(Gpu {
            device,
            queue,
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
