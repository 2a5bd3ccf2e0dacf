//! Accessors, checked before they are read and read in proportion to the file.
//!
//! An accessor without a bufferView holds only its sparse values; every other element is zero.
//! Its `count` is bounded by nothing in the file: 605 bytes can declare 50 million vertices.
//! Such an accessor is kept sparse ([`Elements::Sparse`]): its stored values and the one value
//! all the others share, never `count` elements.

use gltf::accessor::sparse::IndexType;
use gltf::accessor::{DataType, Dimensions};

/// An accessor's elements: every one when a bufferView holds them, else only the stored ones.
pub(super) enum Elements<T> {
    Dense(Vec<T>),
    Sparse {
        count: usize,
        /// Strictly increasing, each below `count`.
        indices: Vec<u32>,
        values: Vec<T>,
        /// The value of every element not in `indices` (zero in the file).
        rest: T,
    },
}

impl<T: Copy> Elements<T> {
    pub(super) fn count(&self) -> usize {
        match self {
            Elements::Dense(v) => v.len(),
            Elements::Sparse { count, .. } => *count,
        }
    }

    /// Element `i` (`i < count`).
    pub(super) fn get(&self, i: usize) -> T {
        match self {
            Elements::Dense(v) => v[i],
            Elements::Sparse {
                indices,
                values,
                rest,
                ..
            } => match u32::try_from(i).map(|i| indices.binary_search(&i)) {
                Ok(Ok(k)) => values[k],
                _ => *rest,
            },
        }
    }

    /// `f` of every element (applied to each stored value once, and once to `rest`).
    pub(super) fn map<U>(&self, f: impl Fn(T) -> U) -> Elements<U> {
        match self {
            Elements::Dense(v) => Elements::Dense(v.iter().map(|&x| f(x)).collect()),
            Elements::Sparse {
                count,
                indices,
                values,
                rest,
            } => Elements::Sparse {
                count: *count,
                indices: indices.clone(),
                values: values.iter().map(|&x| f(x)).collect(),
                rest: f(*rest),
            },
        }
    }

    /// The first element, in index order, for which `bad` holds, with its index. A sparse
    /// accessor tests each stored value and `rest` (at the first index it stands for).
    pub(super) fn find(&self, bad: impl Fn(T) -> bool) -> Option<(usize, T)> {
        match self {
            Elements::Dense(v) => v.iter().copied().enumerate().find(|&(_, x)| bad(x)),
            Elements::Sparse {
                count,
                indices,
                values,
                rest,
            } => {
                // The first index without a stored value (the indices increase from 0).
                let first_rest = indices
                    .iter()
                    .enumerate()
                    .find(|&(k, &i)| i as usize != k)
                    .map_or(indices.len(), |(k, _)| k);
                let stored = indices.iter().zip(values).map(|(&i, &x)| (i as usize, x));
                let rest = (first_rest < *count).then_some((first_rest, *rest));
                let mut all: Vec<(usize, T)> =
                    stored.chain(rest).filter(|&(_, x)| bad(x)).collect();
                all.sort_by_key(|&(i, _)| i);
                all.first().copied()
            }
        }
    }
}

/// Reads `acc` (checked by [`check`]): through the glTF reader (`dense`) when a bufferView
/// holds it, else its sparse values, decoded by `decode` from the bytes of one element.
pub(super) fn read<T: Copy>(
    acc: &gltf::Accessor,
    buffers: &[gltf::buffer::Data],
    dense: impl FnOnce() -> Option<Vec<T>>,
    decode: impl Fn(&[u8]) -> T,
    zero: T,
) -> Result<Elements<T>, String> {
    let i = acc.index();
    if acc.view().is_some() {
        let v = dense().ok_or_else(|| {
            format!("accessor {i} cannot be read: the glTF reader found no data for it")
        })?;
        if v.len() != acc.count() {
            return Err(format!(
                "accessor {i} has {} elements, not its count {}",
                v.len(),
                acc.count()
            ));
        }
        return Ok(Elements::Dense(v));
    }
    let Some(sparse) = sparse_parts(acc, buffers)? else {
        return Err(format!(
            "accessor {i} has neither bufferView nor sparse data"
        ));
    };
    Ok(Elements::Sparse {
        count: acc.count(),
        values: sparse.values.iter().map(|b| decode(b)).collect(),
        indices: sparse.indices,
        rest: zero,
    })
}

/// Decodes one VEC3 FLOAT element.
pub(super) fn vec3_f32(b: &[u8]) -> glam::Vec3 {
    glam::Vec3::new(f32_at(b, 0), f32_at(b, 4), f32_at(b, 8))
}

/// A VEC2 decoder for `ty` (FLOAT, or normalized UNSIGNED_BYTE / UNSIGNED_SHORT, as the reader's
/// `into_f32` converts them).
pub(super) fn vec2_decoder(ty: DataType) -> impl Fn(&[u8]) -> glam::Vec2 {
    move |b: &[u8]| {
        let c = |k: usize| match ty {
            DataType::U8 => f32::from(b[k]) / 255.0,
            DataType::U16 => f32::from(u16::from_le_bytes([b[2 * k], b[2 * k + 1]])) / 65535.0,
            _ => f32_at(b, 4 * k),
        };
        glam::Vec2::new(c(0), c(1))
    }
}

fn f32_at(b: &[u8], at: usize) -> f32 {
    f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// The bytes of `count` elements of `elem` bytes, `stride` apart, from `offset` of a view.
struct Strided<'a> {
    bytes: &'a [u8],
    stride: usize,
    elem: usize,
    count: usize,
}

