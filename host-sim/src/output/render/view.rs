//! The projection of world coordinates to pixels: the plan of a 2D world or the top view of a
//! 3D one, and the side view of a 3D world.

use crate::output::scene::Scene;

/// Maps drawing-plane world coordinates to pixels.
#[derive(Clone, Copy, Debug)]
pub(super) struct View {
    pub(super) w: usize,
    pub(super) h: usize,
    u0: f32,
    v0: f32,
    pub(super) scale: f32,
    pub(super) ox: f32,
    oy: f32,
    /// World extent in pixels along v (for flipping).
    vspan: f32,
    flip: bool,
    /// The side view of a 3D world (x, y) instead of its plan.
    pub(super) side: bool,
}

impl View {
    pub(super) fn new(scene: &Scene, width: u32) -> Self {
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
    pub(super) fn side(scene: &Scene, top: &View) -> Self {
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
    pub(super) fn px(&self, p: [f32; 2]) -> (f32, f32) {
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
    pub(super) fn world(&self, scene: &Scene, p: [f32; 3]) -> (f32, f32) {
        if self.side {
            self.px([p[0], p[1]])
        } else {
            self.px(scene.plan(p))
        }
    }
}
