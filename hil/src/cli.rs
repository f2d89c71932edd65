//! The `swarm-hil` command line: mirror a device's decisions against the simulator, over a
//! serial port, TCP, or a loopback to the soft device; or run the soft device on a serial
//! port. The binary is [`main`]; a team that adds a model builds its own `swarm-hil` by
//! registering the model first (`swarm_sim::models::register`), then calling [`main`].

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use crate::client::{Client, ClientOptions, RtoOptions};
use crate::loopback::{Line, LinkKind, loopback, with_scalar};
use crate::mirror::{MirrorOptions, MirrorReport, mirror_scenario};
use crate::qemu::{QemuRun, mirror_in_qemu};
use crate::transport::{FaultSpec, Faulty, SerialTransport, TcpTransport, Transport};
use crate::{HilError, Verdict};
use clap::{Parser, Subcommand, ValueEnum};
use swarm_sim::scenario::{Backend, ScalarType, Scenario};

#[derive(Parser)]
#[command(
    name = "swarm-hil",
    version,
    about = "Prove that a device decides exactly what the simulation decides",
    long_about = "Runs a swarm-sim scenario and, for the chosen agents, sends every step's sensor \
                  frames to a device (a board on a serial port, QEMU over TCP, or the soft device) \
                  and compares its decisions with the host's, bit for bit. Exits non-zero on any \
                  mismatch or protocol failure.",
    after_help = EXIT_CODES
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The exit statuses, for `--help`.
const EXIT_CODES: &str = "Exit status: 0 when the run completed and every decision matched at the \
first asking; otherwise the sum of\n  \
1  the run did not complete: link, protocol or setup failure (the --json report holds what was \
compared until then)\n  \
2  a mismatch: the device decided otherwise, and again when asked again\n  \
4  a flaky device: it answered wrong, then right when asked the same again\n\
(3 = a mismatch found before the link failed); 64 when the command line cannot be used (nothing \
was run).";

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Scalar {
    /// IEEE f32 (libm).
    F32,
    /// I16F16 fixed point.
    Fixed,
}

