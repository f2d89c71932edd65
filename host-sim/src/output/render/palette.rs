//! The renderer's one fixed palette of indexed colours: background and ink, object kinds, and
//! agent colours by label or group, each in shades fading towards the background.

use super::ColorBy;
use crate::output::scene::{Scene, ShapeKind};

/// Number of shades per agent colour: 0 full, then fading towards the background.
pub(super) const SHADES: usize = 5;
/// How far each shade is blended towards the background, in percent.
const SHADE_MIX: [u32; SHADES] = [0, 35, 55, 72, 86];

const BG: [u8; 3] = [0xf7, 0xf5, 0xef];
const OUTSIDE: [u8; 3] = [0xe4, 0xe1, 0xd8];
const BORDER: [u8; 3] = [0xa8, 0xa4, 0x98];
pub(super) const INK: [u8; 3] = [0x20, 0x20, 0x20];
const PAPER: [u8; 3] = [0xff, 0xff, 0xff];

/// Agent colours by label: 0 nothing grey, 1 food green, 2 nest blue, then others.
const LABEL_COLORS: [[u8; 3]; 8] = [
    [0x70, 0x70, 0x70],
    [0x1a, 0x9a, 0x2c],
    [0x1f, 0x5f, 0xd0],
    [0xd6, 0x27, 0x28],
    [0x94, 0x67, 0xbd],
    [0x17, 0xbe, 0xcf],
    [0xbc, 0xbd, 0x22],
    [0xe3, 0x77, 0xc2],
];

/// Agent colours by group.
/// (No orange, green or red: those are targets, food and disturbances.)
const GROUP_COLORS: [[u8; 3]; 8] = [
    [0x1f, 0x77, 0xb4],
    [0xc0, 0x3a, 0xa8],
    [0x17, 0xa8, 0xb8],
    [0x8c, 0x56, 0x4b],
    [0x6a, 0x4c, 0xc4],
    [0x9a, 0x9b, 0x1a],
    [0x39, 0x3b, 0x79],
    [0xe3, 0x77, 0xc2],
];

/// Object colours, in [`ShapeKind::ALL`] order.
const KIND_COLORS: [[u8; 3]; 8] = [
    [0x5c, 0x3a, 0x1e], // nest: dark brown
    [0x6c, 0xc0, 0x5a], // food: green
    [0x8c, 0x8c, 0x8c], // rock: grey
    [0xd6, 0x27, 0x28], // disturbance: red (ring)
    [0x94, 0x67, 0xbd], // waypoint: purple (ring)
    [0xff, 0x8c, 0x00], // target: orange
    [0x40, 0x40, 0x40], // shaft: dark grey
    [0x6c, 0x7a, 0x89], // sphere: slate
];

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
