//! Pictures of a run: a PNG snapshot of the last frame with fading trails, and an animated GIF.
//!
//! Everything is drawn by hand with simple raster operations (filled discs, rings, Bresenham
//! lines, scanline polygon fill, a 3×5 pixel font) onto an indexed canvas whose colours come
//! from one fixed palette. The PNG is that canvas expanded to RGB (an [`image::RgbImage`]); the
//! GIF uses the palette directly as its global colour table, so no quantisation is needed and
//! the output is deterministic: the same inputs give the same bytes.
//!
//! 2D worlds are drawn with x to the right and y up; 3D worlds as a top view (looking down the
//! y axis) with x to the right and z down, and below it a side view (looking along +z: x to the
//! right, y up) in which every bee is drawn as its body along its heading (a line from the dot
//! toward where it flies) and its wings as a dark bar through the dot along the rolled wing axis
//! cos(roll)·s − sin(roll)·up (s = heading × up, the bee's right), projected: a bee flying
//! across the view shows its roll as the tilt of the bar (positive roll: right wing down).
//! Shafts are drawn full height in the side view.

use std::io;
use std::path::Path;

use image::ImageEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

use super::atomic::write_atomic;
use super::error::{OutputError, Result};
use super::frames::{Frame, check_frames, label_name};
use super::scene::{Geometry, Scene, Shape, ShapeKind};

/// How agents are coloured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ColorBy {
    /// By label in 2D worlds (ants), by group in 3D worlds (bees).
    #[default]
    Auto,
    /// By state label (ants: nothing grey, food green, nest blue).
    Label,
    /// By agent group.
    Group,
}

/// Rendering settings.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// PNG width in pixels (height follows the world's aspect ratio, at most 4× the width).
    pub width: u32,
    /// PNG: trail length in recorded frames.
    pub trail: usize,
    /// Trails are drawn for at most this many agents (an evenly spaced subset by id).
    pub max_trail_agents: usize,
    /// Agent dot radius in PNG pixels; `None` picks one from the agent count.
    pub agent_radius_px: Option<f32>,
    /// PNG: draw a legend (colour swatches with names) and the step.
    pub legend: bool,
    /// Agent colours.
    pub color_by: ColorBy,
    /// GIF width in pixels.
    pub gif_width: u32,
    /// GIF: at most this many frames (evenly subsampled, first and last kept).
    pub gif_max_frames: usize,
    /// GIF: trail length, in shown GIF frames.
    pub gif_trail: usize,
    /// GIF: delay between frames in hundredths of a second.
    pub gif_delay_cs: u16,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            width: 1024,
            trail: 60,
            max_trail_agents: 2000,
            agent_radius_px: None,
            legend: true,
            color_by: ColorBy::Auto,
            gif_width: 480,
            gif_max_frames: 150,
            gif_trail: 6,
            gif_delay_cs: 6,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Palette

/// Number of shades per agent colour: 0 full, then fading towards the background.
const SHADES: usize = 5;
/// How far each shade is blended towards the background, in percent.
const SHADE_MIX: [u32; SHADES] = [0, 35, 55, 72, 86];

const BG: [u8; 3] = [0xf7, 0xf5, 0xef];
const OUTSIDE: [u8; 3] = [0xe4, 0xe1, 0xd8];
const BORDER: [u8; 3] = [0xa8, 0xa4, 0x98];
const INK: [u8; 3] = [0x20, 0x20, 0x20];
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
const I_BG: u8 = 0;
const I_OUTSIDE: u8 = 1;
const I_BORDER: u8 = 2;
const I_INK: u8 = 3;
const I_PAPER: u8 = 4;
const I_KIND: u8 = 8;
const I_LABEL: u8 = 16;
const I_GROUP: u8 = I_LABEL + (8 * SHADES) as u8;
/// Palette size (a power of two, as GIF wants).
const PALETTE_LEN: usize = 128;

fn kind_index(k: ShapeKind) -> u8 {
    I_KIND + ShapeKind::ALL.iter().position(|&x| x == k).unwrap_or(0) as u8
}

fn mix(c: [u8; 3], to: [u8; 3], pct: u32) -> [u8; 3] {
    let f = |a: u8, b: u8| ((u32::from(a) * (100 - pct) + u32::from(b) * pct + 50) / 100) as u8;
    [f(c[0], to[0]), f(c[1], to[1]), f(c[2], to[2])]
}