impl<'a> Strided<'a> {
    fn iter(&self) -> impl Iterator<Item = &'a [u8]> + '_ {
        (0..self.count).map(|k| &self.bytes[k * self.stride..k * self.stride + self.elem])
    }
}

/// The part of `view` that `count` elements at `offset` read, checked against the view and
/// the view against its buffer. `what` names the data in errors.
fn strided<'a>(
    what: &str,
    view: &gltf::buffer::View,
    offset: usize,
    count: usize,
    elem: usize,
    buffers: &'a [gltf::buffer::Data],
) -> Result<Strided<'a>, String> {
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(format!(
            "{what}: byteStride {stride} is smaller than an element ({elem})"
        ));
    }
    let end = count
        .checked_sub(1)
        .and_then(|n| n.checked_mul(stride))
        .and_then(|x| x.checked_add(offset)?.checked_add(elem));
    let end = match end {
        Some(e) if e <= view.length() => e,
        _ => {
            return Err(format!(
                "{what}: {count} elements from byte {offset}, {stride} bytes apart, run past \
                 the end of bufferView {} ({} bytes)",
                view.index(),
                view.length()
            ));
        }
    };
    let buf = view.buffer();
    let data = buffers.get(buf.index()).map_or(&[][..], |d| &d.0[..]);
    let available = data.len().min(buf.length());
    let view_bytes = view
        .offset()
        .checked_add(view.length())
        .filter(|&e| e <= available)
        .map(|e| &data[view.offset()..e])
        .ok_or_else(|| {
            format!(
                "bufferView {} extends past the end of buffer {} ({} bytes)",
                view.index(),
                buf.index(),
                buf.length()
            )
        })?;
    Ok(Strided {
        bytes: &view_bytes[offset..end],
        stride,
        elem,
        count,
    })
}

/// A sparse accessor's indices (checked: strictly increasing, below the count) and the bytes of
/// its values.
struct Sparse<'a> {
    indices: Vec<u32>,
    values: Vec<&'a [u8]>,
}

fn sparse_parts<'a>(
    acc: &gltf::Accessor,
    buffers: &'a [gltf::buffer::Data],
) -> Result<Option<Sparse<'a>>, String> {
    let Some(sparse) = acc.sparse() else {
        return Ok(None);
    };
    let i = acc.index();
    let n = sparse.count();
    if n == 0 || n > acc.count() {
        return Err(format!(
            "accessor {i} has sparse count {n}; it must be between 1 and the count {}",
            acc.count()
        ));
    }
    let ix = sparse.indices();
    let size = match ix.index_type() {
        IndexType::U8 => 1,
        IndexType::U16 => 2,
        IndexType::U32 => 4,
    };
    let what = format!("accessor {i}: sparse indices");
    let raw = strided(&what, &ix.view(), ix.offset(), n, size, buffers)?;
    let indices: Vec<u32> = raw
        .iter()
        .map(|b| match size {
            1 => u32::from(b[0]),
            2 => u32::from(u16::from_le_bytes([b[0], b[1]])),
            _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        })
        .collect();
    if let Some(w) = indices.windows(2).find(|w| w[0] >= w[1]) {
        return Err(format!(
            "{what} must strictly increase, but {} is followed by {}",
            w[0], w[1]
        ));
    }
    if let Some(&last) = indices.last().filter(|&&l| l as usize >= acc.count()) {
        return Err(format!(
            "{what}: index {last} is not below the accessor's count {}",
            acc.count()
        ));
    }
    let values = sparse.values();
    let what = format!("accessor {i}: sparse values");
    let raw = strided(
        &what,
        &values.view(),
        values.offset(),
        n,
        acc.size(),
        buffers,
    )?;
    Ok(Some(Sparse {
        indices,
        values: raw.iter().collect(),
    }))
}

/// A vertex attribute must have one element per vertex; checked before it is read, since a
/// sparse accessor's count is not bounded by any data in the file.
pub(super) fn same_count(acc: &gltf::Accessor, n_verts: usize) -> Result<(), String> {
    if acc.count() == n_verts {
        Ok(())
    } else {
        Err(format!(
            "accessor {} has {} elements for {n_verts} vertices",
            acc.index(),
            acc.count()
        ))
    }
}

/// Checks type, count and that the accessor's bytes (and its sparse indices and values) lie
/// inside their buffer views and buffers, so the reader can neither panic nor silently read
/// garbage, and an unreadable accessor is named with the reason.
pub(super) fn check(
    acc: &gltf::Accessor,
    dims: &[Dimensions],
    types: &[DataType],
    buffers: &[gltf::buffer::Data],
) -> Result<(), String> {
    let i = acc.index();
    if !dims.contains(&acc.dimensions()) {
        return Err(format!(
            "accessor {i} has type {:?}, expected {dims:?}",
            acc.dimensions()
        ));
    }
    if !types.contains(&acc.data_type()) {
        return Err(format!(
            "accessor {i} has component type {:?}, expected {types:?}",
            acc.data_type()
        ));
    }
    if acc.count() == 0 {
        return Err(format!("accessor {i} has count 0"));
    }
    let sparse = sparse_parts(acc, buffers)?;
    match acc.view() {
        Some(view) => {
            let what = format!("accessor {i}");
            strided(&what, &view, acc.offset(), acc.count(), acc.size(), buffers)?;
        }
        None if sparse.is_none() => {
            return Err(format!(
                "accessor {i} has neither bufferView nor sparse data"
            ));
        }
        None => {}
    }
    Ok(())
}
