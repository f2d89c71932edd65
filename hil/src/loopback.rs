//! Loopback: the mirror against the soft device on the far end of an in-memory link or a
//! pseudo-terminal pair, optionally through injected faults. What `swarm-hil loopback` runs,
//! and how the protocol and the harness are tested without hardware.

use swarm_sim::engine::Engine;
use swarm_sim::scenario::{ScalarType, Scenario};

use crate::Result;
use crate::client::{Client, ClientOptions};
use crate::mirror::{MirrorOptions, MirrorReport, mirror, mirror_with_events};
use crate::soft::{SoftDevice, serve};
use crate::transport::{FaultSpec, Faulty, Transport, memory_pair};

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

/// The line of a loopback run: the link, the faults injected on it (both directions, seeded
/// by `fault_seed`) and the client's pacing.
#[derive(Clone, Copy, Debug)]
pub struct Line {
    /// The link.
    pub link: LinkKind,
    /// What to damage.
    pub faults: FaultSpec,
    /// The seed of the damage.
    pub fault_seed: u64,
    /// The client's window, timeouts and retries.
    pub client: ClientOptions,
}

impl Line {
    /// `link` without faults, the default client.
    pub fn clean(link: LinkKind) -> Line {
        Line {
            link,
            faults: FaultSpec::default(),
            fault_seed: 1,
            client: ClientOptions::default(),
        }
    }
}

/// Mirrors scenario `sc` (any model) in `scalar` against a soft device over `line`.
pub fn loopback(
    sc: &Scenario,
    scalar: ScalarType,
    line: Line,
    opts: &MirrorOptions,
) -> Result<MirrorReport> {
    let sc = with_scalar(sc, scalar);
    let engine = swarm_sim::models::engine(&sc, sc.seed)?;
    serve_and_mirror(&sc.name, engine, Some(&sc), line, opts)
}

/// [`loopback`] of a simulation already built (of any model, e.g. one defined outside this
/// workspace): its soft device ([`Engine::device`]) on the far end of the line.
pub fn loopback_engine(
    name: &str,
    engine: Box<dyn Engine>,
    line: Line,
    opts: &MirrorOptions,
) -> Result<MirrorReport> {
    serve_and_mirror(name, engine, None, line, opts)
}

/// The soft device of `engine` on the far end of `line`, and the mirror run against it, with
/// the timed events of `events` (the scenario the engine was built from) if given.
fn serve_and_mirror(
    name: &str,
    mut engine: Box<dyn Engine>,
    events: Option<&Scenario>,
    line: Line,
    opts: &MirrorOptions,
) -> Result<MirrorReport> {
    let (device_end, host_end) = open(line.link)?;
    let device = engine.device()?.soft;
    let soft: SoftDevice<()> =
        SoftDevice::spawn(move |stop| serve(device, device_end, stop).map(|_| ()));
    let mut client = Client::new(
        Faulty::new(host_end, line.faults, line.fault_seed),
        line.client,
    );
    let report = match events {
        Some(sc) => mirror_with_events(sc, &mut *engine, &mut client, opts, &mut |_| Ok(())),
        None => mirror(name, engine, &mut client, opts, &mut |_| Ok(())),
    };
    soft.stop()?;
    let counts = (!line.faults.is_clean()).then(|| client.link_mut().counts());
    let add_faults = |r: &mut MirrorReport| r.faults = counts;
    match report {
        Ok(mut r) => {
            add_faults(&mut r);
            Ok(r)
        }
        Err(e) => Err(e.with_report(add_faults)),
    }
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
            return Err(crate::HilError::Unsupported(
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
            let r = loopback(&sc, scalar, Line::clean(LinkKind::Memory), &opts(20, 20)).unwrap();
            assert_eq!(r.decisions, 800, "{scalar:?}");
            assert_eq!(r.mismatches, 0, "{}", r.human());
        }
    }
}
