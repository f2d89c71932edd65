//! Where a swarm is, li2015's measures of a swarm against data (§5, Figs. 4, 8, 9; spec
//! L-T7..L-T9): the distance of the insects to their centroid, averaged over frames, and the
//! total variation between two accumulated densities (every sample of a track set binned on a
//! common grid).

use std::collections::BTreeMap;

use super::Tracks;
use crate::li::mean_centroid_distance;

/// Cells per axis of the grid on which [`density_tv`] bins both track sets (16³, li2015's
/// finest grid of Fig. 9 that a 100-insect reference of a few hundred frames fills).
pub const DENSITY_CELLS: usize = 16;

/// The positions of every frame, by frame index.
fn frames(tracks: &Tracks) -> BTreeMap<i64, Vec<[f64; 3]>> {
    let mut out: BTreeMap<i64, Vec<[f64; 3]>> = BTreeMap::new();
    for samples in tracks.by_id.values() {
        for &(k, p) in samples {
            out.entry(k).or_default().push(p);
        }
    }
    out
}

/// The mean over frames of the insects' mean distance to that frame's centroid (li2015
/// Fig. 8); 0 without samples.
pub fn centroid_distance(tracks: &Tracks) -> f64 {
    let f = frames(tracks);
    if f.is_empty() {
        return 0.0;
    }
    f.values().map(|p| mean_centroid_distance(p)).sum::<f64>() / f.len() as f64
}

/// The total variation ½ Σ_c |p_c − q_c| between the accumulated densities of `a` and `b`
/// (li2015 Figs. 4 and 9: each set's samples counted per cell and normalised) on a grid of
/// `cells`³ equal cells over the bounding box of both sets: 0 for the same spread, 1 for sets
/// that share no cell. `None` when either set is empty.
pub fn density_tv(a: &Tracks, b: &Tracks, cells: usize) -> Option<f64> {
    if a.is_empty() || b.is_empty() || cells == 0 {
        return None;
    }
    let all = || {
        [a, b]
            .into_iter()
            .flat_map(|t| t.by_id.values().flatten().map(|s| s.1))
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in all() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let cell_of = |p: [f64; 3]| {
        (0..3).fold(0, |index, k| {
            let span = hi[k] - lo[k];
            let i = if span > 0.0 {
                (((p[k] - lo[k]) / span * cells as f64) as usize).min(cells - 1)
            } else {
                0
            };
            index * cells + i
        })
    };
    let histogram = |t: &Tracks| {
        let mut h = vec![0u64; cells.pow(3)];
        for s in t.by_id.values().flatten() {
            h[cell_of(s.1)] += 1;
        }
        (h, t.len() as f64)
    };
    let ((ha, na), (hb, nb)) = (histogram(a), histogram(b));
    let sum: f64 = ha
        .iter()
        .zip(&hb)
        .map(|(&x, &y)| (x as f64 / na - y as f64 / nb).abs())
        .sum();
    Some(0.5 * sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cloud(centre: [f64; 3], radius: f64, seed: u32) -> Tracks {
        let u = |id: u64, k: i64, d: u32| {
            f64::from(swarm_core::rand::rand(seed, id as u32, k as u32, d)) / f64::from(u32::MAX)
                - 0.5
        };
        Tracks::from_samples(
            0.1,
            (0..30u64).flat_map(|id| {
                (0..40i64).map(move |k| {
                    let p = [0, 1, 2].map(|d| centre[d as usize] + 2.0 * radius * u(id, k, d));
                    (id, k, p)
                })
            }),
        )
    }

    /// Two insects on opposite sides of their centroid at distance 1, then 3: 2 on average.
    #[test]
    fn centroid_distance_averages_over_frames() {
        let t = Tracks::from_samples(
            0.1,
            [
                (0, 0, [-1.0, 0.0, 0.0]),
                (1, 0, [1.0, 0.0, 0.0]),
                (0, 1, [0.0, -3.0, 5.0]),
                (1, 1, [0.0, 3.0, 5.0]),
            ],
        );
        assert!((centroid_distance(&t) - 2.0).abs() < 1e-12);
        assert_eq!(centroid_distance(&Tracks::from_samples(0.1, [])), 0.0);
        // A cloud twice as wide is about twice as far from its centroid.
        let ratio = centroid_distance(&cloud([0.0; 3], 2.0, 1))
            / centroid_distance(&cloud([0.0; 3], 1.0, 1));
        assert!((ratio - 2.0).abs() < 0.05, "{ratio}");
    }

    /// The same spread is close (0 for itself), a shifted one far, disjoint ones 1; the
    /// measure is symmetric.
    #[test]
    fn density_tv_tells_spreads_apart() {
        let a = cloud([0.0; 3], 1.0, 1);
        assert_eq!(density_tv(&a, &a, DENSITY_CELLS), Some(0.0));
        // 1,200 samples each, on 4³ cells.
        let same = density_tv(&a, &cloud([0.0; 3], 1.0, 2), 4).unwrap();
        let shifted = density_tv(&a, &cloud([0.8, 0.0, 0.0], 1.0, 2), 4).unwrap();
        let wide = density_tv(&a, &cloud([0.0; 3], 2.0, 2), 4).unwrap();
        assert!(
            same < 0.2 && shifted > same + 0.2 && wide > same + 0.2,
            "{same} {shifted} {wide}"
        );
        let far = cloud([10.0, 0.0, 0.0], 1.0, 2);
        assert!((density_tv(&a, &far, 8).unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(density_tv(&a, &far, 8), density_tv(&far, &a, 8));
        assert_eq!(density_tv(&a, &Tracks::from_samples(0.1, []), 8), None);
    }
}