impl From<Scalar> for ScalarType {
    fn from(s: Scalar) -> Self {
        match s {
            Scalar::F32 => ScalarType::F32,
            Scalar::Fixed => ScalarType::Fixed,
        }
    }
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Link {
    /// In-memory channels.
    Memory,
    /// A pseudo-terminal pair made for the run.
    Pty,
}

/// What every mirroring command takes.
#[derive(clap::Args)]
struct Run {
    /// Scenario: a built-in name (`swarm list`) or a TOML file.
    #[arg(long)]
    scenario: String,
    /// Agents to mirror, spread evenly over the ids (default: all).
    #[arg(long)]
    agents: Option<usize>,
    /// Steps to run.
    #[arg(long, default_value_t = 100)]
    steps: u32,
    /// Number type of the device (every group of the scenario runs in it).
    #[arg(long, value_enum, default_value_t = Scalar::F32)]
    scalar: Scalar,
    /// Who makes the host's decisions the device is compared with: `cpu` or `gpu` (the model's
    /// GPU engine; in fixed point the same bits). Default: the scenario's `backend`.
    #[arg(long, value_enum)]
    backend: Option<Backend>,
    /// Requests in flight at most: cut after the handshake to what the device says it
    /// buffers while computing (`Identity.rx_buffer`; 1 for a polled UART) unless
    /// `--flow-control`.
    #[arg(long, default_value_t = 8)]
    window: usize,
    /// The line holds the host back when the device's receiver is full (RTS/CTS): keep
    /// `--window` requests in flight whatever the device buffers. Implied by `qemu` (QEMU's
    /// UARTs take a byte only when they have room).
    #[arg(long)]
    flow_control: bool,
    /// Milliseconds before an unanswered request is sent again, until a round trip has been
    /// measured (then the timeout follows the measured round trips).
    #[arg(long, default_value_t = 200)]
    timeout_ms: u64,
    /// The retransmission timeout's floor, in milliseconds.
    #[arg(long, default_value_t = 2.0)]
    rto_min_ms: f64,
    /// The retransmission timeout's ceiling (backoff included), in milliseconds.
    #[arg(long, default_value_t = 2000.0)]
    rto_max_ms: f64,
    /// Times a request is sent again before the run fails.
    #[arg(long, default_value_t = 10_000)]
    retries: u32,
    /// Seconds without any intact reply before the device is declared lost.
    #[arg(long, default_value_t = 5.0)]
    dead_after: f64,
    /// Write the report as JSON here (on every exit but a usage error, failures included).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Damage the link: `drop=R,flip=R,insert=R,garbage=R,delay=MS@R` (rates per byte).
    #[arg(long, default_value = "")]
    inject: String,
    /// Seed of the injected faults.
    #[arg(long, default_value_t = 1)]
    fault_seed: u64,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Mirror against the soft device over an in-memory link or a pseudo-terminal pair.
    Loopback {
        /// The link to the soft device.
        #[arg(long, value_enum, default_value_t = Link::Memory)]
        transport: Link,
        #[command(flatten)]
        run: Run,
    },
    /// Mirror against a device on a serial port (`--port`) or a TCP socket (`--tcp`).
    Mirror {
        /// Serial port of the device (`/dev/ttyUSB0`, `/dev/pts/3`, `COM3`).
        #[arg(long, conflicts_with = "tcp", required_unless_present = "tcp")]
        port: Option<String>,
        /// Baud rate of the serial port.
        #[arg(long, default_value_t = 115_200)]
        baud: u32,
        /// `HOST:PORT` of a TCP link (QEMU `-serial tcp:...,server`).
        #[arg(long)]
        tcp: Option<String>,
        #[command(flatten)]
        run: Run,
    },
    /// Start a firmware image in QEMU with its UART on a pseudo-terminal and mirror it there
    /// (QEMU is stopped whatever happens).
    Qemu {
        /// The node: `ant-node`, `bee-node` or `fly-node` (`--scalar fixed` picks the
        /// fixed-point image).
        #[arg(long)]
        firmware: String,
        /// The ELF to run (default: firmware-examples/target/<triple>/release/<image>).
        #[arg(long)]
        elf: Option<PathBuf>,
        /// Send this many random bytes to the board's UART before the session.
        #[arg(long, default_value_t = 0)]
        garbage: usize,
        /// Reset the emulated board before this step (the harness must re-handshake).
        #[arg(long)]
        reset_at_step: Option<u32>,
        #[command(flatten)]
        run: Run,
    },
    /// Run the soft device (swarm-core's endpoint on this host) on a serial port, with the
    /// parameters of a scenario, until interrupted.
    Device {
        /// Serial port to serve on.
        #[arg(long)]
        port: String,
        /// Baud rate.
        #[arg(long, default_value_t = 115_200)]
        baud: u32,
        /// The scenario whose parameters the device runs.
        #[arg(long)]
        scenario: String,
        /// Number type.
        #[arg(long, value_enum, default_value_t = Scalar::F32)]
        scalar: Scalar,
    },
}

type AnyError = Box<dyn std::error::Error>;

/// Why a command stopped without a verdict of its own.
enum Stop {
    /// The command line cannot be used: nothing was run.
    Usage(String),
    /// The run failed (a partial report, if any, is already written).
    Failed(AnyError),
}

impl<E: Into<AnyError>> From<E> for Stop {
    fn from(e: E) -> Self {
        Stop::Failed(e.into())
    }
}

fn usage(message: String) -> Stop {
    Stop::Usage(message)
}

/// The `swarm-hil` command line on the process's arguments, with the models of
/// `swarm_sim::models::all`: prints the report or the error, and returns the exit status
/// ([`Verdict::exit_code`], [`Verdict::EXIT_USAGE`], [`Verdict::EXIT_LINK_FAILURE`]).
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return match e.kind() {
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion => {
                    ExitCode::SUCCESS
                }
                _ => ExitCode::from(Verdict::EXIT_USAGE),
            };
        }
    };
    match run(cli) {
        Ok(verdict) => ExitCode::from(verdict.exit_code()),
        Err(Stop::Usage(m)) => {
            eprintln!("error: {m}");
            ExitCode::from(Verdict::EXIT_USAGE)
        }
        Err(Stop::Failed(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(Verdict::EXIT_LINK_FAILURE)
        }
    }
}

