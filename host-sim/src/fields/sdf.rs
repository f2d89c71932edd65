//! The signed distance to the obstacles on the cell centres (wang2014 eq. 5) and the repulsion
//! value of eq. 6 computed from it.

use rayon::prelude::*;
use swarm_core::Scalar;

use super::CellGrid;
use crate::space::Shape3;

/// The signed distance φ from every cell centre to the nearest obstacle surface (wang2014
/// eq. 5): `−distance` inside an obstacle, `+distance` outside, the minimum over the obstacles
/// (the signed distance of their union).
///
/// Distances are those of [`Shape3::surface`] in `f32` (analytic spheres, boxes and shafts,
/// not the paper's triangle meshes). With no obstacles every cell holds `+∞` (g = 0 there:
/// [`repulsion`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SignedDistance {
    /// φ per cell centre, indexed like the grid's cells.
    pub phi: Vec<f32>,
}

impl SignedDistance {
    /// φ on the cell centres of `grid` for `shapes` in a world with bounds `[lo, hi]` (faces of
    /// boxes and shaft caps lying on the world bounds are closed, [`Shape3::surface`]).
    ///
    /// Parallel over cells; every cell's value is the same function of its centre whatever the
    /// thread count, so the result is deterministic.
    pub fn build(grid: &CellGrid, shapes: &[Shape3], lo: [f32; 3], hi: [f32; 3]) -> Self {
        let phi = (0..grid.len())
            .into_par_iter()
            .with_min_len(256)
            .map(|i| {
                let p = grid.center_vec::<f32>(i);
                shapes.iter().fold(f32::INFINITY, |best, s| {
                    let f = s.surface(p, lo, hi);
                    let phi = if f.inside { -f.distance } else { f.distance };
                    best.min(phi)
                })
            })
            .collect();
        SignedDistance { phi }
    }

    /// A signed distance of `+∞` everywhere: no obstacles.
    pub fn empty(grid: &CellGrid) -> Self {
        SignedDistance {
            phi: vec![f32::INFINITY; grid.len()],
        }
    }

    /// Whether cell `index` lies inside an obstacle (φ < 0).
    #[inline]
    pub fn inside(&self, index: usize) -> bool {
        self.phi[index] < 0.0
    }
}

/// The repulsion value g of wang2014 eq. 6 at signed distance `phi` on a grid of cell side
/// `cell`: `g = h(φ/(2a))` with `a = √2·cell` (the paper's "diagonal length of a regular grid",
/// spec W6), so g = 1 inside obstacles and on their surface, falls monotonically to 0 at
/// `2√2·cell` and is 0 beyond (and for `φ = +∞`, no obstacle). NaN gives 1 (treated as inside).
pub fn repulsion(phi: f32, cell: f32) -> f32 {
    if phi.is_nan() {
        return 1.0;
    }
    let reach = 2.0 * std::f32::consts::SQRT_2 * cell;
    swarm_core::wang::bell(phi / reach)
}

