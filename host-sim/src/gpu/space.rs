//! The 3D world's corrections on the GPU (`shaders/space.wgsl`): the obstacles' confinement
//! boxes in the agents' scalar, so that `space_confine` decides as
//! [`confine`](crate::space::confine) does in `f64` (shared by the bee and wang2014 engines).

use swarm_core::ScalarKind;

use super::words::Word;
use crate::scalar::SimScalar;
use crate::space::BeeObstacle;

/// Words of an obstacle's confinement box (`SPACE_BOX_WORDS` in `space.wgsl`, [`confine_boxes`]).
pub const BOX_WORDS: usize = 7;

/// The next value of `S` above (`up`) or below `v`, if there is one.
fn adjacent<S: Word>(v: S, up: bool) -> Option<S> {
    match S::KIND {
        ScalarKind::I16F16 => {
            let r = v.to_word() as i32;
            let r = if up {
                r.checked_add(1)?
            } else {
                r.checked_sub(1)?
            };
            Some(S::from_word(r as u32))
        }
        ScalarKind::F32 => {
            let f = f32::from_bits(v.to_word());
            Some(S::from_word(
                if up { f.next_up() } else { f.next_down() }.to_bits(),
            ))
        }
    }
}

/// The least value of `S` at or above `x` (`up`), or the greatest at or below it; `None` if
/// there is none. A value of `S` converts to `f64` exactly, so for every `p` of `S`, `p ≥ x` in
/// `f64` exactly when `p ≥` the first (and `p ≤ x` when `p ≤` the second).
fn bound<S: Word + SimScalar>(x: f64, up: bool) -> Option<S> {
    // The nearest value (saturating), then one step if it lies on the wrong side.
    let v = S::from_f64(x);
    let wrong = |v: S| if up { v.to_f64() < x } else { v.to_f64() > x };
    if !wrong(v) {
        return Some(v);
    }
    let v = adjacent(v, up)?;
    (!wrong(v)).then_some(v)
}

