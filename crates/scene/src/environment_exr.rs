//! OpenEXR maps decoded straight into the map's own texels (RGB f32), with the `exr` crate.
//!
//! The `image` crate's decoder holds the pixels twice (its own `f32` buffer, then the image
//! it returns), and an RGBA file a third time once converted to RGB: up to 44 bytes a texel
//! for the 12 the map keeps. Here the one buffer is allocated after the caller has accepted
//! the size from the header, and each pixel is written into it as its block is decompressed.
//!
//! The texels are what `image` decodes (`DynamicImage::into_rgb32f`): the first layer that is
//! not deep and has R, G and B channels; its display window gives the size and its data
//! window is placed in it (texels outside the data window stay black, pixels outside the
//! display window are dropped); alpha is ignored.

use exr::meta::header::Header;
use exr::prelude::{ReadChannels, ReadLayers};
use glam::Vec3;
use std::io::Cursor;

/// The layer of an `.exr` file that is decoded: its display window and where its data window
/// starts in it.
pub(super) struct ExrLayer {
    pub width: u32,
    pub height: u32,
    offset: (i64, i64),
}

/// The layer to decode (the first with R, G and B channels that is not deep), from the file's
/// headers alone.
pub(super) fn header(bytes: &[u8]) -> Result<ExrLayer, String> {
    let meta = exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), false)
        .map_err(|e| e.to_string())?;
    let rgb = |h: &&Header| {
        !h.deep
            && ["R", "G", "B"]
                .iter()
                .all(|&c| h.channels.find_index_of_channel(&c.into()).is_some())
    };
    let h = meta
        .headers
        .iter()
        .find(rgb)
        .ok_or("no layer has R, G and B channels")?;
    let display = h.shared_attributes.display_window;
    let offset = h.own_attributes.layer_position - display.position;
    let side = |s: usize| u32::try_from(s).map_err(|_| format!("a side of {s} pixels"));
    Ok(ExrLayer {
        width: side(display.size.width())?,
        height: side(display.size.height())?,
        offset: (i64::from(offset.x()), i64::from(offset.y())),
    })
}