/// The fixed palette, `PALETTE_LEN` RGB triples.
fn palette() -> Vec<[u8; 3]> {
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

// ---------------------------------------------------------------------------------------------
// Canvas

/// An indexed-colour raster.
struct Canvas {
    w: usize,
    h: usize,
    px: Vec<u8>,
}

impl Canvas {
    fn new(w: usize, h: usize, fill: u8) -> Self {
        Self {
            w,
            h,
            px: vec![fill; w * h],
        }
    }

    #[inline]
    fn set(&mut self, x: i64, y: i64, c: u8) {
        if x >= 0 && y >= 0 && (x as usize) < self.w && (y as usize) < self.h {
            self.px[y as usize * self.w + x as usize] = c;
        }
    }

    fn hspan(&mut self, x0: i64, x1: i64, y: i64, c: u8) {
        if y < 0 || y as usize >= self.h {
            return;
        }
        let x0 = x0.max(0);
        let x1 = x1.min(self.w as i64 - 1);
        if x0 > x1 {
            return;
        }
        let row = y as usize * self.w;
        self.px[row + x0 as usize..=row + x1 as usize].fill(c);
    }

    fn rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: u8) {
        for y in y0..=y1 {
            self.hspan(x0, x1, y, c);
        }
    }

    fn rect_outline(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: u8) {
        self.hspan(x0, x1, y0, c);
        self.hspan(x0, x1, y1, c);
        for y in y0..=y1 {
            self.set(x0, y, c);
            self.set(x1, y, c);
        }
    }

    /// A filled disc of radius `r` (pixel centres at integer coordinates).
    fn disc(&mut self, cx: f32, cy: f32, r: f32, c: u8) {
        if r < 0.75 {
            self.set(cx.round() as i64, cy.round() as i64, c);
            return;
        }
        let y0 = (cy - r).ceil() as i64;
        let y1 = (cy + r).floor() as i64;
        for y in y0.max(-1)..=y1.min(self.h as i64) {
            let dy = y as f32 - cy;
            let dx = (r * r - dy * dy).max(0.0).sqrt();
            self.hspan((cx - dx).ceil() as i64, (cx + dx).floor() as i64, y, c);
        }
    }

    /// A ring between radii `r - t` and `r`.
    fn ring(&mut self, cx: f32, cy: f32, r: f32, t: f32, c: u8) {
        let ri = (r - t).max(0.0);
        let (r2, ri2) = (r * r, ri * ri);
        let y0 = ((cy - r).ceil() as i64).max(0);
        let y1 = ((cy + r).floor() as i64).min(self.h as i64 - 1);
        let x0 = ((cx - r).ceil() as i64).max(0);
        let x1 = ((cx + r).floor() as i64).min(self.w as i64 - 1);
        for y in y0..=y1 {
            let dy = y as f32 - cy;
            for x in x0..=x1 {
                let dx = x as f32 - cx;
                let d2 = dx * dx + dy * dy;
                if d2 <= r2 && d2 >= ri2 {
                    self.px[y as usize * self.w + x as usize] = c;
                }
            }
        }
    }

    /// A one-pixel line (Bresenham), clipped to the canvas.
    fn line(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, c: u8) {
        let (mut x, mut y) = (x0.round() as i64, y0.round() as i64);
        let (xe, ye) = (x1.round() as i64, y1.round() as i64);
        let (w, h) = (self.w as i64, self.h as i64);
        if (x < 0 && xe < 0) || (y < 0 && ye < 0) || (x >= w && xe >= w) || (y >= h && ye >= h) {
            return;
        }
        let dx = (xe - x).abs();
        let dy = -(ye - y).abs();
        let sx = if x < xe { 1 } else { -1 };
        let sy = if y < ye { 1 } else { -1 };
        let mut err = dx + dy;
        loop {
            self.set(x, y, c);
            if x == xe && y == ye {
                break;
            }
            let e2 = 2 * err;
            if e2 >= dy {
                err += dy;
                x += sx;
            }
            if e2 <= dx {
                err += dx;
                y += sy;
            }
        }
    }

    /// Scanline fill of a polygon (even-odd rule), pixel centres at integer coordinates.
    fn polygon(&mut self, pts: &[[f32; 2]], c: u8) {
        if pts.len() < 3 {
            return;
        }
        let ymin = pts.iter().map(|p| p[1]).fold(f32::INFINITY, f32::min);
        let ymax = pts.iter().map(|p| p[1]).fold(f32::NEG_INFINITY, f32::max);
        let y0 = (ymin.ceil() as i64).max(0);
        let y1 = (ymax.floor() as i64).min(self.h as i64 - 1);
        let mut xs: Vec<f32> = Vec::new();
        for y in y0..=y1 {
            let yf = y as f32;
            xs.clear();
            for i in 0..pts.len() {
                let a = pts[i];
                let b = pts[(i + 1) % pts.len()];
                // Half-open rule so shared vertices count once.
                if (a[1] <= yf && b[1] > yf) || (b[1] <= yf && a[1] > yf) {
                    xs.push(a[0] + (yf - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
                }
            }
            xs.sort_by(f32::total_cmp);
            for pair in xs.chunks_exact(2) {
                self.hspan(pair[0].ceil() as i64, pair[1].floor() as i64, y, c);
            }
        }
    }

    /// Text in the 3×5 font, each font pixel `scale`×`scale`; returns the width drawn.
    fn text(&mut self, x: i64, y: i64, s: &str, scale: i64, c: u8) -> i64 {
        let mut cx = x;
        for ch in s.chars() {
            let g = glyph(ch);
            for (row, bits) in g.iter().enumerate() {
                for col in 0..3 {
                    if bits & (0b100 >> col) != 0 {
                        self.rect(
                            cx + col * scale,
                            y + row as i64 * scale,
                            cx + col * scale + scale - 1,
                            y + row as i64 * scale + scale - 1,
                            c,
                        );
                    }
                }
            }
            cx += 4 * scale;
        }
        cx - x
    }
}

/// Width in pixels of `s` in the 3×5 font at `scale`.
fn text_width(s: &str, scale: i64) -> i64 {
    s.chars().count() as i64 * 4 * scale - scale
}

/// 3×5 glyphs, one row per entry, bit 2 = left column.
fn glyph(c: char) -> [u8; 5] {
    match c.to_ascii_uppercase() {
        'A' => [0b010, 0b101, 0b111, 0b101, 0b101],
        'B' => [0b110, 0b101, 0b110, 0b101, 0b110],
        'C' => [0b011, 0b100, 0b100, 0b100, 0b011],
        'D' => [0b110, 0b101, 0b101, 0b101, 0b110],
        'E' => [0b111, 0b100, 0b110, 0b100, 0b111],
        'F' => [0b111, 0b100, 0b110, 0b100, 0b100],
        'G' => [0b011, 0b100, 0b101, 0b101, 0b011],
        'H' => [0b101, 0b101, 0b111, 0b101, 0b101],
        'I' => [0b111, 0b010, 0b010, 0b010, 0b111],
        'J' => [0b001, 0b001, 0b001, 0b101, 0b010],
        'K' => [0b101, 0b101, 0b110, 0b101, 0b101],
        'L' => [0b100, 0b100, 0b100, 0b100, 0b111],
        'M' => [0b101, 0b111, 0b111, 0b101, 0b101],
        'N' => [0b110, 0b101, 0b101, 0b101, 0b101],
        'O' => [0b010, 0b101, 0b101, 0b101, 0b010],
        'P' => [0b110, 0b101, 0b110, 0b100, 0b100],
        'Q' => [0b010, 0b101, 0b101, 0b110, 0b011],
        'R' => [0b110, 0b101, 0b110, 0b101, 0b101],
        'S' => [0b011, 0b100, 0b010, 0b001, 0b110],
        'T' => [0b111, 0b010, 0b010, 0b010, 0b010],
        'U' => [0b101, 0b101, 0b101, 0b101, 0b111],
        'V' => [0b101, 0b101, 0b101, 0b101, 0b010],
        'W' => [0b101, 0b101, 0b111, 0b111, 0b101],
        'X' => [0b101, 0b101, 0b010, 0b101, 0b101],
        'Y' => [0b101, 0b101, 0b010, 0b010, 0b010],
        'Z' => [0b111, 0b001, 0b010, 0b100, 0b111],
        '0' => [0b111, 0b101, 0b101, 0b101, 0b111],
        '1' => [0b010, 0b110, 0b010, 0b010, 0b111],
        '2' => [0b110, 0b001, 0b010, 0b100, 0b111],
        '3' => [0b110, 0b001, 0b010, 0b001, 0b110],
        '4' => [0b101, 0b101, 0b111, 0b001, 0b001],
        '5' => [0b111, 0b100, 0b110, 0b001, 0b110],
        '6' => [0b011, 0b100, 0b111, 0b101, 0b111],
        '7' => [0b111, 0b001, 0b010, 0b010, 0b010],
        '8' => [0b111, 0b101, 0b111, 0b101, 0b111],
        '9' => [0b111, 0b101, 0b111, 0b001, 0b110],
        '-' => [0b000, 0b000, 0b111, 0b000, 0b000],
        '.' => [0b000, 0b000, 0b000, 0b000, 0b010],
        ':' => [0b000, 0b010, 0b000, 0b010, 0b000],
        '/' => [0b001, 0b001, 0b010, 0b100, 0b100],
        '_' => [0b000, 0b000, 0b000, 0b000, 0b111],
        _ => [0; 5],
    }
}

// ---------------------------------------------------------------------------------------------
// World → pixels

/// Maps drawing-plane world coordinates to pixels.
#[derive(Clone, Copy, Debug)]
struct View {
    w: usize,
    h: usize,
    u0: f32,
    v0: f32,
    scale: f32,
    ox: f32,
    oy: f32,
    /// World extent in pixels along v (for flipping).
    vspan: f32,
    flip: bool,
    /// The side view of a 3D world (x, y) instead of its plan.
    side: bool,
}

impl View {
    fn new(scene: &Scene, width: u32) -> Self {
        let width = width.clamp(32, 16384) as f32;
        let lo = scene.plan(scene.min);
        let hi = scene.plan(scene.max);
        let (du, dv) = ((hi[0] - lo[0]).max(1e-6), (hi[1] - lo[1]).max(1e-6));
        let margin = (width * 0.012).round().max(2.0);
        let inner_w = width - 2.0 * margin;
        let scale = (inner_w / du).min((4.0 * width - 2.0 * margin) / dv);
        let h = (dv * scale + 2.0 * margin).round().max(8.0);
        let ox = margin + ((inner_w - du * scale) / 2.0).max(0.0);
        Self {
            w: width as usize,
            h: h as usize,
            u0: lo[0],
            v0: lo[1],
            scale,
            ox,
            oy: margin,
            vspan: dv * scale,
            flip: scene.dim != 3,
            side: false,
        }
    }

    /// The side view of a 3D scene (x to the right, y up) at the same scale as its plan `top`.
    fn side(scene: &Scene, top: &View) -> Self {
        let dv = (scene.max[1] - scene.min[1]).max(1e-6);
        let margin = top.oy;
        // Room for the panel's title above the world.
        let title = 9.0 * (top.w as f32 / 400.0).max(1.0).floor();
        let h = (dv * top.scale + 2.0 * margin + title).round().max(8.0);
        View {
            w: top.w,
            h: h as usize,
            u0: scene.min[0],
            v0: scene.min[1],
            scale: top.scale,
            ox: top.ox,
            oy: margin + title,
            vspan: dv * top.scale,
            flip: true,
            side: true,
        }
    }

    #[inline]
    fn px(&self, p: [f32; 2]) -> (f32, f32) {
        let x = self.ox + (p[0] - self.u0) * self.scale;
        let v = (p[1] - self.v0) * self.scale;
        let y = if self.flip {
            self.oy + self.vspan - v
        } else {
            self.oy + v
        };
        (x, y)
    }

    #[inline]
    fn world(&self, scene: &Scene, p: [f32; 3]) -> (f32, f32) {
        if self.side {
            self.px([p[0], p[1]])
        } else {
            self.px(scene.plan(p))
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Drawing a frame

/// The world area and its border on the outside colour.
fn draw_base(canvas: &mut Canvas, view: &View, scene: &Scene) {
    canvas.px.fill(I_OUTSIDE);
    let (x0, y0) = view.world(scene, scene.min);
    let (x1, y1) = view.world(scene, scene.max);
    let (xa, xb) = (x0.min(x1).round() as i64, x0.max(x1).round() as i64);
    let (ya, yb) = (y0.min(y1).round() as i64, y0.max(y1).round() as i64);
    canvas.rect(xa, ya, xb, yb, I_BG);
    canvas.rect_outline(xa - 1, ya - 1, xb + 1, yb + 1, I_BORDER);
}

/// Index meaning "nothing drawn here" in an overlay.
const CLEAR: u8 = 255;

/// The objects visible at `step` on a clear canvas: obstacles first, then nests, food and
/// targets (a nest on the ground box of a bee scene stays visible from above), then rings.
/// Drawn over the trails and under the agents.
fn draw_objects(canvas: &mut Canvas, view: &View, scene: &Scene, step: u32) {
    canvas.px.fill(CLEAR);
    let layer = |k: ShapeKind| match k {
        ShapeKind::Rock | ShapeKind::Shaft | ShapeKind::Sphere => 0,
        ShapeKind::Nest | ShapeKind::Food | ShapeKind::Target => 1,
        ShapeKind::Disturbance | ShapeKind::Waypoint => 2,
    };
    for l in 0..3 {
        for s in scene
            .shapes
            .iter()
            .filter(|s| layer(s.kind) == l && s.visible_at(step))
        {
            draw_shape(canvas, view, scene, s);
        }
    }
}

/// Copies the non-clear pixels of `overlay` onto `canvas`.
fn compose(canvas: &mut Canvas, overlay: &Canvas) {
    for (d, &s) in canvas.px.iter_mut().zip(&overlay.px) {
        if s != CLEAR {
            *d = s;
        }
    }
}

fn draw_shape(canvas: &mut Canvas, view: &View, scene: &Scene, s: &Shape) {
    let c = kind_index(s.kind);
    let ring_px = (view.w as f32 / 400.0).max(1.5);
    match &s.geom {
        Geometry::Circle { center, radius } if view.side && s.kind == ShapeKind::Shaft => {
            // A vertical shaft, full height.
            let (x0, y0) = view.world(scene, [center[0] - radius, scene.min[1], 0.0]);
            let (x1, y1) = view.world(scene, [center[0] + radius, scene.max[1], 0.0]);
            canvas.rect(
                x0.round() as i64,
                y1.min(y0).round() as i64,
                x1.round().max(x0.round() + 1.0) as i64,
                y0.max(y1).round() as i64,
                c,
            );
        }
        Geometry::Polygon { .. } if view.side => {}
        Geometry::Circle { center, radius } => {
            let (x, y) = view.world(scene, *center);
            let r = radius * view.scale;
            match s.kind {
                ShapeKind::Disturbance | ShapeKind::Waypoint => {
                    canvas.ring(x, y, r.max(2.0), ring_px, c)
                }
                ShapeKind::Nest | ShapeKind::Food | ShapeKind::Target => {
                    canvas.disc(x, y, r.max(2.0), c)
                }
                _ => canvas.disc(x, y, r.max(0.5), c),
            }
        }
        Geometry::Polygon { points } => {
            let pts: Vec<[f32; 2]> = points
                .iter()
                .map(|p| {
                    let (x, y) = view.px(*p);
                    [x, y]
                })
                .collect();
            canvas.polygon(&pts, c);
        }
        Geometry::Box { min, max } => {
            let (x0, y0) = view.world(scene, *min);
            let (x1, y1) = view.world(scene, *max);
            canvas.rect(
                x0.min(x1).round() as i64,
                y0.min(y1).round() as i64,
                x0.max(x1).round() as i64,
                y0.max(y1).round() as i64,
                c,
            );
        }
    }
}

/// Resolved colouring: `Label` or `Group`.
fn resolve_color_by(by: ColorBy, scene: &Scene) -> ColorBy {
    match by {
        ColorBy::Auto if scene.dim == 3 => ColorBy::Group,
        ColorBy::Auto => ColorBy::Label,
        b => b,
    }
}

#[inline]
fn agent_index(by: ColorBy, label: u8, group: u16, shade: usize) -> u8 {
    let (base, slot) = if by == ColorBy::Group {
        (I_GROUP, group as usize % 8)
    } else {
        (I_LABEL, label as usize % 8)
    };
    base + (slot * SHADES + shade) as u8
}

/// Draws the trails through `frames[idx]` for the agents `0, stride, 2·stride, ...`, oldest
/// segments first and most faded.
fn draw_trails(
    canvas: &mut Canvas,
    view: &View,
    scene: &Scene,
    frames: &[Frame],
    idx: &[usize],
    agent_stride: usize,
    by: ColorBy,
) {
    if idx.len() < 2 {
        return;
    }
    let segs = idx.len() - 1;
    let max_jump = (view.w.max(view.h) as f32) / 4.0;
    let n = frames[idx[0]].agents.len();
    for s in 0..segs {
        // Age: segs-1 (oldest) ... 0 (newest); shade 1 (newest) ... SHADES-1 (oldest).
        let age = segs - 1 - s;
        let shade = 1 + age * (SHADES - 1) / segs;
        let (fa, fb) = (&frames[idx[s]], &frames[idx[s + 1]]);
        for a in (0..n).step_by(agent_stride) {
            let (p, q) = (&fa.agents[a], &fb.agents[a]);
            let (x0, y0) = view.world(scene, p.pos);
            let (x1, y1) = view.world(scene, q.pos);
            if !(x0.is_finite() && y0.is_finite() && x1.is_finite() && y1.is_finite()) {
                continue;
            }
            if (x1 - x0).abs() > max_jump || (y1 - y0).abs() > max_jump {
                continue;
            }
            canvas.line(x0, y0, x1, y1, agent_index(by, q.label, q.group, shade));
        }
    }
}

fn draw_agents(
    canvas: &mut Canvas,
    view: &View,
    scene: &Scene,
    frame: &Frame,
    r: f32,
    by: ColorBy,
) {
    for a in &frame.agents {
        let (x, y) = view.world(scene, a.pos);
        if x.is_finite() && y.is_finite() {
            canvas.disc(x, y, r, agent_index(by, a.label, a.group, 0));
        }
    }
}

/// The side view's bees: each a dot, its body as a line along its heading and its wings as a
/// dark bar along the rolled wing axis, projected on (x, y) (see the module docs).
fn draw_bees_side(
    canvas: &mut Canvas,
    view: &View,
    scene: &Scene,
    frame: &Frame,
    r: f32,
    by: ColorBy,
) {
    let body = (3.0 * r).max(5.0);
    let wing = 0.7 * body;
    for a in &frame.agents {
        let (x, y) = view.world(scene, a.pos);
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        let c = agent_index(by, a.label, a.group, 0);
        let h = a.heading;
        // Screen y grows downward: a world direction (u, v) is (u, −v) on screen.
        canvas.line(x, y, x + body * h[0], y - body * h[1], c);
        // s = heading × up = (−h.z, 0, h.x), normalized; wing axis cos·s − sin·up.
        let len = h[0].hypot(h[2]);
        let (sx, _sz) = if len > 1e-6 {
            (-h[2] / len, h[0] / len)
        } else {
            (0.0, 1.0)
        };
        let (sin, cos) = a.roll.to_radians().sin_cos();
        let (wx, wy) = (cos * sx, -sin);
        canvas.line(
            x - wing * wx,
            y + wing * wy,
            x + wing * wx,
            y - wing * wy,
            I_INK,
        );
        canvas.disc(x, y, (0.6 * r).max(0.5), c);
    }
}

/// The side panel of a 3D scene at `frame`: world, shafts and objects, trails through
/// `frames[idx]`, the bees with heading and wings, and a title.
#[allow(clippy::too_many_arguments)]
fn side_canvas(
    view: &View,
    scene: &Scene,
    frames: &[Frame],
    idx: &[usize],
    stride: usize,
    frame: &Frame,
    r: f32,
    by: ColorBy,
) -> Canvas {
    let mut canvas = Canvas::new(view.w, view.h, I_BG);
    draw_base(&mut canvas, view, scene);
    draw_trails(&mut canvas, view, scene, frames, idx, stride, by);
    let mut objects = Canvas::new(view.w, view.h, CLEAR);
    draw_objects(&mut objects, view, scene, frame.step);
    compose(&mut canvas, &objects);
    draw_bees_side(&mut canvas, view, scene, frame, r, by);
    let scale = (view.w as i64 / 400).max(1);
    canvas.text(
        view.ox as i64,
        2 * scale,
        "side view - x right / y up - line: heading - bar: wings at the roll",
        scale,
        I_INK,
    );
    canvas
}

/// `top` with `bottom` below it (same width).
fn stack(top: Canvas, bottom: &Canvas) -> Canvas {
    let mut px = top.px;
    px.extend_from_slice(&bottom.px);
    Canvas {
        w: top.w,
        h: top.h + bottom.h,
        px,
    }
}

fn auto_radius(agents: usize, width: usize) -> f32 {
    let base = match agents {
        0..=1000 => 3.0,
        1001..=5000 => 2.2,
        5001..=50_000 => 1.4,
        _ => 0.5,
    };
    (base * width as f32 / 1024.0).max(0.5)
}

fn trail_stride(agents: usize, max: usize) -> usize {
    agents.div_ceil(max.max(1)).max(1)
}

/// Legend: agent colour swatches then object kinds present, with names, in a box at top left;
/// the step at the top right.
fn draw_legend(canvas: &mut Canvas, scene: &Scene, frame: &Frame, by: ColorBy, scale: i64) {
    let mut entries: Vec<(String, u8, bool)> = Vec::new();
    let mut used = [false; 8];
    let mut used_codes: Vec<u16> = Vec::new();
    for a in &frame.agents {
        let code = if by == ColorBy::Group {
            a.group
        } else {
            u16::from(a.label)
        };
        if !used[code as usize % 8] {
            used[code as usize % 8] = true;
            used_codes.push(code);
        }
    }
    if by == ColorBy::Label && used_codes.iter().all(|&c| c < 3) {
        // Ant labels only: show all three, used or not.
        used_codes = vec![0, 1, 2];
    }
    used_codes.sort_unstable();
    for code in used_codes {
        let name = if by == ColorBy::Group {
            format!("group {code}")
        } else {
            format!("label: {}", label_name(code as u8))
        };
        entries.push((name, agent_index(by, code as u8, code, 0), false));
    }
    for k in ShapeKind::ALL {
        if scene.shapes.iter().any(|s| s.kind == k) {
            let ring = matches!(k, ShapeKind::Disturbance | ShapeKind::Waypoint);
            let name = match k {
                ShapeKind::Food => "food source".to_owned(),
                // Ant rocks and polygons, bee boxes (the grassland's ground among them).
                ShapeKind::Rock => "obstacle".to_owned(),
                _ => serde_json::to_value(k)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_owned))
                    .unwrap_or_default(),
            };
            entries.push((name, kind_index(k), ring));
        }
    }
    let pad = 3 * scale;
    let sw = 5 * scale; // swatch size = text height
    let line_h = 5 * scale + 2 * scale;
    let text_w = entries
        .iter()
        .map(|e| text_width(&e.0, scale))
        .max()
        .unwrap_or(0);
    let (x0, y0) = (canvas.w as i64 / 60 + 2, canvas.w as i64 / 60 + 2);
    if !entries.is_empty() {
        let bw = pad * 2 + sw + 2 * scale + text_w;
        let bh = pad * 2 + line_h * entries.len() as i64 - 2 * scale;
        canvas.rect(x0, y0, x0 + bw, y0 + bh, I_PAPER);
        canvas.rect_outline(x0, y0, x0 + bw, y0 + bh, I_BORDER);
        for (i, (name, c, ring)) in entries.iter().enumerate() {
            let y = y0 + pad + i as i64 * line_h;
            let x = x0 + pad;
            if *ring {
                canvas.rect_outline(x, y, x + sw - 1, y + sw - 1, *c);
                canvas.rect_outline(x + 1, y + 1, x + sw - 2, y + sw - 2, *c);
            } else {
                canvas.rect(x, y, x + sw - 1, y + sw - 1, *c);
            }
            canvas.text(x + sw + 2 * scale, y, name, scale, I_INK);
        }
    }
    draw_step(canvas, frame.step, scale);
}

fn draw_step(canvas: &mut Canvas, step: u32, scale: i64) {
    let s = format!("step {step}");
    let w = text_width(&s, scale);
    let pad = 2 * scale;
    let x1 = canvas.w as i64 - canvas.w as i64 / 60 - 2;
    let y0 = canvas.w as i64 / 60 + 2;
    let x0 = x1 - w - 2 * pad;
    canvas.rect(x0, y0, x1, y0 + 5 * scale + 2 * pad, I_PAPER);
    canvas.text(x0 + pad, y0 + pad, &s, scale, I_INK);
}

fn check_inputs(scene: &Scene, frames: &[Frame], path: &Path) -> Result<()> {
    scene.validate(path)?;
    if frames.is_empty() {
        return Err(OutputError::invalid(
            path,
            "there are no recorded frames to draw",
        ));
    }
    check_frames(frames, path)?;
    Ok(())
}

/// Draws the last frame with trails; returns the canvas.
fn snapshot_canvas(scene: &Scene, frames: &[Frame], opts: &RenderOptions) -> (Canvas, View) {
    let view = View::new(scene, opts.width);
    let mut canvas = Canvas::new(view.w, view.h, I_BG);
    let last = frames.len() - 1;
    let frame = &frames[last];
    let by = resolve_color_by(opts.color_by, scene);
    draw_base(&mut canvas, &view, scene);
    let first = last.saturating_sub(opts.trail);
    let idx: Vec<usize> = (first..=last).collect();
    let n = frame.agents.len();
    draw_trails(
        &mut canvas,
        &view,
        scene,
        frames,
        &idx,
        trail_stride(n, opts.max_trail_agents),
        by,
    );
    let mut objects = Canvas::new(view.w, view.h, CLEAR);
    draw_objects(&mut objects, &view, scene, frame.step);
    compose(&mut canvas, &objects);
    let r = opts
        .agent_radius_px
        .unwrap_or_else(|| auto_radius(n, view.w));
    draw_agents(&mut canvas, &view, scene, frame, r, by);
    if opts.legend {
        let scale = (view.w as i64 / 400).max(1);
        draw_legend(&mut canvas, scene, frame, by, scale);
    }
    if scene.dim == 3 {
        let side = View::side(scene, &view);
        let panel = side_canvas(
            &side,
            scene,
            frames,
            &idx,
            trail_stride(n, opts.max_trail_agents),
            frame,
            r,
            by,
        );
        canvas = stack(canvas, &panel);
    }
    (canvas, view)
}

/// Renders the PNG image (RGB) of the last frame in memory, without writing it.
pub fn snapshot_image(
    scene: &Scene,
    frames: &[Frame],
    opts: &RenderOptions,
) -> Result<image::RgbImage> {
    check_inputs(scene, frames, Path::new("<snapshot>"))?;
    let (canvas, _) = snapshot_canvas(scene, frames, opts);
    Ok(to_rgb(&canvas))
}

fn to_rgb(canvas: &Canvas) -> image::RgbImage {
    let pal = palette();
    let mut rgb = Vec::with_capacity(canvas.px.len() * 3);
    for &i in &canvas.px {
        rgb.extend_from_slice(&pal[i as usize]);
    }
    image::RgbImage::from_raw(canvas.w as u32, canvas.h as u32, rgb).expect("buffer size matches")
}

/// Writes a PNG snapshot of the last frame: objects visible at its step, fading trails of the last
/// `opts.trail` frames (for at most `opts.max_trail_agents` agents), every agent as a dot
/// coloured by label or group, and a legend. Whole or not at all.
pub fn render_png(
    scene: &Scene,
    frames: &[Frame],
    path: impl AsRef<Path>,
    opts: &RenderOptions,
) -> Result<()> {
    let path = path.as_ref();
    check_inputs(scene, frames, path)?;
    let (canvas, _) = snapshot_canvas(scene, frames, opts);
    let img = to_rgb(&canvas);
    write_atomic(path, |w| {
        PngEncoder::new_with_quality(w, CompressionType::Default, FilterType::Adaptive)
            .write_image(
                img.as_raw(),
                img.width(),
                img.height(),
                image::ExtendedColorType::Rgb8,
            )
            .map_err(io::Error::other)
    })
}

/// The indices of the frames shown in the GIF: at most `max` (≥ 2), evenly spaced, first and
/// last included.
pub fn gif_frame_indices(n: usize, max: usize) -> Vec<usize> {
    let m = n.min(max.max(2));
    match m {
        0 => Vec::new(),
        1 => vec![0],
        _ => (0..m).map(|i| i * (n - 1) / (m - 1)).collect(),
    }
}

/// Writes an animated, looping GIF of the run: at most `opts.gif_max_frames` frames, each with
/// the objects visible at its step, short fading trails, the agents and the step number. Uses
/// the renderer's fixed palette (no quantisation). Whole or not at all.
pub fn render_gif(
    scene: &Scene,
    frames: &[Frame],
    path: impl AsRef<Path>,
    opts: &RenderOptions,
) -> Result<()> {
    let path = path.as_ref();
    check_inputs(scene, frames, path)?;
    let view = View::new(scene, opts.gif_width);
    let side = (scene.dim == 3).then(|| View::side(scene, &view));
    let total_h = view.h + side.as_ref().map_or(0, |s| s.h);
    if view.w > u16::MAX as usize || total_h > u16::MAX as usize {
        return Err(OutputError::invalid(
            path,
            format!("GIF size {}x{} is too large", view.w, total_h),
        ));
    }
    let by = resolve_color_by(opts.color_by, scene);
    let shown = gif_frame_indices(frames.len(), opts.gif_max_frames);
    let n = frames[0].agents.len();
    let stride = trail_stride(n, opts.max_trail_agents);
    let r = opts
        .agent_radius_px
        .map(|r| r * view.w as f32 / opts.width.max(1) as f32)
        .unwrap_or_else(|| auto_radius(n, view.w))
        .max(0.5);
    let text_scale = (view.w as i64 / 320).max(1);
    let flat_palette: Vec<u8> = palette().into_iter().flatten().collect();

    write_atomic(path, |w| {
        let mut enc = gif::Encoder::new(w, view.w as u16, total_h as u16, &flat_palette)
            .map_err(io::Error::other)?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(io::Error::other)?;
        let mut canvas = Canvas::new(view.w, view.h, I_BG);
        let mut base = Canvas::new(view.w, view.h, I_BG);
        draw_base(&mut base, &view, scene);
        // Object overlay, redrawn only when the set of visible shapes changes.
        let mut objects_key: Option<Vec<bool>> = None;
        let mut objects = Canvas::new(view.w, view.h, CLEAR);
        for (k, &fi) in shown.iter().enumerate() {
            let frame = &frames[fi];
            let key: Vec<bool> = scene
                .shapes
                .iter()
                .map(|s| s.visible_at(frame.step))
                .collect();
            if objects_key.as_ref() != Some(&key) {
                draw_objects(&mut objects, &view, scene, frame.step);
                objects_key = Some(key);
            }
            canvas.px.copy_from_slice(&base.px);
            // Trail: the original frames spanning the last `gif_trail` shown frames, at most 32
            // segments per agent.
            let from = shown[k.saturating_sub(opts.gif_trail)];
            let step = (fi - from).div_ceil(32).max(1);
            let mut idx: Vec<usize> = (from..=fi).rev().step_by(step).collect();
            if idx.last() != Some(&from) {
                idx.push(from);
            }
            idx.reverse();
            draw_trails(&mut canvas, &view, scene, frames, &idx, stride, by);
            compose(&mut canvas, &objects);
            draw_agents(&mut canvas, &view, scene, frame, r, by);
            draw_step(&mut canvas, frame.step, text_scale);
            let both;
            let pixels = match &side {
                Some(sv) => {
                    let panel = side_canvas(sv, scene, frames, &idx, stride, frame, r, by);
                    let top = Canvas {
                        w: canvas.w,
                        h: canvas.h,
                        px: canvas.px.clone(),
                    };
                    both = stack(top, &panel);
                    both.px.as_slice()
                }
                None => canvas.px.as_slice(),
            };
            let mut gf =
                gif::Frame::from_indexed_pixels(view.w as u16, total_h as u16, pixels, None);
            gf.delay = if k + 1 == shown.len() {
                opts.gif_delay_cs.saturating_mul(20).max(100)
            } else {
                opts.gif_delay_cs
            };
            enc.write_frame(&gf).map_err(io::Error::other)?;
        }
        enc.into_inner().map_err(io::Error::other)?.flush()
    })
}

#[cfg(test)]
mod tests {
    use super::super::frames::AgentSample;
    use super::*;
    use crate::output::scene::Shape;

    fn scene() -> Scene {
        let mut s = Scene::new_2d([0.0, 0.0], [200.0, 100.0]);
        s.shapes = vec![
            Shape::circle([30.0, 50.0, 0.0], 8.0, ShapeKind::Nest).named("home"),
            Shape::circle([170.0, 50.0, 0.0], 6.0, ShapeKind::Food).during(None, Some(10)),
            Shape::circle([160.0, 80.0, 0.0], 6.0, ShapeKind::Food).during(Some(10), None),
            Shape::polygon(
                vec![[95.0, 35.0], [110.0, 35.0], [102.0, 60.0]],
                ShapeKind::Rock,
            ),
            Shape::circle([100.0, 15.0, 0.0], 7.0, ShapeKind::Disturbance),
        ];
        s
    }

    /// 50 agents × 20 frames walking around the world, never near the nest centre.
    fn frames(agents: usize, nframes: usize) -> Vec<Frame> {
        (0..nframes)
            .map(|f| Frame {
                step: (f * 5) as u32,
                agents: (0..agents)
                    .map(|i| {
                        let a = i as f32 * 0.7 + f as f32 * 0.05;
                        let r = 20.0 + (i % 7) as f32 * 3.0;
                        AgentSample {
                            id: i as u32,
                            group: (i % 2) as u16,
                            pos: [100.0 + r * a.cos() * 1.8, 50.0 + r * a.sin(), 0.0],
                            heading: [a.cos(), a.sin(), 0.0],
                            label: (i % 3) as u8,
                            motion: 1,
                            ..Default::default()
                        }
                    })
                    .collect(),
            })
            .collect()
    }

    #[test]
    fn palette_is_small_and_distinct() {
        let p = palette();
        assert_eq!(p.len(), PALETTE_LEN);
        assert!((I_GROUP as usize + 8 * SHADES) <= PALETTE_LEN);
        let kinds: std::collections::BTreeSet<[u8; 3]> = KIND_COLORS.iter().copied().collect();
        assert_eq!(kinds.len(), KIND_COLORS.len());
    }

    #[test]
    fn png_has_expected_size_and_nest_colour() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("snapshot.png");
        let (sc, fr) = (scene(), frames(50, 20));
        let opts = RenderOptions::default();
        render_png(&sc, &fr, &p, &opts).unwrap();
        let img = image::open(&p).unwrap().to_rgb8();
        assert_eq!(img.width(), 1024);
        let view = View::new(&sc, 1024);
        assert_eq!(img.height() as usize, view.h);
        // World is 2:1, so about 512 px tall.
        assert!((500..=530).contains(&img.height()), "{}", img.height());
        let (x, y) = view.world(&sc, [30.0, 50.0, 0.0]);
        assert_eq!(
            img.get_pixel(x.round() as u32, y.round() as u32).0,
            kind_color(ShapeKind::Nest)
        );
        // The food source visible at the last step (moved at step 10) is drawn, the old one not.
        let (x, y) = view.world(&sc, [160.0, 80.0, 0.0]);
        assert_eq!(
            img.get_pixel(x.round() as u32, y.round() as u32).0,
            kind_color(ShapeKind::Food)
        );
        let (x, y) = view.world(&sc, [170.0, 50.0, 0.0]);
        assert_ne!(
            img.get_pixel(x.round() as u32, y.round() as u32).0,
            kind_color(ShapeKind::Food)
        );
        // Some agent of each label colour is drawn.
        for label in 0..3u16 {
            let c = agent_color(ColorBy::Label, label);
            assert!(img.pixels().any(|px| px.0 == c), "label {label}");
        }
        // Rock polygon centre.
        let (x, y) = view.world(&sc, [102.0, 43.0, 0.0]);
        assert_eq!(
            img.get_pixel(x.round() as u32, y.round() as u32).0,
            kind_color(ShapeKind::Rock)
        );
    }

    #[test]
    fn gif_decodes_with_expected_frames() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("run.gif");
        let (sc, fr) = (scene(), frames(50, 20));
        render_gif(&sc, &fr, &p, &RenderOptions::default()).unwrap();
        let file = std::fs::File::open(&p).unwrap();
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::Indexed);
        let mut dec = opts.read_info(file).unwrap();
        assert_eq!(dec.width(), 480);
        assert_eq!(dec.height() as usize, View::new(&sc, 480).h);
        let mut count = 0;
        while let Some(f) = dec.read_next_frame().unwrap() {
            assert_eq!((f.width, f.height), (dec.width(), dec.height()));
            count += 1;
        }
        assert_eq!(count, 20);
        assert_eq!(dec.repeat(), gif::Repeat::Infinite);

        // Subsampled to at most gif_max_frames.
        let opts = RenderOptions {
            gif_max_frames: 7,
            ..RenderOptions::default()
        };
        render_gif(&sc, &fr, &p, &opts).unwrap();
        let mut dec = gif::DecodeOptions::new()
            .read_info(std::fs::File::open(&p).unwrap())
            .unwrap();
        let mut count = 0;
        while dec.read_next_frame().unwrap().is_some() {
            count += 1;
        }
        assert_eq!(count, 7);
    }

    #[test]
    fn rendering_is_deterministic() {
        let dir = tempfile::tempdir().unwrap();
        let (sc, fr) = (scene(), frames(50, 20));
        let o = RenderOptions::default();
        let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
        render_png(&sc, &fr, dir.path().join("a.png"), &o).unwrap();
        render_png(&sc, &fr, dir.path().join("b.png"), &o).unwrap();
        assert_eq!(read("a.png"), read("b.png"));
        render_gif(&sc, &fr, dir.path().join("a.gif"), &o).unwrap();
        render_gif(&sc, &fr, dir.path().join("b.gif"), &o).unwrap();
        assert_eq!(read("a.gif"), read("b.gif"));
    }

    #[test]
    fn three_d_top_view() {
        let dir = tempfile::tempdir().unwrap();
        let mut sc = Scene::new_3d([0.0, 0.0, 0.0], [100.0, 30.0, 50.0]);
        sc.shapes = vec![
            Shape::circle([50.0, 0.0, 25.0], 4.0, ShapeKind::Shaft),
            Shape::circle([20.0, 10.0, 10.0], 3.0, ShapeKind::Target),
            Shape::cuboid([80.0, 0.0, 5.0], [90.0, 10.0, 15.0], ShapeKind::Sphere),
        ];
        let fr: Vec<Frame> = (0..10)
            .map(|f| Frame {
                step: f,
                agents: (0..30)
                    .map(|i| AgentSample {
                        id: i,
                        group: (i % 3) as u16,
                        pos: [5.0 + f as f32 * 3.0, 15.0, 2.0 + i as f32 * 1.5],
                        ..Default::default()
                    })
                    .collect(),
            })
            .collect();
        let p = dir.path().join("s.png");
        render_png(&sc, &fr, &p, &RenderOptions::default()).unwrap();
        let img = image::open(&p).unwrap().to_rgb8();
        let view = View::new(&sc, 1024);
        let side = View::side(&sc, &view);
        // The top view, then the side view below it.
        assert_eq!(
            (img.width(), img.height() as usize),
            (1024, view.h + side.h)
        );
        // The shaft stands full height in the side view.
        for y in [2.0, 15.0, 28.0] {
            let (x, py) = side.world(&sc, [50.0, y, 0.0]);
            assert_eq!(
                img.get_pixel(x.round() as u32, (py.round() as usize + view.h) as u32)
                    .0,
                kind_color(ShapeKind::Shaft)
            );
        }
        let (x, y) = view.world(&sc, [50.0, 99.0, 25.0]);
        assert_eq!(
            img.get_pixel(x.round() as u32, y.round() as u32).0,
            kind_color(ShapeKind::Shaft)
        );
        // z grows downwards in the top view.
        assert!(view.world(&sc, [0.0, 0.0, 40.0]).1 > view.world(&sc, [0.0, 0.0, 10.0]).1);
        // Bees are coloured by group in 3D.
        assert!(
            img.pixels()
                .any(|px| px.0 == agent_color(ColorBy::Group, 1))
        );
    }

    /// The side view draws a bee's wings as a bar along the rolled wing axis: a bee flying +x
    /// (across the view, wings along z, edge-on) with a roll of 40° shows a dark bar above and
    /// below its dot; a level one shows none.
    #[test]
    fn the_side_view_shows_the_roll_as_a_tilted_wing_bar() {
        let sc = Scene::new_3d([0.0, 0.0, 0.0], [100.0, 30.0, 50.0]);
        let ink = |roll: f32| {
            let fr = vec![Frame {
                step: 0,
                agents: vec![AgentSample {
                    pos: [50.0, 15.0, 25.0],
                    heading: [1.0, 0.0, 0.0],
                    roll,
                    ..Default::default()
                }],
            }];
            let opts = RenderOptions {
                agent_radius_px: Some(4.0),
                legend: false,
                ..RenderOptions::default()
            };
            let img = snapshot_image(&sc, &fr, &opts).unwrap();
            let view = View::new(&sc, opts.width);
            let side = View::side(&sc, &view);
            let (x, y) = side.world(&sc, [50.0, 15.0, 25.0]);
            let (x, y) = (x.round() as u32, y.round() as u32 + view.h as u32);
            // Pixels straight above and below the dot, past its disc.
            (5..8)
                .filter(|d| img.get_pixel(x, y - d).0 == INK && img.get_pixel(x, y + d).0 == INK)
                .count()
        };
        assert!(ink(40.0) > 0, "no wing bar for a rolled bee");
        assert_eq!(
            ink(0.0),
            0,
            "a level bee flying across the view shows no bar"
        );
    }

    #[test]
    fn a_nest_on_the_ground_box_stays_visible_from_above() {
        let dir = tempfile::tempdir().unwrap();
        let mut sc = Scene::new_3d([0.0, 0.0, 0.0], [100.0, 30.0, 50.0]);
        // The ground box comes after the nest in the scene, as in bees-fig15-nest.
        sc.shapes = vec![
            Shape::circle([50.0, 2.0, 25.0], 5.0, ShapeKind::Target),
            Shape::cuboid([0.0, 0.0, 0.0], [100.0, 1.0, 50.0], ShapeKind::Rock),
        ];
        let fr = vec![Frame {
            step: 0,
            agents: vec![AgentSample {
                pos: [5.0, 15.0, 5.0],
                ..Default::default()
            }],
        }];
        let p = dir.path().join("n.png");
        render_png(&sc, &fr, &p, &RenderOptions::default()).unwrap();
        let img = image::open(&p).unwrap().to_rgb8();
        let view = View::new(&sc, 1024);
        let (x, y) = view.world(&sc, [50.0, 2.0, 25.0]);
        assert_eq!(
            img.get_pixel(x.round() as u32, y.round() as u32).0,
            kind_color(ShapeKind::Target)
        );
        let (x, y) = view.world(&sc, [90.0, 0.5, 45.0]);
        assert_eq!(
            img.get_pixel(x.round() as u32, y.round() as u32).0,
            kind_color(ShapeKind::Rock)
        );
    }

    #[test]
    fn refuses_empty_frames_and_leaves_no_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.png");
        let msg = render_png(&scene(), &[], &p, &RenderOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("x.png") && msg.contains("no recorded frames"),
            "{msg}"
        );
        assert!(!p.exists());
    }

    #[test]
    fn frame_index_subsampling() {
        assert_eq!(gif_frame_indices(0, 150), Vec::<usize>::new());
        assert_eq!(gif_frame_indices(1, 150), vec![0]);
        assert_eq!(gif_frame_indices(5, 150), vec![0, 1, 2, 3, 4]);
        let v = gif_frame_indices(1000, 150);
        assert_eq!(v.len(), 150);
        assert_eq!((v[0], v[149]), (0, 999));
        assert!(v.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn raster_primitives() {
        let mut c = Canvas::new(20, 20, 0);
        c.disc(10.0, 10.0, 3.0, 1);
        assert_eq!(c.px[10 * 20 + 10], 1);
        assert_eq!(c.px[10 * 20 + 13], 1);
        assert_eq!(c.px[10 * 20 + 14], 0);
        c.line(-5.0, 0.0, 25.0, 0.0, 2);
        assert!(c.px[..20].iter().all(|&p| p == 2));
        c.polygon(&[[0.0, 15.0], [19.0, 15.0], [19.0, 19.0], [0.0, 19.0]], 3);
        assert!(c.px[17 * 20..18 * 20].iter().all(|&p| p == 3));
        c.ring(10.0, 10.0, 5.0, 1.0, 4);
        assert_eq!(c.px[10 * 20 + 15], 4);
        assert_eq!(c.px[10 * 20 + 10], 1);
    }

    /// 500 agents × 300 frames: both pictures well under a few seconds in release (this test
    /// only checks it finishes; time it with `cargo test --release -- --nocapture perf`).
    #[test]
    fn perf_500_agents_300_frames() {
        let dir = tempfile::tempdir().unwrap();
        let (sc, fr) = (scene(), frames(500, 300));
        let t = std::time::Instant::now();
        render_png(
            &sc,
            &fr,
            dir.path().join("p.png"),
            &RenderOptions::default(),
        )
        .unwrap();
        let t_png = t.elapsed();
        let t = std::time::Instant::now();
        render_gif(
            &sc,
            &fr,
            dir.path().join("p.gif"),
            &RenderOptions::default(),
        )
        .unwrap();
        eprintln!(
            "perf: 500 agents x 300 frames: png {t_png:?}, gif {:?}",
            t.elapsed()
        );
    }
}
