//! Texture images: found (buffer view, data URI or file), sized from their header, decoded.
//!
//! Only images that a material's texture uses are touched at all: the others are not opened.
//! A used image's size is read from its header before it is decoded (a few hundred bytes of
//! PNG can declare 60,000 x 60,000 texels, and the decision to use the image must not cost
//! them), and an external file is read only up to what such an image can need.

use super::Ctx;
use super::uri::{self, Refused};
use crate::SceneError;
use crate::scene::Image;
use gltf::image::Source;
use image::{DynamicImage, ImageFormat, ImageReader};
use std::borrow::Cow;
use std::io::{BufRead, Cursor, Read, Seek};

/// Encoded bytes allowed per declared texel (RGBA16 PNG is 8, plus filter bytes, zlib and
/// chunk framing), and allowed on top for headers and metadata.
const MAX_BYTES_PER_TEXEL: u64 = 16;
const MAX_HEADER_BYTES: u64 = 1 << 20;

/// Decodes every image some material uses to RGBA8, while the texels its header declares fit
/// in `texels` (what is left of the budget for all images). Returns the decoded images and,
/// per glTF image index, its index among them (`None` when unused, or when it could not be
/// used: a warning, one line per kind of problem, and textures using it are dropped from
/// their materials). An image URI that leads outside the scene directory is an error.
pub(super) fn load(
    document: &gltf::Document,
    mut texels: u64,
    ctx: &mut Ctx,
) -> Result<(Vec<Image>, Vec<Option<u32>>), SceneError> {
    let used = used_images(document);
    let mut images = Vec::new();
    let mut map = Vec::new();
    for image in document.images() {
        if !used[image.index()] {
            map.push(None);
            continue;
        }
        match decode(&image, &mut texels, ctx) {
            Ok(img) => {
                map.push(Some(images.len() as u32));
                images.push(img);
            }
            Err(Unusable::Outside { uri, dir, reason }) => {
                return Err(SceneError::OutsidePath {
                    path: ctx.path.to_path_buf(),
                    what: format!("image {}", image.index()),
                    uri,
                    dir,
                    reason,
                });
            }
            Err(Unusable::Warn(kind, problem)) => {
                let i = image.index();
                let plural = format!("{}; textures using them are ignored", kind.plural());
                ctx.warnings.warn_item(
                    kind.key(),
                    &plural,
                    || format!("image {i}: {problem}"),
                    |_| {
                        format!(
                            "image {i} cannot be used ({problem}); textures using it are ignored"
                        )
                    },
                );
                map.push(None);
            }
        }
    }
    Ok((images, map))
}

/// Per glTF image, whether a texture of a material uses it (through a slot the loader reads,
/// with TEXCOORD_0).
fn used_images(document: &gltf::Document) -> Vec<bool> {
    let mut used = vec![false; document.images().len()];
    for m in document.materials() {
        let pbr = m.pbr_metallic_roughness();
        let slots = [
            pbr.base_color_texture(),
            pbr.metallic_roughness_texture(),
            m.emissive_texture(),
        ];
        for info in slots.into_iter().flatten() {
            if info.tex_coord() == 0 {
                used[info.texture().source().index()] = true;
            }
        }
    }
    used
}

/// Why an image is not used.
enum Unusable {
    /// Its URI leads outside the scene directory: an error, not a warning.
    Outside {
        uri: String,
        dir: std::path::PathBuf,
        reason: String,
    },
    Warn(Kind, String),
}

/// The kinds of problem, one warning line each.
#[derive(Clone, Copy)]
enum Kind {
    Missing,
    Unreadable,
    Undecodable,
    OverBudget,
}

impl Kind {
    fn key(self) -> &'static str {
        match self {
            Kind::Missing => "image-missing",
            Kind::Unreadable => "image-unreadable",
            Kind::Undecodable => "image-undecodable",
            Kind::OverBudget => "image-over-budget",
        }
    }

    fn plural(self) -> &'static str {
        match self {
            Kind::Missing => "images missing",
            Kind::Unreadable => "images unreadable",
            Kind::Undecodable => "images undecodable",
            Kind::OverBudget => "images over the loader's texel budget",
        }
    }
}

/// Where an image's encoded bytes are.
enum Encoded<'a> {
    Bytes(Cow<'a, [u8]>),
    File(std::fs::File, std::path::PathBuf),
}

fn decode(image: &gltf::Image, texels_left: &mut u64, ctx: &Ctx) -> Result<Image, Unusable> {
    let undecodable = |e: String| Unusable::Warn(Kind::Undecodable, e);
    let encoded = find(image, ctx)?;
    let (w, h) = match &encoded {
        Encoded::Bytes(b) => from_header(Cursor::new(&b[..])),
        Encoded::File(f, _) => from_header(std::io::BufReader::new(f)),
    }
    .map_err(undecodable)?;
    let declared = u64::from(w) * u64::from(h);
    if declared > *texels_left {
        let problem = format!(
            "its header declares {w} x {h} = {declared} texels, over the {} texels left of the \
             loader's budget for all images",
            *texels_left
        );
        return Err(Unusable::Warn(Kind::OverBudget, problem));
    }
    let bytes = match encoded {
        Encoded::Bytes(b) => b,
        Encoded::File(file, path) => {
            let max = declared
                .saturating_mul(MAX_BYTES_PER_TEXEL)
                .saturating_add(MAX_HEADER_BYTES);
            Cow::Owned(read_file(file, max).map_err(|e| {
                Unusable::Warn(Kind::Unreadable, format!("{}: {e}", path.display()))
            })?)
        }
    };
    let format = image::guess_format(&bytes).map_err(|e| undecodable(e.to_string()))?;
    let decoded = image::load_from_memory_with_format(&bytes, format).map_err(|e| match e {
        image::ImageError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
            undecodable("the image data is truncated (unexpected end of file)".into())
        }
        e => undecodable(e.to_string()),
    })?;
    let (width, height) = (decoded.width(), decoded.height());
    let rgba8 = to_rgba8(decoded).map_err(undecodable)?;
    *texels_left = texels_left.saturating_sub(u64::from(width) * u64::from(height));
    Ok(Image {
        name: image.name().map(str::to_string),
        width,
        height,
        rgba8,
    })
}

