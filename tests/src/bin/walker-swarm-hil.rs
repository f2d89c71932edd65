//! `swarm-hil` knowing the test-only walker model: what a team's own `swarm-hil` binary looks
//! like once it adds a model (the integration tests mirror `tests/data/walker-box.toml`).

fn main() -> std::process::ExitCode {
    if let Err(e) = swarm_sim::models::register(&swarm_tests::walker::ENTRY) {
        eprintln!("error: {e}");
        return std::process::ExitCode::FAILURE;
    }
    swarm_hil::cli::main()
}
