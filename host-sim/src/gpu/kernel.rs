//! Compiled compute kernels, storage buffers, and reading results back.
//!
//! [`map_words`] runs a WGSL function over many inputs and returns its outputs: the harness of
//! the bit-for-bit tests of every WGSL helper against its Rust original.

use std::sync::Arc;

use wgpu::util::DeviceExt;

use super::Gpu;
use super::context::Compiled;
use super::shaders::{self, Module, WORKGROUP};
use crate::error::{Result, SimError};

/// Compiles entry point `entry` of the composed `source` on `gpu`'s device.
fn compile(gpu: &Gpu, name: &'static str, source: &str, entry: &str) -> Result<Compiled> {
    let bindings = bindings_used(name, source, entry)?;
    let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(name),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
    let pipeline = gpu
        .device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(name),
            layout: None,
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
    if let Some(e) = pollster::block_on(scope.pop()) {
        return Err(SimError::GpuShader {
            kernel: name,
            message: e.to_string(),
        });
    }
    Ok(Compiled {
        pipeline,
        bindings: bindings.into(),
    })
}

/// A compute pipeline: one entry point of a composed WGSL source.
pub struct Kernel {
    name: &'static str,
    pipeline: wgpu::ComputePipeline,
    /// The bindings of group 0 the entry point uses (its layout's; naga's analysis).
    bindings: Arc<[u32]>,
}

/// The bindings of group 0 that entry point `entry` of `source` uses, directly or through the
/// functions it calls.
fn bindings_used(name: &'static str, source: &str, entry: &str) -> Result<Vec<u32>> {
    let shader = |message: String| SimError::GpuShader {
        kernel: name,
        message,
    };
    let module =
        naga::front::wgsl::parse_str(source).map_err(|e| shader(e.emit_to_string(source)))?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|e| shader(e.emit_to_string(source)))?;
    let index = module
        .entry_points
        .iter()
        .position(|e| e.name == entry)
        .ok_or_else(|| shader(format!("no entry point `{entry}`")))?;
    let uses = info.get_entry_point(index);
    Ok(module
        .global_variables
        .iter()
        .filter(|&(h, _)| !uses[h].is_empty())
        .filter_map(|(_, v)| v.binding.as_ref())
        .filter(|b| b.group == 0)
        .map(|b| b.binding)
        .collect())
}

impl Kernel {
    /// Compiles entry point `entry` of `kernel` (its text after the modules it `uses`, see
    /// [`shaders::compose`]), with the bind-group layout wgpu derives from the source; once
    /// per device (`Gpu::compiled`): later engines on the device share the pipeline.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuShader`] with the compiler's diagnostic if it does not compile.
    pub fn new(
        gpu: &Gpu,
        name: &'static str,
        uses: &[&Module],
        kernel: &str,
        entry: &str,
    ) -> Result<Kernel> {
        let source = shaders::compose(uses, kernel);
        let Compiled { pipeline, bindings } =
            gpu.compiled(&source, entry, || compile(gpu, name, &source, entry))?;
        Ok(Kernel {
            name,
            pipeline,
            bindings,
        })
    }

    /// The kernel's name.
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// A bind group of `buffers` for bind group 0 (binding `i` = `buffers[i]`).
    pub fn bind(&self, gpu: &Gpu, buffers: &[&wgpu::Buffer]) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = buffers
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.name),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    }

    /// A bind group for bind group 0 of the bindings `entries` (binding number, buffer) that
    /// the entry point uses: for kernels whose modules fix their binding numbers, the entries
    /// may name more (those of every kernel of a module); its layout holds only the bindings it
    /// uses.
    pub fn bind_at(&self, gpu: &Gpu, entries: &[(u32, &wgpu::Buffer)]) -> wgpu::BindGroup {
        let entries: Vec<(u32, wgpu::BindingResource<'_>)> = entries
            .iter()
            .map(|&(binding, b)| (binding, b.as_entire_binding()))
            .collect();
        self.bind_resources(gpu, &entries)
    }

    /// [`Kernel::bind_at`] of any resources (buffer ranges: an array of a larger buffer, a
    /// chunk of the agents).
    pub fn bind_resources(
        &self,
        gpu: &Gpu,
        entries: &[(u32, wgpu::BindingResource<'_>)],
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = entries
            .iter()
            .filter(|(binding, _)| self.bindings.contains(binding))
            .map(|(binding, r)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: r.clone(),
            })
            .collect();
        gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.name),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    }

    /// Records a dispatch of one thread per element of `threads` (see `thread_index` in
    /// `shaders/dispatch.wgsl`) into `pass`.
    pub fn dispatch(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        group: &wgpu::BindGroup,
        threads: u32,
    ) {
        let [x, y] = workgroups(threads);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}

/// The 2D grid of workgroups that covers `threads` threads.
pub fn workgroups(threads: u32) -> [u32; 2] {
    const MAX_X: u32 = 65_535;
    let groups = threads.div_ceil(WORKGROUP);
    if groups <= MAX_X {
        [groups, 1]
    } else {
        [MAX_X, groups.div_ceil(MAX_X)]
    }
}

/// A storage buffer holding `data` (readable and writable by kernels, copyable both ways).
/// An empty `data` gets one zero word: wgpu refuses empty bindings.
pub fn storage<T: bytemuck::Pod>(gpu: &Gpu, label: &'static str, data: &[T]) -> wgpu::Buffer {
    let bytes: &[u8] = bytemuck::cast_slice(data);
    let zero = [0u8; 4];
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: if bytes.is_empty() { &zero } else { bytes },
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
        })
}

