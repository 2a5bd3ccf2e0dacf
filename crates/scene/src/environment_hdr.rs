//! Radiance `.hdr` pixels decoded straight into the map's texels, with one scanline buffer
//! besides. The `image` crate's decoder holds an 8192 x 4096 map three times over (its own
//! f32 copy, the bytes it returns, then the texels made from them): 1.1 GB for a map of
//! 384 MB. The header is still read by `image` (`HdrDecoder`), and a pixel converts as its
//! `Rgbe8Pixel::to_hdr` does, so the texels are the same bits (tested against it).

use glam::Vec3;
use image::ImageDecoder;
use image::codecs::hdr::HdrDecoder;
use std::io::Cursor;

/// The map's size from the header, and the bytes after it (the scanlines).
pub(super) fn header(bytes: &[u8]) -> Result<(u32, u32, &[u8]), String> {
    let mut cursor = Cursor::new(bytes);
    // The header is read a byte at a time: the cursor stops where the pixels start.
    let (width, height) = HdrDecoder::new(&mut cursor)
        .map_err(|e| e.to_string())?
        .dimensions();
    let start = usize::try_from(cursor.position()).unwrap_or(bytes.len());
    Ok((width, height, bytes.get(start..).unwrap_or_default()))
}

/// The `width * height` texels of the scanlines in `data`, top row first.
pub(super) fn pixels(data: &[u8], width: u32, height: u32) -> Result<Vec<Vec3>, String> {
    let (w, h) = (width as usize, height as usize);
    let mut reader = Reader { data, at: 0 };
    let mut row = vec![[0u8; 4]; w];
    // Reserved, not touched: a truncated file commits only the rows it has.
    let mut texels = Vec::with_capacity(w * h);
    for _ in 0..h {
        if w > 0 {
            scanline(&mut reader, &mut row)?;
        }
        texels.extend(row.iter().map(|&p| to_hdr(p)));
    }
    Ok(texels)
}

/// An RGBE pixel as linear RGB: `image`'s `Rgbe8Pixel::to_hdr`, operation for operation.
fn to_hdr([r, g, b, e]: [u8; 4]) -> Vec3 {
    if e == 0 {
        return Vec3::ZERO;
    }
    let exp = f32::exp2(f32::from(e) - (128.0 + 8.0));
    Vec3::new(exp * f32::from(r), exp * f32::from(g), exp * f32::from(b))
}

/// The scanline bytes, read front to back.
struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn bytes(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self.at.saturating_add(n);
        let b = self
            .data
            .get(self.at..end)
            .ok_or("the file ends before its last scanline")?;
        self.at = end;
        Ok(b)
    }

    fn byte(&mut self) -> Result<u8, String> {
        Ok(self.bytes(1)?[0])
    }

    fn pixel(&mut self) -> Result<[u8; 4], String> {
        let b = self.bytes(4)?;
        Ok([b[0], b[1], b[2], b[3]])
    }
}

fn wrong_length(got: usize, width: usize) -> String {
    format!("Wrong length of decoded scanline: got {got}, expected {width}")
}

/// One scanline into `row` (not empty): per-component run lengths when it starts with the
/// marker `(2, 2, < 128, _)`, else the old format of pixels and run markers `(1, 1, 1, n)`.
fn scanline(r: &mut Reader, row: &mut [[u8; 4]]) -> Result<(), String> {
    let width = row.len();
    let first = r.pixel()?;
    if first[0] == 2 && first[1] == 2 && first[2] < 128 {
        for c in 0..4 {
            let mut pos = 0;
            while pos < width {
                let n = r.byte()? as usize;
                let (count, run) = if n <= 128 {
                    (n, false)
                } else {
                    (n - 128, true)
                };
                if pos + count > width {
                    return Err(wrong_length(pos + count, width));
                }
                if run {
                    let v = r.byte()?;
                    row[pos..pos + count].iter_mut().for_each(|p| p[c] = v);
                } else {
                    let values = r.bytes(count)?;
                    for (p, &v) in row[pos..pos + count].iter_mut().zip(values) {
                        p[c] = v;
                    }
                }
                // (A zero count reads nothing and moves nowhere, as `image` allows.)
                pos += count;
            }
        }
        return Ok(());
    }
    let marker = |p: [u8; 4]| (p[..3] == [1, 1, 1]).then_some(p[3] as usize);
    if marker(first).is_some() {
        return Err("First pixel of a scanline shouldn't be run length marker".into());
    }
    row[0] = first;
    let (mut x, mut multiplier, mut previous) = (1, 1usize, first);
    while x < width {
        let p = r.pixel()?;
        match marker(p) {
            Some(n) => {
                // Consecutive markers are the higher bytes of one run length.
                let run = n.saturating_mul(multiplier);
                multiplier = multiplier.saturating_mul(256);
                if x.saturating_add(run) > width {
                    return Err(wrong_length(x.saturating_add(run), width));
                }
                row[x..x + run].fill(previous);
                x += run;
            }
            None => {
                multiplier = 1;
                previous = p;
                row[x] = p;
                x += 1;
            }
        }
    }
    Ok(())
}
