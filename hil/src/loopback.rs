//! Loopback: the mirror against the soft device on the far end of an in-memory link or a
//! pseudo-terminal pair, optionally through injected faults. What `swarm-hil loopback` runs,
//! and how the protocol and the harness are tested without hardware.

use serde::Serialize;
use serde::de::DeserializeOwned;
use swarm_core::Fx;
use swarm_core::ant::AntParams;
use swarm_core::bee::BeeParams;
use swarm_core::wire::{AntDevice, BeeDevice, Controller};
use swarm_sim::ants::AntSim;
use swarm_sim::bees::BeeSim;
use swarm_sim::scalar::SimScalar;
use swarm_sim::scenario::{ScalarType, Scenario};

use crate::client::{Client, ClientOptions};
use crate::mirror::{
    BeeGroupsOf, DeviceParams, GroupsOf, MirrorOptions, MirrorReport, device_params,
    mirror_scenario,
};
use crate::soft::{SoftDevice, serve};
use crate::transport::{FaultSpec, Faulty, Transport, memory_pair};
use crate::{HilError, Result};

/// The link between the harness and the soft device.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinkKind {
    /// In-memory channels.
    Memory,
    /// A pseudo-terminal pair, the harness on the terminal side through `serialport`.
    Pty,
}

/// `sc` with every group in scalar type `scalar`.
pub fn with_scalar(sc: &Scenario, scalar: ScalarType) -> Scenario {
    let mut sc = sc.clone();
    for g in &mut sc.groups {
        g.scalar = scalar;
    }
    sc
}

/// Mirrors scenario `sc` (ants or bees) in `scalar` against a soft device over `link`, with
/// `faults` injected on the link (both directions, seeded by `fault_seed`).
pub fn loopback(
    sc: &Scenario,
    scalar: ScalarType,
    link: LinkKind,
    faults: FaultSpec,
    fault_seed: u64,
    client: ClientOptions,
    opts: &MirrorOptions,
) -> Result<MirrorReport> {
    let sc = with_scalar(sc, scalar);
    match scalar {
        ScalarType::F32 => run::<f32>(&sc, link, faults, fault_seed, client, opts),
        ScalarType::Fixed => run::<Fx>(&sc, link, faults, fault_seed, client, opts),
    }
}

fn run<S>(
    sc: &Scenario,
    link: LinkKind,
    faults: FaultSpec,
    fault_seed: u64,
    client: ClientOptions,
    opts: &MirrorOptions,
) -> Result<MirrorReport>
where
    S: SimScalar + Serialize + DeserializeOwned + Send + 'static,
    AntSim: GroupsOf<S>,
    BeeSim: BeeGroupsOf<S>,
    AntParams<S>: Controller,
    BeeParams<S>: Controller,
{
    let (device_end, host_end) = open(link)?;
    let soft: SoftDevice<()> = match device_params::<S>(sc)? {
        DeviceParams::Ant(p) => {
            let device = AntDevice::<S>::new(p, "soft-ant").map_err(soft_err)?;
            SoftDevice::spawn(move |stop| serve(device, device_end, stop).map(|_| ()))
        }
        DeviceParams::Bee(p) => {
            let device = BeeDevice::<S>::new(p, "soft-bee").map_err(soft_err)?;
            SoftDevice::spawn(move |stop| serve(device, device_end, stop).map(|_| ()))
        }
    };
    let mut client = Client::new(Faulty::new(host_end, faults, fault_seed), client);
    let report = mirror_scenario::<S, _>(sc, &mut client, opts, &mut |_| Ok(()));
    soft.stop()?;
    let counts = (!faults.is_clean()).then(|| client.link_mut().counts());
    let add_faults = |r: &mut MirrorReport| r.faults = counts;
    match report {
        Ok(mut r) => {
            add_faults(&mut r);
            Ok(r)
        }
        Err(e) => Err(e.with_report(add_faults)),
    }
}

fn soft_err(e: swarm_core::Error) -> HilError {
    HilError::Invalid(format!("soft device: {e}"))
}

fn open(link: LinkKind) -> Result<(Box<dyn Transport>, Box<dyn Transport>)> {
    Ok(match link {
        LinkKind::Memory => {
            let (a, b) = memory_pair();
            (Box::new(a), Box::new(b))
        }
        #[cfg(unix)]
        LinkKind::Pty => {
            let (a, b) = crate::transport::pty_pair(115_200)?;
            (Box::new(a), Box::new(b))
        }
        #[cfg(not(unix))]
        LinkKind::Pty => {
            return Err(HilError::Invalid(
                "pseudo-terminals need a Unix host".into(),
            ));
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts(agents: usize, steps: u32) -> MirrorOptions {
        MirrorOptions {
            agents: Some(agents),
            steps,
            session: 7,
            progress: false,
        }
    }

    #[test]
    fn memory_loopback_mirrors_ants_without_a_mismatch() {
        let sc = swarm_sim::scenario::builtin("ants-fig7a-single-colony").unwrap();
        for scalar in [ScalarType::F32, ScalarType::Fixed] {
            let r = loopback(
                &sc,
                scalar,
                LinkKind::Memory,
                FaultSpec::default(),
                1,
                ClientOptions::default(),
                &opts(20, 20),
            )
            .unwrap();
            assert_eq!(r.decisions, 800, "{scalar:?}");
            assert_eq!(r.mismatches, 0, "{}", r.human());
        }
    }
}