/// The verdict of the run.
fn run(cli: Cli) -> Result<Verdict, Stop> {
    match cli.command {
        Command::Loopback { transport, run } => {
            let (sc, faults) = checked(&run, None)?;
            let link = match transport {
                Link::Memory => LinkKind::Memory,
                Link::Pty => LinkKind::Pty,
            };
            let line = Line {
                link,
                faults,
                fault_seed: run.fault_seed,
                client: client_options(&run)?,
            };
            let report = loopback(&sc, run.scalar.into(), line, &mirror_options(&run));
            finish(report, run.json.as_deref())
        }
        Command::Mirror {
            port,
            baud,
            tcp,
            run,
        } => {
            let (sc, faults) = checked(&run, None)?;
            let opts = client_options(&run)?;
            let link: Box<dyn Transport> = match (port, tcp) {
                (Some(p), _) => Box::new(SerialTransport::open(&p, baud)?),
                (None, Some(a)) => Box::new(TcpTransport::connect(&a, Duration::from_secs(5))?),
                (None, None) => return Err(usage("give --port or --tcp".into())),
            };
            let sc = with_scalar(&sc, run.scalar.into());
            let mut client = Client::new(Faulty::new(link, faults, run.fault_seed), opts);
            let report = mirror(&sc, &mut client, &run, &mut |_| Ok(()));
            let counts = (!faults.is_clean()).then(|| client.link_mut().counts());
            let report = match report {
                Ok(mut r) => {
                    r.faults = counts;
                    Ok(r)
                }
                Err(e) => Err(e.with_report(|r| r.faults = counts)),
            };
            finish(report, run.json.as_deref())
        }
        Command::Qemu {
            firmware,
            elf,
            garbage,
            reset_at_step,
            run,
        } => {
            let (sc, faults) = checked(&run, reset_at_step)?;
            let image = match run.scalar {
                Scalar::F32 => firmware.clone(),
                Scalar::Fixed => format!("{firmware}-fixed"),
            };
            let elf = match elf {
                Some(e) => e,
                None => QemuRun::elf_of(Path::new("."), &image).ok_or_else(|| {
                    usage(format!(
                        "unknown firmware `{firmware}` (ant-node, bee-node, fly-node)"
                    ))
                })?,
            };
            let qrun = QemuRun {
                image,
                elf,
                garbage,
                reset_at: reset_at_step,
                faults,
                fault_seed: run.fault_seed,
            };
            let sc = with_scalar(&sc, run.scalar.into());
            let flow = ClientOptions {
                flow_control: true,
                ..client_options(&run)?
            };
            let report =
                mirror_in_qemu(&qrun, flow, |client, hook| mirror(&sc, client, &run, hook));
            finish(report, run.json.as_deref())
        }
        Command::Device {
            port,
            baud,
            scenario: name,
            scalar,
        } => {
            let sc = with_scalar(
                &scenario(&name).map_err(|e| usage(e.to_string()))?,
                scalar.into(),
            );
            let link = SerialTransport::open(&port, baud)?;
            eprintln!(
                "soft device on {port} ({scalar:?}, parameters of {}); Ctrl-C stops it",
                sc.name
            );
            let stop = AtomicBool::new(false);
            serve(&sc, link, &stop)?;
            Ok(Verdict::default())
        }
    }
}

/// Serves a soft device running `sc`'s parameters on `link` until the link closes.
fn serve(sc: &Scenario, link: SerialTransport, stop: &AtomicBool) -> Result<(), AnyError> {
    let device = swarm_sim::models::engine(sc, sc.seed)?.device()?.soft;
    crate::soft::serve(device, link, stop)?;
    Ok(())
}