/// A storage buffer of `words` zeroed `u32` (at least one: wgpu refuses empty bindings),
/// readable, writable and copyable both ways, allocated on the device only, bound whole.
///
/// # Errors
///
/// [`SimError::GpuTooLarge`] beyond the adapter's largest storage binding (at most 4 GiB).
pub fn zeroed(gpu: &Gpu, label: &'static str, words: u64) -> Result<wgpu::Buffer> {
    zeroed_within(gpu, label, words, gpu.max_binding())
}

/// [`zeroed`] for a buffer bound in ranges (arrays, chunks of agents), each within the
/// adapter's largest binding: the buffer itself may be as large as the adapter's largest
/// buffer.
///
/// # Errors
///
/// [`SimError::GpuTooLarge`] beyond the adapter's largest buffer (at most 4 GiB).
pub fn zeroed_ranges(gpu: &Gpu, label: &'static str, words: u64) -> Result<wgpu::Buffer> {
    zeroed_within(gpu, label, words, gpu.device.limits().max_buffer_size)
}

fn zeroed_within(gpu: &Gpu, label: &'static str, words: u64, limit: u64) -> Result<wgpu::Buffer> {
    let bytes = 4 * words.max(1);
    // At most 4 GiB, as in Vulkan: the kernels' 32-bit indices and lengths never overflow.
    let limit = limit.min(u64::from(u32::MAX));
    if bytes > limit {
        return Err(SimError::GpuTooLarge {
            buffer: label,
            bytes,
            limit,
        });
    }
    Ok(gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    }))
}

/// Copies the first `len` elements of `buffer` to the host (waits for the GPU).
///
/// # Errors
///
/// [`SimError::GpuReadback`] if the copy cannot be mapped, [`SimError::GpuLost`] if the
/// device stops.
pub fn read_back<T: bytemuck::Pod>(
    gpu: &Gpu,
    label: &'static str,
    buffer: &wgpu::Buffer,
    len: usize,
) -> Result<Vec<T>> {
    let size = (len * std::mem::size_of::<T>()) as u64;
    if size == 0 {
        return Ok(Vec::new());
    }
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    enc.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    gpu.queue.submit([enc.finish()]);
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    gpu.wait()?;
    rx.recv()
        .unwrap_or(Err(wgpu::BufferAsyncError))
        .map_err(|source| SimError::GpuReadback {
            buffer: label,
            source,
        })?;
    let view = slice
        .get_mapped_range()
        .map_err(|_| SimError::GpuReadback {
            buffer: label,
            source: wgpu::BufferAsyncError,
        })?;
    let out = bytemuck::cast_slice::<u8, T>(&view).to_vec();
    drop(view);
    staging.unmap();
    Ok(out)
}

/// Runs `entry` once per element: element `i` is `input[i * in_words..(i + 1) * in_words]`,
/// and the thread writes `output[i * out_words..(i + 1) * out_words]`. The kernel declares
///
/// ```wgsl
/// @group(0) @binding(0) var<storage, read> input: array<u32>;
/// @group(0) @binding(1) var<storage, read_write> output: array<u32>;
/// @compute @workgroup_size(WORKGROUP)
/// fn entry(@builtin(global_invocation_id) id: vec3<u32>,
///          @builtin(num_workgroups) groups: vec3<u32>) {
///     let i = thread_index(id, groups);
///     if (i >= arrayLength(&input) / IN_WORDS) { return; }
///     ...
/// }
/// ```
///
/// (`i32` values travel as their bits: `bitcast<i32>` in WGSL, `as u32` in Rust.)
///
/// # Errors
///
/// As [`Kernel::new`] and [`read_back`].
pub fn map_words(
    gpu: &Gpu,
    uses: &[&Module],
    kernel: &str,
    entry: &str,
    input: &[u32],
    in_words: usize,
    out_words: usize,
) -> Result<Vec<u32>> {
    let mut all = vec![&shaders::DISPATCH];
    all.extend_from_slice(uses);
    let k = Kernel::new(gpu, "map_words", &all, kernel, entry)?;
    run_elements(gpu, &k, ["input", "output"], input, in_words, out_words)
}

