//! Materials, textures and images.

use super::Ctx;
use crate::SceneError;
use crate::scene::{Image, Material, Texture, Wrap};
use glam::Vec3;
use gltf::image::Format;
use gltf::texture::{MagFilter, WrappingMode};
use std::path::Path;

/// Decodes every image to RGBA8, while the texels its header declares fit in `texels` (what
/// is left of the budget for all images). Returns the decoded images and, per glTF image
/// index, its index among them (`None` when it could not be used: a warning, and textures
/// using it are dropped from their materials).
pub(super) fn load_images(
    document: &gltf::Document,
    base: Option<&Path>,
    mut texels: u64,
    ctx: &mut Ctx,
) -> (Vec<Image>, Vec<Option<u32>>) {
    let mut images = Vec::new();
    let mut map = Vec::new();
    for image in document.images() {
        match decode(&image, base, &mut texels, ctx) {
            Ok(img) => {
                map.push(Some(images.len() as u32));
                images.push(img);
            }
            Err(problem) => {
                let i = image.index();
                ctx.warnings.warn_item(
                    "image",
                    "images cannot be used; textures using them are ignored",
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
    (images, map)
}

fn decode(
    image: &gltf::Image,
    base: Option<&Path>,
    texels_left: &mut u64,
    ctx: &Ctx,
) -> Result<Image, String> {
    if let gltf::image::Source::View { view, .. } = image.source() {
        let len = ctx
            .buffers
            .get(view.buffer().index())
            .map_or(0, |d| d.len());
        if view
            .offset()
            .checked_add(view.length())
            .is_none_or(|end| end > len)
        {
            return Err(format!("bufferView {} is out of range", view.index()));
        }
    }
    let mut base = base;
    if let gltf::image::Source::Uri { uri, .. } = image.source() {
        super::uri::check(uri, base)?;
        if base.is_none() {
            if !uri.starts_with("data:") {
                return Err("an external image in a scene loaded from memory".into());
            }
            base = Some(Path::new(".")); // the reader decodes data URIs only when given a base
        }
    }
    let (w, h) = super::image_size::declared(image.source(), base.unwrap_or(Path::new(".")), ctx)?;
    let declared = u64::from(w) * u64::from(h);
    if declared > *texels_left {
        return Err(format!(
            "its header declares {w} x {h} = {declared} texels, over the {} texels left of the \
             loader's budget for all images",
            *texels_left
        ));
    }
    let data = gltf::image::Data::from_source(image.source(), base, ctx.buffers)
        .map_err(|e| e.to_string())?;
    let n = data.width as usize * data.height as usize;
    let px = &data.pixels;
    let mut rgba = Vec::with_capacity(n * 4);
    let f32_at = |i: usize| {
        let b = [px[i * 4], px[i * 4 + 1], px[i * 4 + 2], px[i * 4 + 3]];
        (f32::from_le_bytes(b).clamp(0.0, 1.0) * 255.0 + 0.5) as u8
    };
    let (channels, bytes_per) = match data.format {
        Format::R8 => (1, 1),
        Format::R8G8 => (2, 1),
        Format::R8G8B8 => (3, 1),
        Format::R8G8B8A8 => (4, 1),
        Format::R16 => (1, 2),
        Format::R16G16 => (2, 2),
        Format::R16G16B16 => (3, 2),
        Format::R16G16B16A16 => (4, 2),
        Format::R32G32B32FLOAT => (3, 4),
        Format::R32G32B32A32FLOAT => (4, 4),
    };
    if px.len() < n * channels * bytes_per {
        return Err("decoded pixel data is too short".into());
    }
    for p in 0..n {
        let mut c = [0u8, 0, 0, 255];
        for (ch, out) in c.iter_mut().enumerate().take(channels) {
            let i = p * channels + ch;
            *out = match bytes_per {
                1 => px[i],
                2 => px[i * 2 + 1], // little-endian u16: keep the high byte
                _ => f32_at(i),
            };
        }
        match channels {
            1 => [c[1], c[2]] = [c[0], c[0]],             // grey
            2 => [c[3], c[1], c[2]] = [c[1], c[0], c[0]], // grey + alpha
            _ => {}
        }
        rgba.extend_from_slice(&c);
    }
    *texels_left = texels_left.saturating_sub(n as u64);
    Ok(Image {
        name: image.name().map(str::to_string),
        width: data.width,
        height: data.height,
        rgba8: rgba,
    })
}

pub(super) fn load_textures(
    document: &gltf::Document,
    image_map: &[Option<u32>],
) -> Vec<Option<Texture>> {
    let wrap = |m: WrappingMode| match m {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
    };
    document
        .textures()
        .map(|t| {
            let image = image_map.get(t.source().index()).copied().flatten()?;
            let s = t.sampler();
            Some(Texture {
                image,
                wrap_s: wrap(s.wrap_s()),
                wrap_t: wrap(s.wrap_t()),
                nearest: s.mag_filter() == Some(MagFilter::Nearest),
            })
        })
        .collect()
}

/// Reads every material. Texture indices are remapped to the usable textures, which are
/// appended to `textures` (compacted: undecodable ones are dropped). An emission (factor times
/// strength) that overflows f32 is an error.
pub(super) fn load_materials(
    document: &gltf::Document,
    all_textures: &[Option<Texture>],
    textures: &mut Vec<Texture>,
    ctx: &mut Ctx,
) -> Result<Vec<Material>, SceneError> {
    let mut remap: Vec<Option<u32>> = vec![None; all_textures.len()];
    let mut use_texture = |info: Option<gltf::texture::Info>, slot: &str, ctx: &mut Ctx| {
        let info = info?;
        if info.tex_coord() != 0 {
            let set = info.tex_coord();
            ctx.warnings.warn_item(
                "texcoord",
                "textures using a TEXCOORD other than TEXCOORD_0 ignored",
                || format!("{slot} texture using TEXCOORD_{set}"),
                |_| format!("{slot} textures using TEXCOORD_{set} ignored (only TEXCOORD_0)"),
            );
            return None;
        }
        let i = info.texture().index();
        if let Some(r) = remap[i] {
            return Some(r);
        }
        let tex = all_textures.get(i).copied().flatten()?;
        let r = textures.len() as u32;
        textures.push(tex);
        remap[i] = Some(r);
        Some(r)
    };
    let mut out = Vec::new();
    for m in document.materials() {
        let pbr = m.pbr_metallic_roughness();
        let strength = m.emissive_strength().unwrap_or(1.0);
        if m.normal_texture().is_some() {
            ctx.warnings.warn("normalmap", || {
                "normal maps ignored (interpolated normals used)".into()
            });
        }
        if m.alpha_mode() != gltf::material::AlphaMode::Opaque {
            ctx.warnings.warn("alpha", || {
                "alpha modes MASK/BLEND not supported: materials treated as opaque".into()
            });
        }
        let finite = |x: f32, default: f32| if x.is_finite() { x } else { default };
        let bc = pbr.base_color_factor().map(|x| finite(x, 1.0).max(0.0));
        // Non-finite emission (a product that overflows f32, or a strength written as 1e39)
        // would render black or NaN: an error, not a silent zero.
        let factor = Vec3::from(m.emissive_factor());
        let emissive = if factor == Vec3::ZERO {
            Vec3::ZERO
        } else {
            factor * strength
        };
        if !emissive.is_finite() {
            let name = m.name().map_or(String::new(), |n| format!(" ('{n}')"));
            return Err(SceneError::Light {
                path: ctx.path.to_path_buf(),
                what: format!("material {}{name}", m.index().unwrap_or_default()),
                problem: format!(
                    "has emissiveFactor {:?} times emissiveStrength {strength:?}, which is not \
                     finite in f32 (infinite radiance renders black); scale the emission down",
                    factor.to_array()
                ),
            });
        }
        let (specular, specular_color) = specular_of(&m, ctx);
        out.push(Material {
            name: m.name().map(str::to_string),
            base_color: bc,
            metallic: finite(pbr.metallic_factor(), 1.0).clamp(0.0, 1.0),
            roughness: finite(pbr.roughness_factor(), 1.0).clamp(0.0, 1.0),
            emissive: emissive.max(Vec3::ZERO),
            specular,
            specular_color,
            base_color_texture: use_texture(pbr.base_color_texture(), "base color", ctx),
            metallic_roughness_texture: use_texture(
                pbr.metallic_roughness_texture(),
                "metallic-roughness",
                ctx,
            ),
            emissive_texture: use_texture(m.emissive_texture(), "emissive", ctx),
            double_sided: m.double_sided(),
        });
    }
    Ok(out)
}

/// KHR_materials_specular factors (1 and white without the extension). Its textures are
/// skipped with one warning; non-finite factors fall back to the defaults.
fn specular_of(m: &gltf::Material, ctx: &mut Ctx) -> (f32, Vec3) {
    let Some(s) = m.specular() else {
        return (1.0, Vec3::ONE);
    };
    if s.specular_texture().is_some() || s.specular_color_texture().is_some() {
        ctx.warnings.warn("specular-texture", || {
            "KHR_materials_specular textures ignored (the factors are used)".into()
        });
    }
    let f = s.specular_factor();
    let factor = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        1.0
    };
    let c = Vec3::from(s.specular_color_factor());
    let color = if c.is_finite() {
        c.max(Vec3::ZERO)
    } else {
        Vec3::ONE
    };
    (factor, color)
}