/// The texels of `layer` (from [`header`] of the same bytes), rows from the top. Allocates
/// `width x height` texels: call it with a size the caller has accepted.
pub(super) fn pixels(bytes: &[u8], layer: &ExrLayer) -> Result<Vec<Vec3>, String> {
    let (w, h) = (layer.width as usize, layer.height as usize);
    let (dx, dy) = layer.offset;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            move |_, _| vec![Vec3::ZERO; w * h],
            move |texels: &mut Vec<Vec3>, at, (r, g, b, _): (f32, f32, f32, f32)| {
                let (x, y) = (at.x() as i64 + dx, at.y() as i64 + dy);
                if (0..w as i64).contains(&x) && (0..h as i64).contains(&y) {
                    texels[y as usize * w + x as usize] = Vec3::new(r, g, b);
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| e.to_string())?;
    let texels = image.layer_data.channel_data.pixels;
    // The layer read is the one `header` picked (the same rule), so of the size it gave.
    if texels.len() != w * h {
        return Err("the layer read is not the one the headers describe".into());
    }
    Ok(texels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{EnvMap, EnvMapError};
    use exr::prelude::{
        Encoding, Image, ImageAttributes, IntegerBounds, Layer, LayerAttributes, SpecificChannels,
        Vec2, WritableImage, f16,
    };
    use std::path::Path;

    /// A test value for pixel `(x, y)` of layer `k`: distinct, negative and tiny ones included.
    fn value(k: usize, x: usize, y: usize, c: usize) -> f32 {
        let v = (k * 131 + x * 17 + y * 29 + c * 7) % 23;
        (v as f32 - 5.0) * 0.37
    }

    /// A layer to write: its size, its position in the display window, and RGBA (else `Y`).
    type TestLayer = ((usize, usize), (i32, i32), bool);

    /// An `.exr` whose display window is `display`; each layer is `(size, position, rgb)`, an
    /// RGBA layer (R as f16, the rest f32) or, without `rgb`, a layer of a `Y` channel only.
    fn exr_bytes(display: (usize, usize), layers: &[TestLayer]) -> Vec<u8> {
        let window = ImageAttributes::new(IntegerBounds::from_dimensions(display));
        let attributes = |k: usize, position: (i32, i32)| {
            let mut a = LayerAttributes::named(format!("layer{k}").as_str());
            a.layer_position = Vec2(position.0, position.1);
            a
        };
        let mut out = Cursor::new(Vec::new());
        if let [(size, position, false)] = layers {
            let y = SpecificChannels::build()
                .with_channel("Y")
                .with_pixel_fn(|_: Vec2<usize>| (1.0f32,));
            let layer = Layer::new(*size, attributes(0, *position), Encoding::UNCOMPRESSED, y);
            let image = Image::from_layers(window, vec![layer]);
            image.write().to_buffered(&mut out).expect("write");
            return out.into_inner();
        }
        let rgba = |k: usize, size, position| {
            let pixel = move |p: Vec2<usize>| {
                let v = |c| value(k, p.x(), p.y(), c);
                (f16::from_f32(v(0)), v(1), v(2), v(3))
            };
            let channels = SpecificChannels::rgba(pixel);
            Layer::new(
                size,
                attributes(k, position),
                Encoding::FAST_LOSSLESS,
                channels,
            )
        };
        let all: Vec<_> = (layers.iter().enumerate())
            .map(|(k, &(size, position, _))| rgba(k, size, position))
            .collect();
        Image::from_layers(window, all)
            .write()
            .to_buffered(&mut out)
            .expect("write");
        out.into_inner()
    }

    /// This module's decoding: `(width, height, texels)`.
    fn decodes(bytes: &[u8]) -> (u32, u32, Vec<Vec3>) {
        let layer = header(bytes).expect("header");
        let texels = pixels(bytes, &layer).expect("pixels");
        (layer.width, layer.height, texels)
    }

    /// `image`'s decoding (the reference), as RGB texels.
    fn image_decodes(bytes: &[u8]) -> (u32, u32, Vec<Vec3>) {
        let img = image::load_from_memory_with_format(bytes, image::ImageFormat::OpenExr)
            .expect("image decodes")
            .into_rgb32f();
        let texels = img.pixels().map(|p| Vec3::from_array(p.0)).collect();
        (img.width(), img.height(), texels)
    }

    #[test]
    fn exr_maps_decode_to_what_image_decodes() {
        let cases: [((usize, usize), &[TestLayer]); 4] = [
            // One layer filling the display window.
            ((5, 3), &[((5, 3), (0, 0), true)]),
            // A data window inside it (black around), and one sticking out of it.
            ((6, 4), &[((4, 2), (1, 1), true)]),
            ((5, 4), &[((4, 3), (-1, 2), true)]),
            // Two RGBA layers: the first is decoded.
            ((3, 2), &[((3, 2), (0, 0), true), ((3, 2), (0, 0), true)]),
        ];
        for (display, layers) in cases {
            let bytes = exr_bytes(display, layers);
            assert_eq!(
                decodes(&bytes),
                image_decodes(&bytes),
                "{display:?} {layers:?}"
            );
        }
        // RGB and RGBA f32 files as `image` writes them.
        for rgba in [false, true] {
            let v: Vec<f32> = (0..24).map(|i| value(0, i, i / 4, i % 3)).collect();
            let img = if rgba {
                image::DynamicImage::ImageRgba32F(
                    image::Rgba32FImage::from_raw(3, 2, v).expect("3x2"),
                )
            } else {
                image::DynamicImage::ImageRgb32F(
                    image::Rgb32FImage::from_raw(4, 2, v).expect("4x2"),
                )
            };
            let mut bytes = Cursor::new(Vec::new());
            img.write_to(&mut bytes, image::ImageFormat::OpenExr)
                .expect("exr");
            let bytes = bytes.into_inner();
            assert_eq!(decodes(&bytes), image_decodes(&bytes), "rgba {rgba}");
        }
    }

    #[test]
    fn an_exr_without_rgb_or_too_large_is_refused_from_its_headers() {
        let y_only = exr_bytes((4, 2), &[((4, 2), (0, 0), false)]);
        let e = EnvMap::from_bytes(Path::new("y.exr"), &y_only).unwrap_err();
        assert!(e.to_string().contains("no layer has R, G and B"), "{e}");
        // A display window of 16385 x 1 around 2 x 1 stored pixels: refused by size, not decoded.
        let wide = exr_bytes((16385, 1), &[((2, 1), (0, 0), true)]);
        let e = EnvMap::from_bytes(Path::new("wide.exr"), &wide).unwrap_err();
        assert!(
            matches!(
                e,
                EnvMapError::Size {
                    width: 16385,
                    height: 1,
                    ..
                }
            ),
            "{e}"
        );
    }
}
