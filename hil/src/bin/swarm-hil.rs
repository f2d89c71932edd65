//! The `swarm-hil` command line ([`swarm_hil::cli`]) with the built-in models.

fn main() -> std::process::ExitCode {
    swarm_hil::cli::main()
}
