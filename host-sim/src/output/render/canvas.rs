//! The indexed-colour raster and its drawing primitives.

/// An indexed-colour raster.
pub(super) struct Canvas {
    pub(super) w: usize,
    pub(super) h: usize,
    pub(super) px: Vec<u8>,
}

impl Canvas {
    pub(super) fn new(w: usize, h: usize, fill: u8) -> Self {
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

    pub(super) fn rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: u8) {
        for y in y0..=y1 {
            self.hspan(x0, x1, y, c);
        }
    }

    pub(super) fn rect_outline(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: u8) {
        self.hspan(x0, x1, y0, c);
        self.hspan(x0, x1, y1, c);
        for y in y0..=y1 {
            self.set(x0, y, c);
            self.set(x1, y, c);
        }
    }

    /// A filled disc of radius `r` (pixel centres at integer coordinates).
    pub(super) fn disc(&mut self, cx: f32, cy: f32, r: f32, c: u8) {
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
    pub(super) fn ring(&mut self, cx: f32, cy: f32, r: f32, t: f32, c: u8) {
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
    pub(super) fn line(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, c: u8) {
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
    pub(super) fn polygon(&mut self, pts: &[[f32; 2]], c: u8) {
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
}

/// Index meaning "nothing drawn here" in an overlay.
pub(super) const CLEAR: u8 = 255;

/// Copies the non-clear pixels of `overlay` onto `canvas`.
pub(super) fn compose(canvas: &mut Canvas, overlay: &Canvas) {
    for (d, &s) in canvas.px.iter_mut().zip(&overlay.px) {
        if s != CLEAR {
            *d = s;
        }
    }
}

/// `top` with `bottom` below it (same width).
pub(super) fn stack(top: Canvas, bottom: &Canvas) -> Canvas {
    let mut px = top.px;
    px.extend_from_slice(&bottom.px);
    Canvas {
        w: top.w,
        h: top.h + bottom.h,
        px,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
