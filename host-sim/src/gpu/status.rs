//! The status words of the controller kernels: how an [`Error`] of a controller is written as
//! one `u32` (`kind | field << 8 | (index + 1) << 16`, 0 for no error) and read back, shared by
//! the ant and bee layouts, each with its own table of field names and kinds of error.

use swarm_core::Error;

use crate::error::{Result, SimError};

/// The status word of a controller error: `kind | field << 8 | (index + 1) << 16`, the kind 1
/// for [`Error::NonFinite`], 2 for [`Error::OutOfRange`], 3 for [`Error::Inconsistent`], the
/// field its position in `fields` (whose entry 0 is no field); `u32::MAX` for an error of a
/// kind above `kinds` or with a field not in `fields`.
pub fn status_of(fields: &[&str], kinds: u32, e: &Error) -> u32 {
    let (kind, field, index) = match *e {
        Error::NonFinite { field, index } => (1, field, index),
        Error::OutOfRange { field, index } => (2, field, index),
        Error::Inconsistent { field, index } => (3, field, index),
        _ => return u32::MAX,
    };
    if kind > kinds {
        return u32::MAX;
    }
    let Some(code) = fields.iter().skip(1).position(|&f| f == field) else {
        return u32::MAX;
    };
    let index = index.map_or(0, |i| u32::from(i.min(0xfffe)) + 1);
    kind | ((code as u32 + 1) << 8) | (index << 16)
}

/// The controller's answer of a status word ([`status_of`] over the same `fields` and
/// `kinds`): `Ok(())` for 0, else the [`Error`] it stands for.
///
/// # Errors
///
/// [`SimError::GpuWords`] (naming `what`) for a word no kernel writes.
pub fn status_error(
    fields: &[&'static str],
    kinds: u32,
    what: &'static str,
    word: u32,
) -> Result<std::result::Result<(), Error>> {
    if word == 0 {
        return Ok(Ok(()));
    }
    let bad = SimError::GpuWords { what, word };
    let field = match fields.get(((word >> 8) & 0xff) as usize) {
        Some(&f) if !f.is_empty() => f,
        _ => return Err(bad),
    };
    let index = match word >> 16 {
        0 => None,
        i => Some((i - 1) as u16),
    };
    let kind = word & 0xff;
    if kind > kinds {
        return Err(bad);
    }
    Ok(Err(match kind {
        1 => Error::NonFinite { field, index },
        2 => Error::OutOfRange { field, index },
        3 => Error::Inconsistent { field, index },
        _ => return Err(bad),
    }))
}
