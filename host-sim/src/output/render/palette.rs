//! The renderer's one fixed palette of indexed colours: background and ink, object kinds, and
//! agent colours by label or group, each in shades fading towards the background.

use super::ColorBy;
use crate::output::scene::{Scene, ShapeKind};

/// Number of shades per agent colour: 0 full, then fading towards the background.
pub(super) const SHADES: usize = 5;
/// How far each shade is blended towards the background, in percent.
const SHADE_MIX: [u32; SHADES] = [0, 35, 55, 72, 86];

/// `0xRRGGBB` as RGB bytes.
const fn rgb(hex: u32) -> [u8; 3] {
    [(hex >> 16) as u8, (hex >> 8) as u8, hex as u8]
}

/// Each `0xRRGGBB` as RGB bytes.
const fn rgbs<const N: usize>(hex: [u32; N]) -> [[u8; 3]; N] {
    let mut out = [[0; 3]; N];
    let mut i = 0;
    while i < N {
        out[i] = rgb(hex[i]);
        i += 1;
    }
    out
}

const BG: [u8; 3] = rgb(0xf7f5ef);
const OUTSIDE: [u8; 3] = rgb(0xe4e1d8);
const BORDER: [u8; 3] = rgb(0xa8a498);
pub(super) const INK: [u8; 3] = rgb(0x202020);
const PAPER: [u8; 3] = rgb(0xffffff);

/// Agent colours by label: 0 nothing grey, 1 food green, 2 nest blue, then others.
const LABEL_COLORS: [[u8; 3]; 8] = rgbs([
    0x707070, 0x1a9a2c, 0x1f5fd0, 0xd62728, 0x9467bd, 0x17becf, 0xbcbd22, 0xe377c2,
]);

/// Agent colours by group.
/// (No orange, green or red: those are targets, food and disturbances.)
const GROUP_COLORS: [[u8; 3]; 8] = rgbs([
    0x1f77b4, 0xc03aa8, 0x17a8b8, 0x8c564b, 0x6a4cc4, 0x9a9b1a, 0x393b79, 0xe377c2,
]);

/// Object colours, in [`ShapeKind::ALL`] order.
const KIND_COLORS: [[u8; 3]; 8] = rgbs([
    0x5c3a1e, // nest: dark brown
    0x6cc05a, // food: green
    0x8c8c8c, // rock: grey
    0xd62728, // disturbance: red (ring)
    0x9467bd, // waypoint: purple (ring)
    0xff8c00, // target: orange
    0x404040, // shaft: dark grey
    0x6c7a89, // sphere: slate
]);

// Palette indices.
pub(super) const I_BG: u8 = 0;
pub(super) const I_OUTSIDE: u8 = 1;
pub(super) const I_BORDER: u8 = 2;
pub(super) const I_INK: u8 = 3;
pub(super) const I_PAPER: u8 = 4;
const I_KIND: u8 = 8;
const I_LABEL: u8 = 16;
const I_GROUP: u8 = I_LABEL + (8 * SHADES) as u8;
/// Palette size (a power of two, as GIF wants).
const PALETTE_LEN: usize = 128;

pub(super) fn kind_index(k: ShapeKind) -> u8 {
    I_KIND + ShapeKind::ALL.iter().position(|&x| x == k).unwrap_or(0) as u8
}

fn mix(c: [u8; 3], to: [u8; 3], pct: u32) -> [u8; 3] {
    let f = |a: u8, b: u8| ((u32::from(a) * (100 - pct) + u32::from(b) * pct + 50) / 100) as u8;
    [f(c[0], to[0]), f(c[1], to[1]), f(c[2], to[2])]
}

/// The fixed palette, `PALETTE_LEN` RGB triples.
pub(super) fn palette() -> Vec<[u8; 3]> {
    let mut p = vec![[0u8; 3]; PALETTE_LEN];
    p[I_BG as usize] = BG;
    p[I_OUTSIDE as usize] = OUTSIDE;
    p[I_BORDER as usize] = BORDER;
    p[I_INK as usize] = INK;
    p[I_PAPER as usize] = PAPER;
    for (i, c) in KIND_COLORS.iter().enumerate() {
        p[I_KIND as usize + i] = *c;
    }
    for (base, colors) in [(I_LABEL, &LABEL_COLORS), (I_GROUP, &GROUP_COLORS)] {
        for (i, c) in colors.iter().enumerate() {
            for (s, pct) in SHADE_MIX.iter().enumerate() {
                p[base as usize + i * SHADES + s] = mix(*c, BG, *pct);
            }
        }
    }
    p
}

/// The RGB colour the renderer uses for an object kind (e.g. to check a picture).
pub fn kind_color(kind: ShapeKind) -> [u8; 3] {
    palette()[kind_index(kind) as usize]
}

/// The RGB colour (full shade) of agent colour slot `code` (a label or group) for `by`.
pub fn agent_color(by: ColorBy, code: u16) -> [u8; 3] {
    let base = if by == ColorBy::Group {
        GROUP_COLORS
    } else {
        LABEL_COLORS
    };
    base[code as usize % 8]
}

/// Resolved colouring: `Label` or `Group`.
pub(super) fn resolve_color_by(by: ColorBy, scene: &Scene) -> ColorBy {
    match by {
        ColorBy::Auto if scene.dim == 3 => ColorBy::Group,
        ColorBy::Auto => ColorBy::Label,
        b => b,
    }
}

#[inline]
pub(super) fn agent_index(by: ColorBy, label: u8, group: u16, shade: usize) -> u8 {
    let (base, slot) = if by == ColorBy::Group {
        (I_GROUP, group as usize % 8)
    } else {
        (I_LABEL, label as usize % 8)
    };
    base + (slot * SHADES + shade) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palette_is_small_and_distinct() {
        let p = palette();
        assert_eq!(p.len(), PALETTE_LEN);
        assert!((I_GROUP as usize + 8 * SHADES) <= PALETTE_LEN);
        let kinds: std::collections::BTreeSet<[u8; 3]> = KIND_COLORS.iter().copied().collect();
        assert_eq!(kinds.len(), KIND_COLORS.len());
    }
}
