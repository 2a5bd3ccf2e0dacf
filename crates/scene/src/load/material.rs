//! Materials and textures (their images are in `images`).

use super::Ctx;
use crate::SceneError;
use crate::scene::{Material, Texture, Wrap};
use glam::Vec3;
use gltf::texture::{MagFilter, WrappingMode};

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