/// Mirrors `sc` (already in the run's scalar type) over `client`.
fn mirror<T: Transport>(
    sc: &Scenario,
    client: &mut Client<T>,
    run: &Run,
    hook: &mut dyn FnMut(u32) -> crate::Result<()>,
) -> crate::Result<MirrorReport> {
    mirror_scenario(sc, client, &mirror_options(run), hook)
}

fn scenario(name: &str) -> Result<Scenario, AnyError> {
    Ok(swarm_sim::scenario::resolve(name)?)
}

/// The scenario and the faults of a mirror run, after checking the command line against
/// them: at least one step and one agent, no more agents than the scenario has, a reset
/// within the run, finite times, a valid `--inject`.
fn checked(run: &Run, reset_at_step: Option<u32>) -> Result<(Scenario, FaultSpec), Stop> {
    swarm_sim::scenario::check_steps(run.steps, "--steps").map_err(|e| usage(e.to_string()))?;
    let sc = scenario(&run.scenario).map_err(|e| usage(e.to_string()))?;
    let population: u64 = sc.groups.iter().map(|g| u64::from(g.count)).sum();
    match run.agents {
        Some(0) => return Err(usage("--agents 0: mirror at least one agent".into())),
        Some(k) if k as u64 > population => {
            return Err(usage(format!(
                "--agents {k}: scenario `{}` has only {population} agents",
                sc.name
            )));
        }
        _ => {}
    }
    if let Some(r) = reset_at_step
        && r >= run.steps
    {
        return Err(usage(format!(
            "--reset-at-step {r} is beyond the run: steps are 0 to {} (--steps {})",
            run.steps - 1,
            run.steps
        )));
    }
    let faults: FaultSpec = run
        .inject
        .parse()
        .map_err(|e: crate::HilError| usage(e.to_string()))?;
    let mut sc = sc;
    if let Some(b) = run.backend {
        sc.backend = b;
    }
    Ok((sc, faults))
}

/// A duration given in seconds on the command line, or the usage error naming `flag`.
fn seconds(flag: &str, s: f64) -> Result<Duration, Stop> {
    Duration::try_from_secs_f64(s)
        .map_err(|_| usage(format!("{flag}: `{s}` is not a duration (a number ≥ 0)")))
}

fn client_options(run: &Run) -> Result<ClientOptions, Stop> {
    let dead_after = seconds("--dead-after", run.dead_after)?;
    if dead_after.is_zero() {
        return Err(usage("--dead-after must be more than 0 seconds".into()));
    }
    Ok(ClientOptions {
        window: run.window,
        flow_control: run.flow_control,
        rto: RtoOptions {
            initial: Duration::from_millis(run.timeout_ms),
            min: seconds("--rto-min-ms", run.rto_min_ms / 1000.0)?,
            max: seconds("--rto-max-ms", run.rto_max_ms / 1000.0)?,
        },
        retries: run.retries,
        dead_after,
    })
}

fn mirror_options(run: &Run) -> MirrorOptions {
    MirrorOptions {
        agents: run.agents,
        steps: run.steps,
        session: std::process::id(),
        progress: !run.quiet,
    }
}

/// Prints the summary and writes the JSON of a run, completed or stopped part way (the
/// partial report); the verdict.
fn finish(report: crate::Result<MirrorReport>, json: Option<&Path>) -> Result<Verdict, Stop> {
    let (report, error) = match report {
        Ok(r) => (r, None),
        Err(HilError::Aborted { report, source }) => (*report, Some(*source)),
        Err(e) => {
            if let Some(path) = json {
                let text = serde_json::json!({
                    "verdict": Verdict { link_failure: true, ..Verdict::default() },
                    "failure": e.to_string(),
                });
                write_json(path, &text)?;
            }
            return Err(e.into());
        }
    };
    println!("{}", report.human());
    if let Some(path) = json {
        write_json(path, &report)?;
    }
    if let Some(e) = error {
        eprintln!("error: {e}");
    }
    Ok(report.verdict)
}

fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<(), Stop> {
    let text = serde_json::to_string_pretty(value)?;
    swarm_sim::output::write_atomic_bytes(path, text.as_bytes())?;
    println!("wrote {}", path.display());
    Ok(())
}
