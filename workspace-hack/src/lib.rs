//! Feature unification between the workspace's build and the Python module's (see
//! `Cargo.toml`): no code.
