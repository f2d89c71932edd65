//! The serial node: a `swarm-core` device endpoint served over any UART that implements the
//! [`embedded-io`](embedded_io) 0.6 traits.
//!
//! A board brings two things: a UART (`embedded_io::Read + Write`: its HAL's own, or a small
//! driver such as `fw_support::uart`) and a reset/panic policy. Everything else is here and
//! board-independent:
//!
//! ```ignore
//! #[cortex_m_rt::entry]
//! fn main() -> ! {
//!     let mut uart = my_hal::Uart0::new(/* pins, clocks, 115200 8N1 */);
//!     let Ok(mut device) = fw_node::ant_device::<swarm_core::Fx>("ant-node-fixed") else {
//!         loop {} // only a name longer than 24 bytes fails
//!     };
//!     fw_node::run(&mut device, &mut uart)
//! }
//! ```
//!
//! [`run`] never returns: it reads what the UART has, feeds it to the endpoint
//! ([`DeviceEndpoint::feed`]) and writes every reply frame back, forever. The protocol
//! (framing, handshake, errors) is `docs/protocol.md`, sections 9-11; the endpoint is
//! `swarm_core::wire::DeviceEndpoint`, used unchanged.
//!
//! # Parameters
//!
//! A host refuses a device whose parameter hash differs from its own (protocol section 10.3).
//! The nodes run the parameters of one built-in host scenario each, cast to the node's scalar
//! exactly as the host simulator does (`AntParams::<f32>::cast`, `BeeParams::<f32>::cast`):
//!
//! * ants: [`ANT_SCENARIO`] (`ants-fig7a-single-colony`: its group has no `ant` overrides,
//!   so `AntParams::default()`), see [`ant_params`];
//! * bees: [`BEE_SCENARIO`] (`bees-fig14-shafts`: preset `optimized`, Table I's optimized
//!   column = `BeeParams::default()`), see [`bee_params`];
//! * flies: [`FLY_SCENARIO`] (`fly-fig1-midges`: preset `midge` with no overrides, ren2016
//!   Table 1's Midge column = `FlyParams::midge()`), see [`fly_params`].
//!
//! A node for other parameters only changes these functions (or passes its own parameters
//! to [`AntDevice::new`] / [`BeeDevice::new`] / [`FlyDevice::new`]).
#![no_std]
#![forbid(unsafe_code)]

use embedded_io::{Read, Write};
use swarm_core::Scalar;
use swarm_core::ant::AntParams;
use swarm_core::bee::BeeParams;
use swarm_core::fly::{FlyDevice, FlyParams};
use swarm_core::wire::{AntDevice, BeeDevice, Controller, DeviceEndpoint};

pub use embedded_io;
pub use swarm_core;

/// The host scenario whose ant parameters [`ant_params`] reproduces.
pub const ANT_SCENARIO: &str = "ants-fig7a-single-colony";
/// The host scenario whose bee parameters [`bee_params`] reproduces.
pub const BEE_SCENARIO: &str = "bees-fig14-shafts";
/// The host scenario whose fly parameters [`fly_params`] reproduces.
pub const FLY_SCENARIO: &str = "fly-fig1-midges";

/// Bytes read from the UART per call (the endpoint takes any chunk size; a larger chunk only
/// saves calls). Lives on the stack of [`run`].
pub const READ_CHUNK: usize = 32;

/// A number type a node runs: `f32`, and with feature `fixed` [`Fx`](swarm_core::Fx).
pub trait NodeScalar: Scalar {
    /// The ant parameters of [`ANT_SCENARIO`] in this type (see [`ant_params`]).
    fn ant_params() -> AntParams<Self>;
}

impl NodeScalar for f32 {
    fn ant_params() -> AntParams<f32> {
        AntParams::default()
    }
}

/// [`ant_params`] for [`Fx`](swarm_core::Fx), as constant bits: what
/// `AntParams::<f32>::default().cast::<Fx>()` gives (a host test pins the equality), without
/// the `f32` → `Fx` conversions at start-up (160 bytes of flash in `ant-node-fixed`).
#[cfg(feature = "fixed")]
pub const ANT_PARAMS_FX: AntParams<swarm_core::Fx> = {
    use swarm_core::Fx;
    const ONE: Fx = Fx::from_bits(0x1_0000);
    AntParams {
        speed: ONE,
        dt: ONE,
        theta: Fx::from_bits(34_315),
        p_stop: Fx::from_bits(328),
        casual_stop_ticks: 5,
        collect_ticks: 10,
        drop_ticks: 10,
        contact_range: Fx::from_bits(0x2_0000),
        avoid_range: Fx::from_bits(0x2_0000),
        collision_range: Fx::from_bits(0x1_8000),
        w0: Fx::from_bits(39_322),
        c: ONE,
        k: 2,
    }
};

