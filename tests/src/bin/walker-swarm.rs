//! `swarm` knowing the test-only walker model: what a team's own `swarm` binary looks like once
//! it adds a model (the integration tests run it on `tests/data/walker-box.toml`).

fn main() -> std::process::ExitCode {
    if let Err(e) = swarm_sim::models::register(&swarm_tests::walker::ENTRY) {
        eprintln!("error: {e}");
        return std::process::ExitCode::FAILURE;
    }
    swarm_sim::cli::main()
}