/// Runs `kernel` once per element of `input`, in one dispatch: thread `i` reads element `i`
/// (`in_words` words) of its binding 0 and writes element `i` (`out_words` words) of its
/// binding 1, as the kernels of [`map_words`]; the output words. `labels` name the input and
/// output buffers.
///
/// # Errors
///
/// As [`read_back`].
pub fn run_elements(
    gpu: &Gpu,
    kernel: &Kernel,
    labels: [&'static str; 2],
    input: &[u32],
    in_words: usize,
    out_words: usize,
) -> Result<Vec<u32>> {
    let n = input.len() / in_words.max(1);
    let inp = storage(gpu, labels[0], input);
    let out = storage(gpu, labels[1], &vec![0u32; (n * out_words).max(1)]);
    let group = kernel.bind(gpu, &[&inp, &out]);
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        kernel.dispatch(&mut pass, &group, n as u32);
    }
    gpu.queue.submit([enc.finish()]);
    read_back(gpu, labels[1], &out, n * out_words)
}

/// As [`run_elements`], in dispatches of at most 64 MiB of input or output (and of the
/// adapter's largest binding).
///
/// # Errors
///
/// As [`read_back`].
pub fn run_chunked(
    gpu: &Gpu,
    kernel: &Kernel,
    labels: [&'static str; 2],
    input: &[u32],
    in_words: usize,
    out_words: usize,
) -> Result<Vec<u32>> {
    let limit = gpu.max_binding().min(64 << 20) as usize;
    let per_dispatch = (limit / (4 * in_words.max(out_words))).max(1);
    let mut out = Vec::with_capacity(input.len() / in_words * out_words);
    for chunk in input.chunks(per_dispatch * in_words) {
        out.extend(run_elements(
            gpu, kernel, labels, chunk, in_words, out_words,
        )?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::test_gpu;

    #[test]
    fn workgroups_cover_every_thread() {
        assert_eq!(workgroups(0), [0, 1]);
        assert_eq!(workgroups(1), [1, 1]);
        assert_eq!(workgroups(64), [1, 1]);
        assert_eq!(workgroups(65), [2, 1]);
        let [x, y] = workgroups(10_000_000);
        assert!(u64::from(x) * u64::from(y) * 64 >= 10_000_000 && x <= 65_535);
    }

    /// One device per process, a kernel compiled once per device: engines after the first
    /// compile nothing (each used to take its own device and 20-35 s of compilation on
    /// lavapipe, and the driver's memory with them), and another source is another kernel.
    #[test]
    fn the_process_shares_one_device_and_compiles_a_kernel_once() {
        let (a, b) = (test_gpu(), Gpu::shared().expect("the shared device"));
        assert!(a.device == b.device && a.queue == b.queue);
        let body = |k: u32| {
            format!(
                "@group(0) @binding(0) var<storage, read_write> out: array<u32>;
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {{
    out[thread_index(id, groups)] = {k}u;
}}"
            )
        };
        let uses = [&shaders::DISPATCH];
        let first = Kernel::new(&a, "first", &uses, &body(7), "main").unwrap();
        let again = Kernel::new(&b, "again", &uses, &body(7), "main").unwrap();
        let other = Kernel::new(&b, "other", &uses, &body(8), "main").unwrap();
        assert!(first.pipeline == again.pipeline && *first.bindings == *again.bindings);
        assert!(first.pipeline != other.pipeline);
        assert_eq!((first.name(), again.name()), ("first", "again"));
    }

    #[test]
    fn map_words_runs_a_function_per_element_across_a_2d_grid() {
        let gpu = test_gpu();
        let kernel = "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / 2u) { return; }
    output[i] = input[2u * i] * input[2u * i + 1u] + i;
}";
        // More than 65,535 workgroups: the second row of the grid is used.
        let n = 65_536 * 64 + 3;
        let input: Vec<u32> = (0..n).flat_map(|i| [i, 3]).collect();
        let out = map_words(&gpu, &[], kernel, "main", &input, 2, 1).unwrap();
        assert_eq!(out.len(), n as usize);
        for (i, &o) in out.iter().enumerate() {
            assert_eq!(
                o,
                (i as u32).wrapping_mul(3).wrapping_add(i as u32),
                "element {i}"
            );
        }
    }

    #[test]
    fn a_kernel_that_does_not_compile_is_a_typed_error() {
        let gpu = test_gpu();
        let err = Kernel::new(&gpu, "broken", &[], "fn main( {", "main")
            .err()
            .unwrap();
        assert!(
            matches!(
                err,
                SimError::GpuShader {
                    kernel: "broken",
                    ..
                }
            ),
            "{err}"
        );
    }
}