/// The image's encoded bytes, or its file opened (checked to be a regular file in the scene
/// directory).
fn find<'a>(image: &gltf::Image, ctx: &Ctx<'a>) -> Result<Encoded<'a>, Unusable> {
    let unreadable = |e: String| Unusable::Warn(Kind::Unreadable, e);
    match image.source() {
        Source::View { view, .. } => {
            let data = ctx
                .buffers
                .get(view.buffer().index())
                .map_or(&[][..], |d| &d.0);
            let bytes = view
                .offset()
                .checked_add(view.length())
                .and_then(|end| data.get(view.offset()..end))
                .ok_or_else(|| {
                    unreadable(format!("bufferView {} is out of range", view.index()))
                })?;
            Ok(Encoded::Bytes(Cow::Borrowed(bytes)))
        }
        Source::Uri { uri, .. } => match uri::locate(uri, ctx.base, ctx.allow_outside) {
            Ok(None) => {
                // As the reader splits it: the payload follows `;base64,` if present.
                let rest = uri.strip_prefix("data:").unwrap_or(uri);
                let payload = rest.split(";base64,").nth(1).unwrap_or(rest);
                let bytes = base64::decode(payload)
                    .map_err(|e| Unusable::Warn(Kind::Undecodable, format!("data URI: {e}")))?;
                Ok(Encoded::Bytes(Cow::Owned(bytes)))
            }
            Ok(Some(path)) => match crate::open_regular(&path) {
                Ok(file) => Ok(Encoded::File(file, path)),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(Unusable::Warn(
                    Kind::Missing,
                    format!("{}: file not found", path.display()),
                )),
                Err(e) => Err(unreadable(format!("{}: {e}", path.display()))),
            },
            Err(Refused::Outside { dir, reason }) => Err(Unusable::Outside {
                uri: uri.to_string(),
                dir,
                reason,
            }),
            Err(Refused::Other(e)) => Err(unreadable(e)),
        },
    }
}

/// Reads the whole of an opened image file, if it has at most `max` bytes.
fn read_file(mut file: std::fs::File, max: u64) -> std::io::Result<Vec<u8>> {
    file.rewind()?;
    let len = file.metadata()?.len();
    let too_large = |len: u64| {
        std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            format!(
                "the file has {len} bytes, more than an image of its declared size needs (at most {max})"
            ),
        )
    };
    if len > max {
        return Err(too_large(len));
    }
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// `(width, height)` that a PNG or JPEG header declares, read without decoding the texels (no
/// decoder limits apply: nothing is allocated for them).
fn from_header(reader: impl BufRead + Seek) -> Result<(u32, u32), String> {
    let mut reader = ImageReader::new(reader)
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    match reader.format() {
        Some(ImageFormat::Png | ImageFormat::Jpeg) => {}
        _ => return Err("unsupported image format (glTF images are PNG or JPEG)".into()),
    }
    reader.no_limits();
    reader.into_dimensions().map_err(|e| e.to_string())
}

/// RGBA8 texels: 16-bit channels keep their high byte, float channels are clamped to [0, 1],
/// grey is spread to RGB, and a missing alpha is opaque.
fn to_rgba8(image: DynamicImage) -> Result<Vec<u8>, String> {
    let high = |v: Vec<u16>| v.into_iter().map(|x| (x >> 8) as u8).collect::<Vec<u8>>();
    let unit = |v: Vec<f32>| {
        v.into_iter()
            .map(|x| (x.clamp(0.0, 1.0) * 255.0 + 0.5) as u8)
            .collect::<Vec<u8>>()
    };
    let (channels, samples) = match image {
        DynamicImage::ImageLuma8(i) => (1, i.into_raw()),
        DynamicImage::ImageLumaA8(i) => (2, i.into_raw()),
        DynamicImage::ImageRgb8(i) => (3, i.into_raw()),
        DynamicImage::ImageRgba8(i) => return Ok(i.into_raw()),
        DynamicImage::ImageLuma16(i) => (1, high(i.into_raw())),
        DynamicImage::ImageLumaA16(i) => (2, high(i.into_raw())),
        DynamicImage::ImageRgb16(i) => (3, high(i.into_raw())),
        DynamicImage::ImageRgba16(i) => (4, high(i.into_raw())),
        DynamicImage::ImageRgb32F(i) => (3, unit(i.into_raw())),
        DynamicImage::ImageRgba32F(i) => (4, unit(i.into_raw())),
        other => return Err(format!("unsupported pixel format {:?}", other.color())),
    };
    let mut rgba = Vec::with_capacity(samples.len() / channels * 4);
    for px in samples.chunks_exact(channels) {
        rgba.extend_from_slice(&match *px {
            [g] => [g, g, g, 255],
            [g, a] => [g, g, g, a],
            [r, g, b] => [r, g, b, 255],
            [r, g, b, a] => [r, g, b, a],
            _ => unreachable!("1 to 4 channels"),
        });
    }
    Ok(rgba)
}
