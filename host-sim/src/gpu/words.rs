//! What the word layouts of the ant and bee kernels share: a scalar as one `u32` ([`Word`]) and
//! a reader of words in order (`Words`).

use swarm_core::{Fx, Rect, Scalar, Vec2, Vec3};

use crate::error::{Result, SimError};

/// A scalar as one storage word: the bits of an [`Fx`] or of an `f32` (`s_to_word` and
/// `s_from_word` of the scalar modules).
pub trait Word: Scalar {
    /// The bits.
    fn to_word(self) -> u32;
    /// From the bits.
    fn from_word(w: u32) -> Self;
}

impl Word for Fx {
    fn to_word(self) -> u32 {
        self.to_bits() as u32
    }
    fn from_word(w: u32) -> Self {
        Fx::from_bits(w as i32)
    }
}

impl Word for f32 {
    fn to_word(self) -> u32 {
        self.to_bits()
    }
    fn from_word(w: u32) -> Self {
        f32::from_bits(w)
    }
}

/// Reads words in order; missing words read as zero.
pub(crate) struct Words<'a>(pub(crate) &'a [u32]);

impl Words<'_> {
    pub(crate) fn next(&mut self) -> u32 {
        let (&w, rest) = self.0.split_first().unwrap_or((&0, &[]));
        self.0 = rest;
        w
    }
    pub(crate) fn s<S: Word>(&mut self) -> S {
        S::from_word(self.next())
    }
    pub(crate) fn v2<S: Word>(&mut self) -> Vec2<S> {
        let x = self.s();
        Vec2::new(x, self.s())
    }
    pub(crate) fn v3<S: Word>(&mut self) -> Vec3<S> {
        let x = self.s();
        let y = self.s();
        Vec3::new(x, y, self.s())
    }
    pub(crate) fn rect<S: Word>(&mut self) -> Rect<S> {
        let min = self.v2();
        Rect::new(min, self.v2())
    }
    pub(crate) fn u16(&mut self, what: &'static str) -> Result<u16> {
        let w = self.next();
        u16::try_from(w).map_err(|_| SimError::GpuWords { what, word: w })
    }
    pub(crate) fn flag(&mut self) -> Result<bool> {
        match self.next() {
            0 => Ok(false),
            1 => Ok(true),
            word => Err(SimError::GpuWords { what: "flag", word }),
        }
    }
    pub(crate) fn skip(&mut self, n: usize) {
        self.0 = self.0.get(n..).unwrap_or(&[]);
    }
    /// A list length of at most `cap`.
    pub(crate) fn len(&mut self, cap: usize) -> Result<usize> {
        let word = self.next();
        match usize::try_from(word) {
            Ok(n) if n <= cap => Ok(n),
            _ => Err(SimError::GpuWords {
                what: "list length",
                word,
            }),
        }
    }
}
