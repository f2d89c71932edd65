//! The `swarm` command line ([`swarm_sim::cli`]) with the built-in models.

fn main() -> std::process::ExitCode {
    swarm_sim::cli::main()
}
