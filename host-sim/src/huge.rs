//! Large arrays read at scattered places every step (the cost fields' cells), backed by
//! transparent huge pages where Linux gives them.
//!
//! A wang2014 step samples the cost field of every insect's goal at 8 cells spread over
//! three rows and two layers of the grid; on 4 KiB pages a field of a few ten megabytes
//! misses the TLB at almost every sample. Linux backs an anonymous mapping with 2 MiB pages
//! when asked (`madvise(MADV_HUGEPAGE)`, honoured under the default `madvise` setting of
//! `/sys/kernel/mm/transparent_hugepage/enabled`): the same bits, 11 % faster on the 256k
//! bench world (docs/benchmarks.md). Elsewhere, or when the mapping fails, the array is an
//! ordinary heap allocation.

use std::fmt;
use std::marker::PhantomData;
use std::ops::Deref;

use bytemuck::Pod;
use memmap2::MmapMut;

/// Below this size an array stays on the heap (a huge page is 2 MiB).
const MIN_BYTES: usize = 2 << 20;

/// A read-only array of `T`, on huge pages when it is large and the system allows.
pub struct HugeSlice<T: Pod> {
    storage: Storage<T>,
    _items: PhantomData<T>,
}

enum Storage<T> {
    Heap(Vec<T>),
    /// `len` items at the start of an anonymous mapping (page-aligned, so aligned for `T`).
    Mapped {
        map: MmapMut,
        len: usize,
    },
}

impl<T: Pod> HugeSlice<T> {
    /// A copy of `items`.
    pub fn from_slice(items: &[T]) -> Self {
        let storage = Self::mapped(items).unwrap_or_else(|| Storage::Heap(items.to_vec()));
        HugeSlice {
            storage,
            _items: PhantomData,
        }
    }

    /// `items` in an anonymous mapping advised for huge pages; `None` for a small array or
    /// when the system refuses the mapping.
    fn mapped(items: &[T]) -> Option<Storage<T>> {
        let bytes: &[u8] = bytemuck::cast_slice(items);
        if bytes.len() < MIN_BYTES {
            return None;
        }
        let mut map = MmapMut::map_anon(bytes.len()).ok()?;
        // Advice only: the kernel may decline (THP disabled), which changes nothing else.
        #[cfg(target_os = "linux")]
        let _ = map.advise(memmap2::Advice::HugePage);
        map[..bytes.len()].copy_from_slice(bytes);
        Some(Storage::Mapped {
            map,
            len: items.len(),
        })
    }

    /// Whether the array lives in a huge-page-advised mapping (not on the heap).
    pub fn is_mapped(&self) -> bool {
        matches!(self.storage, Storage::Mapped { .. })
    }
}

impl<T: Pod> Deref for HugeSlice<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        match &self.storage {
            Storage::Heap(v) => v,
            Storage::Mapped { map, len } => {
                bytemuck::cast_slice(&map[..len * std::mem::size_of::<T>()])
            }
        }
    }
}

impl<T: Pod> Clone for HugeSlice<T> {
    fn clone(&self) -> Self {
        Self::from_slice(self)
    }
}

impl<T: Pod + PartialEq> PartialEq for HugeSlice<T> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: Pod> fmt::Debug for HugeSlice<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("HugeSlice")
            .field("len", &self.len())
            .field("mapped", &self.is_mapped())
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_arrays_stay_on_the_heap_and_large_ones_are_mapped_with_the_same_items() {
        let small = HugeSlice::from_slice(&[1u32, 2, 3]);
        assert!(!small.is_mapped());
        assert_eq!(&*small, &[1, 2, 3]);
        let items: Vec<[f32; 4]> = (0..200_000).map(|i| [i as f32, 1.0, 2.0, 3.0]).collect();
        let big = HugeSlice::from_slice(&items);
        assert!(big.is_mapped());
        assert_eq!(&*big, &items[..]);
        let copy = big.clone();
        assert_eq!(copy, big);
        assert_eq!(HugeSlice::<u8>::from_slice(&[]).len(), 0);
    }
}