#[cfg(feature = "fixed")]
impl NodeScalar for swarm_core::Fx {
    fn ant_params() -> AntParams<swarm_core::Fx> {
        ANT_PARAMS_FX
    }
}

/// The ant parameters of [`ANT_SCENARIO`] in scalar `S`: `AntParams::<f32>::default()` cast
/// to `S`, as the host simulator does (for `Fx` each value goes through `f32`;
/// `AntParams::<Fx>::default()` computes θ = π/6 in fixed point and differs in the last bit).
pub fn ant_params<S: NodeScalar>() -> AntParams<S> {
    S::ant_params()
}

/// The bee parameters of [`BEE_SCENARIO`] in scalar `S`: `BeeParams::<f32>::default()` (chen
/// Table I, "optimized") cast to `S`, as the host simulator does.
pub fn bee_params<S: Scalar>() -> BeeParams<S> {
    BeeParams::<f32>::default().cast::<S>()
}

/// The fly parameters of [`FLY_SCENARIO`] in scalar `S`: `FlyParams::<f32>::midge()` (ren2016
/// Table 1, "Midge", with our Δt, ORCA and noise choices) cast to `S`, as the host simulator
/// does (the scenario names the preset `midge` and overrides nothing).
pub fn fly_params<S: Scalar>() -> FlyParams<S> {
    FlyParams::<f32>::midge().cast::<S>()
}

/// An ant device running [`ant_params`], reporting `name` in its `Identity`.
///
/// # Errors
///
/// `Error::BadParam` for a name longer than 24 bytes (the parameters are valid).
pub fn ant_device<S>(name: &str) -> swarm_core::Result<AntDevice<S>>
where
    AntParams<S>: Controller,
    S: NodeScalar,
{
    AntDevice::new(ant_params::<S>(), name)
}

/// A bee device running [`bee_params`], reporting `name` in its `Identity`.
///
/// # Errors
///
/// `Error::BadParam` for a name longer than 24 bytes (the parameters are valid).
pub fn bee_device<S>(name: &str) -> swarm_core::Result<BeeDevice<S>>
where
    BeeParams<S>: Controller,
    S: Scalar,
{
    BeeDevice::new(bee_params::<S>(), name)
}

/// A fly device running [`fly_params`], reporting `name` in its `Identity`.
///
/// # Errors
///
/// `Error::BadParam` for a name longer than 24 bytes (the parameters are valid).
pub fn fly_device<S>(name: &str) -> swarm_core::Result<FlyDevice<S>>
where
    FlyParams<S>: Controller,
    S: Scalar,
{
    FlyDevice::new(fly_params::<S>(), name)
}

/// One round of the node loop: one `read` (it blocks until at least one byte is there, then
/// returns what the UART has, up to `buf.len()`), every byte fed to the endpoint, every reply
/// written in order with `write_all`, then one `flush` if anything was written. Returns the
/// number of bytes read.
///
/// A write error does not stop the feeding: the endpoint still sees every byte, so it stays
/// in step with the line; the reply that failed is lost (the host's retry gets it again,
/// identical).
///
/// # Errors
///
/// The UART's read error (nothing was fed then: e.g. an overrun, whose damaged frame the
/// endpoint would have dropped anyway), or the first write/flush error.
pub fn poll<C, const RX: usize, const TX: usize, U>(
    device: &mut DeviceEndpoint<C, RX, TX>,
    uart: &mut U,
    buf: &mut [u8],
) -> Result<usize, U::Error>
where
    C: Controller,
    U: Read + Write,
{
    let n = uart.read(buf)?;
    let mut input = buf.get(..n).unwrap_or_default();
    let mut wrote = false;
    let mut result = Ok(n);
    while let Some((reply, rest)) = device.feed(input) {
        wrote = true;
        if let Err(e) = uart.write_all(reply)
            && result.is_ok()
        {
            result = Err(e);
        }
        input = rest;
    }
    if wrote && let Err(e) = uart.flush() {
        result = result.and(Err(e));
    }
    result
}

/// The node loop: [`poll`] forever, ignoring UART errors (a damaged frame is dropped by the
/// endpoint's CRC check and retried by the host).
///
/// Stack: [`READ_CHUNK`] bytes here, plus the endpoint's work per frame (one request decoded
/// on the stack, the controller, one reply encoded into the endpoint's own buffer).
pub fn run<C, const RX: usize, const TX: usize, U>(
    device: &mut DeviceEndpoint<C, RX, TX>,
    uart: &mut U,
) -> !
where
    C: Controller,
    U: Read + Write,
{
    let mut buf = [0u8; READ_CHUNK];
    loop {
        let _ = poll(device, uart, &mut buf);
    }
}

#[cfg(test)]
mod tests;