/// `repulsion` in any scalar (for an agent-side evaluation at its own position).
pub fn repulsion_in<S: Scalar>(phi: S, cell: S) -> S {
    let reach = S::from_f32(2.0 * std::f32::consts::SQRT_2) * cell;
    swarm_core::wang::bell(phi / reach)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LO: [f32; 3] = [-100.0; 3];
    const HI: [f32; 3] = [100.0; 3];

    /// A 1-cell grid centred on `p` (cell side 0.5), for evaluating φ at a point.
    fn phi_at(shapes: &[Shape3], p: [f32; 3]) -> f32 {
        let g = CellGrid::new(p.map(|v| v - 0.25), p.map(|v| v + 0.25), 0.5).unwrap();
        assert_eq!(g.len(), 1);
        assert_eq!(g.center(0), p);
        SignedDistance::build(&g, shapes, LO, HI).phi[0]
    }

    #[test]
    fn sign_and_distance_of_spheres_boxes_shafts_and_their_union() {
        let sphere = Shape3::Sphere {
            center: [0.0, 0.0, 0.0],
            radius: 2.0,
        };
        let boxed = Shape3::Box {
            min: [4.0, 0.0, 0.0],
            max: [6.0, 2.0, 2.0],
        };
        let shaft = Shape3::Shaft {
            center: [10.0, 0.0],
            radius: 1.0,
            y_min: 0.0,
            y_max: 5.0,
        };
        let close = |a: f32, b: f32| (a - b).abs() < 1e-5;
        let s = std::slice::from_ref(&sphere);
        assert!(close(phi_at(s, [0.0, 0.0, 0.0]), -2.0));
        assert!(close(phi_at(s, [1.0, 0.0, 0.0]), -1.0));
        assert!(close(phi_at(s, [0.0, 3.0, 0.0]), 1.0));
        assert!(close(phi_at(s, [3.0, 4.0, 0.0]), 3.0));
        let b = std::slice::from_ref(&boxed);
        assert!(close(phi_at(b, [5.0, 1.0, 1.0]), -1.0));
        assert!(close(phi_at(b, [4.5, 1.0, 1.0]), -0.5));
        assert!(close(phi_at(b, [5.0, 1.0, 3.5]), 1.5));
        assert!(close(phi_at(b, [7.0, 3.0, 1.0]), 2f32.sqrt()));
        let t = std::slice::from_ref(&shaft);
        assert!(close(phi_at(t, [10.0, 2.5, 0.0]), -1.0));
        assert!(close(phi_at(t, [10.5, 4.75, 0.0]), -0.25));
        assert!(close(phi_at(t, [12.0, 2.0, 0.0]), 1.0));
        assert!(close(phi_at(t, [10.0, 7.0, 0.0]), 2.0));
        // The union: the minimum.
        let all = [sphere.clone(), boxed.clone(), shaft.clone()];
        for p in [
            [0.0, 0.0, 0.0],
            [3.0, 1.0, 1.0],
            [5.0, 1.0, 1.0],
            [8.0, 2.0, 0.0],
            [10.0, 2.5, 0.0],
            [20.0, -3.0, 4.0],
        ] {
            let each = [phi_at(s, p), phi_at(b, p), phi_at(t, p)];
            let min = each.iter().copied().fold(f32::INFINITY, f32::min);
            assert_eq!(phi_at(&all, p), min, "{p:?}: {each:?}");
        }
        assert!(close(phi_at(&all, [3.0, 1.0, 1.0]), 1.0));
        // No obstacles: +inf.
        assert_eq!(phi_at(&[], [1.0, 2.0, 3.0]), f32::INFINITY);
        let g = CellGrid::new([0.0; 3], [2.0; 3], 1.0).unwrap();
        assert_eq!(
            SignedDistance::build(&g, &[], LO, HI),
            SignedDistance::empty(&g)
        );
    }

    #[test]
    fn repulsion_is_one_inside_zero_beyond_two_a_and_decreasing() {
        let l = 0.5f32;
        let reach = 2.0 * 2f32.sqrt() * l;
        assert_eq!(repulsion(-1.0, l), 1.0);
        assert_eq!(repulsion(f32::NEG_INFINITY, l), 1.0);
        assert_eq!(repulsion(f32::NAN, l), 1.0);
        assert_eq!(repulsion(0.0, l), 1.0);
        assert!(repulsion(reach, l) < 1e-6);
        assert_eq!(repulsion(reach * 1.001, l), 0.0);
        assert_eq!(repulsion(10.0, l), 0.0);
        assert_eq!(repulsion(f32::INFINITY, l), 0.0);
        let mut last = 1.0;
        for i in 1..=200 {
            let g = repulsion(reach * i as f32 / 200.0, l);
            assert!(
                g <= last && g >= 0.0,
                "g at {i}/200 of 2a: {g} after {last}"
            );
            last = g;
        }
        assert!(repulsion(0.5 * reach, l) > 0.1 && repulsion(0.5 * reach, l) < 0.9);
        let fx = repulsion_in(swarm_core::Fx::from_f32(0.3), swarm_core::Fx::from_f32(l));
        assert!((fx.to_f32() - repulsion(0.3, l)).abs() < 1e-3);
    }
}