/// Every obstacle's confinement box in `S` ([`BOX_WORDS`] words each, `space_may_be_within`):
/// `BeeObstacle::may_be_within(p, 0.0)`, which the CPU's `confine` computes in `f64` (`p` within
/// the obstacle's bounding box widened by 1e-3), as bounds in `S` that give the same answer for
/// every point of `S` (`bound`): a flag if no point passes, then per axis the least value at
/// or above the box's low side less the margin, and the greatest at or below its high side plus
/// the margin.
pub fn confine_boxes<S: Word + SimScalar>(obstacles: &[BeeObstacle]) -> Vec<u32> {
    // may_be_within's `range + 1e-3` for a range of 0.
    let margin = 0.0f64 + 1e-3;
    let mut out = Vec::with_capacity(obstacles.len() * BOX_WORDS);
    for o in obstacles {
        let (lo, hi) = o.shape.aabb();
        let lo: Vec<Option<S>> = lo
            .iter()
            .map(|&l| bound(f64::from(l) - margin, true))
            .collect();
        let hi: Vec<Option<S>> = hi
            .iter()
            .map(|&h| bound(f64::from(h) + margin, false))
            .collect();
        let never = lo.iter().chain(&hi).any(Option::is_none);
        out.push(u32::from(never));
        for v in lo.iter().chain(&hi) {
            out.push(v.map_or(0, Word::to_word));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::a3;
    use crate::space::Shape3;
    use swarm_core::{Fx, Vec3};

    /// `bound` gives the least value at or above (greatest at or below) an `f64`, for both
    /// scalars, at their grids' points, between them, and past their ranges.
    #[test]
    fn bounds_are_the_nearest_values_on_the_right_side() {
        fn check<S: Word + SimScalar>(x: f64) {
            for up in [true, false] {
                match bound::<S>(x, up) {
                    Some(v) => {
                        let f = v.to_f64();
                        assert!(if up { f >= x } else { f <= x }, "{x} {up} {f}");
                        if let Some(w) = adjacent(v, !up) {
                            let g = w.to_f64();
                            assert!(if up { g < x } else { g > x }, "{x} {up}: {g} also");
                        }
                    }
                    None => {
                        let edge = S::from_word(match (S::KIND, up) {
                            (ScalarKind::I16F16, true) => i32::MAX as u32,
                            (ScalarKind::I16F16, false) => i32::MIN as u32,
                            (ScalarKind::F32, true) => f32::MAX.to_bits(),
                            (ScalarKind::F32, false) => f32::MIN.to_bits(),
                        });
                        assert!(if up {
                            edge.to_f64() < x
                        } else {
                            edge.to_f64() > x
                        });
                    }
                }
            }
        }
        let ulp = 1.0 / 65536.0;
        for base in [
            0.0f64, 1.0, -1.0, 30.0, -10.0, 72.0, 1e-3, 16_000.0, 32_767.99,
        ] {
            for d in [
                0.0,
                1e-3,
                -1e-3,
                ulp,
                -ulp,
                ulp / 2.0,
                -ulp / 2.0,
                ulp / 3.0,
                1e-9,
                -1e-9,
                1e-12,
            ] {
                check::<Fx>(base + d);
                check::<f32>(base + d);
            }
        }
        for x in [40_000.0, -40_000.0, 1e39, -1e39, 3.4e38] {
            check::<Fx>(x);
            check::<f32>(x);
        }
    }

    /// The confinement boxes answer as `may_be_within(p, 0.0)` for points of `S` at and around
    /// every side of every shape's box (the margin's edges, an ulp either side).
    #[test]
    fn confinement_boxes_are_may_be_within() {
        fn check<S: Word + SimScalar>() -> usize {
            let mut obstacles = Vec::new();
            let shapes = [
                Shape3::Sphere {
                    center: [14.3, 8.1, 24.7],
                    radius: 2.05,
                },
                Shape3::Box {
                    min: [0.0; 3],
                    max: [60.0, 1.0, 60.0],
                },
                Shape3::Shaft {
                    center: [24.1, 35.9],
                    radius: 1.5,
                    y_min: 0.0,
                    y_max: 30.0,
                },
            ];
            for (k, s) in shapes.into_iter().enumerate() {
                obstacles.push(BeeObstacle::new(k as u16, format!("o{k}"), s, true));
            }
            let words = confine_boxes::<S>(&obstacles);
            let mut tested = 0;
            for (k, o) in obstacles.iter().enumerate() {
                let b = &words[k * BOX_WORDS..(k + 1) * BOX_WORDS];
                let (lo, hi) = o.shape.aabb();
                let mut xs = Vec::new();
                for e in lo.iter().chain(&hi) {
                    for m in [-1e-3f64, 0.0, 1e-3] {
                        let c = S::from_f64(f64::from(*e) + m);
                        xs.push(c);
                        xs.extend(adjacent(c, true));
                        xs.extend(adjacent(c, false));
                    }
                }
                let mid: [S; 3] = std::array::from_fn(|a| S::from_f32((lo[a] + hi[a]) / 2.0));
                for axis in 0..3 {
                    for &x in &xs {
                        let mut p = Vec3::new(mid[0], mid[1], mid[2]);
                        match axis {
                            0 => p.x = x,
                            1 => p.y = x,
                            _ => p.z = x,
                        }
                        let gpu = b[0] == 0
                            && [p.x, p.y, p.z].iter().enumerate().all(|(a, &c)| {
                                let (l, h) = (S::from_word(b[1 + a]), S::from_word(b[4 + a]));
                                c >= l && c <= h
                            });
                        assert_eq!(gpu, o.may_be_within(a3(p), 0.0), "{k} {:?}", a3(p));
                        tested += 1;
                    }
                }
            }
            tested
        }
        assert!(check::<Fx>() > 100);
        assert!(check::<f32>() > 100);
    }
}
