//! The noise-aware insect swarm of Wang, Jin, Deng and Zhou, *Inherent Noise-Aware Insect
//! Swarm Simulation*, Computer Graphics Forum 33(6), 2014 (wang2014): a field-based,
//! first-order model where every insect is a massless point advected by
//! V = ∇ × N + V_g (eq. 9), the curl of a boundary-modulated Perlin potential (eq. 1-3) plus a
//! global navigation field (the unit descent direction of a minimum-cost field, eq. 4-8), then
//! pushed apart from neighbours that came too close (minimum distance enforcement, §6).
//!
//! The per-insect parts live here; the global fields (signed distance, repulsion, the
//! fast-marching cost field and its gradient) are the host's (`swarm-sim`), which hands an
//! insect the navigation direction in its sensor frame.

pub mod bell;

pub use bell::bell;
