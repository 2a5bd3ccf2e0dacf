//! The scene as storage images for the trace pass (layout: `blueshift_scene::gpu::texels`):
//! each texel array is written a chunk at a time into a staging buffer and copied into its
//! `rgba32ui` image by `scene/upload_texels`, once per scene.
use crate::{Result, TraceError};
use blueshift_device::{
    Binding, Buffer, ComputePipeline, Device, Image, MemoryLocation, Recorder, vk,
};
use blueshift_scene::SceneGpu;
use blueshift_scene::gpu::{Texel, TexelSource};

/// The scene images, in the trace pass's binding order.
pub struct SceneImages {
    pub nodes: Image,
    pub triangles: Image,
    pub shading: Image,
    pub materials: Image,
    pub textures: Image,
    pub texels: Image,
    pub lights: Image,
    /// Whether any material uses a texture (selects the trace variant with texture lookups).
    pub textured: bool,
    /// Whether every material a triangle uses has metallic = specular = 0 (selects the
    /// Lambert-only trace variant: the glTF BRDF is then exactly Lambert).
    pub lambert: bool,
    /// Whether the scene has punctual lights or an environment map (selects the trace
    /// variant that samples them).
    pub punctual_or_map: bool,
}

impl std::fmt::Debug for SceneImages {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneImages")
            .field("nodes", &(self.nodes.width, self.nodes.height))
            .field("textured", &self.textured)
            .field("lambert", &self.lambert)
            .field("punctual_or_map", &self.punctual_or_map)
            .finish_non_exhaustive()
    }
}

/// Texels per upload chunk: 16 MiB of staging (far under the 128 MiB every device allows a
/// storage buffer), however large the scene.
const CHUNK_TEXELS: usize = 1 << 20;

impl SceneImages {
    /// Uploads `scene`'s texel arrays, each written a chunk at a time into one staging buffer
    /// (one submission per chunk, waited on): the host holds no repacked copy of the scene.
    pub fn new(dev: &Device, scene: &SceneGpu) -> Result<Self> {
        let sources = scene.texel_sources();
        let max = dev.info().max_image_dimension_2d;
        let side = sources
            .iter()
            .map(|s| {
                let (w, h) = s.extent();
                w.max(h)
            })
            .max()
            .unwrap_or(1);
        if side > max {
            return Err(TraceError::Scene(format!(
                "the scene needs a {side}-texel image side, over the device's maxImageDimension2D {max}"
            )));
        }
        let upload = blueshift_shaders::pipeline(
            dev,
            "scene/upload_texels",
            &[Binding::storage(0, "src"), Binding::image(1, "dst")],
            8,
        )?;
        let chunk = sources
            .iter()
            .map(|s| s.len())
            .max()
            .unwrap_or(1)
            .min(CHUNK_TEXELS);
        let mut host = vec![[0u32; 4]; chunk];
        let mut staging = Buffer::new(
            dev,
            "scene.upload.staging",
            (chunk * size_of::<Texel>()) as u64,
            MemoryLocation::CpuToGpu,
        )?;
        let mut rec = Recorder::new(dev, "scene.upload")?;
        let mut image = |s: &TexelSource| -> Result<Image> {
            let (w, h) = s.extent();
            let img = Image::new(dev, s.name, w, h, vk::Format::R32G32B32A32_UINT)?;
            for first in (0..s.len()).step_by(chunk) {
                let n = chunk.min(s.len() - first);
                s.write(first, &mut host[..n]);
                staging.write(0, &host[..n])?;
                rec.begin()?;
                rec.begin_pass("upload_texels")?;
                if first == 0 {
                    rec.init_image(&img)?;
                }
                upload_texels(&mut rec, &upload, &staging, &img, first as u32, n as u32)?;
                rec.submit_and_wait()?;
            }
            Ok(img)
        };
        let [
            nodes,
            triangles,
            shading,
            materials,
            textures,
            texels,
            lights,
        ] = &sources;
        Ok(Self {
            nodes: image(nodes)?,
            triangles: image(triangles)?,
            shading: image(shading)?,
            materials: image(materials)?,
            textures: image(textures)?,
            texels: image(texels)?,
            lights: image(lights)?,
            textured: scene
                .materials
                .iter()
                .any(|m| m.base_color_tex >= 0 || m.emissive_tex >= 0 || m.mr_tex >= 0),
            // (A metallic-roughness texture scales metallic, so 0 stays 0.)
            lambert: scene.shading.iter().all(|t| {
                let m = scene.materials.get(t.material as usize);
                m.is_some_and(|m| m.metallic == 0.0 && m.specular == 0.0)
            }),
            punctual_or_map: !scene.light_params.is_empty() || scene.environment.is_some(),
        })
    }
}

/// Records the copy of `count` texels from `src` into the scene image `dst`, from its texel
/// `first` on.
fn upload_texels(
    rec: &mut Recorder,
    pipeline: &ComputePipeline,
    src: &Buffer,
    dst: &Image,
    first: u32,
    count: u32,
) -> Result<()> {
    let groups = count.div_ceil(64);
    let x = groups.min(rec.device().info().max_compute_work_group_count[0]);
    rec.dispatch(
        pipeline,
        &[("src", src.into()), ("dst", dst.into())],
        bytemuck::cast_slice(&[first, count]),
        [x, groups.div_ceil(x), 1],
    )?;
    Ok(())
}
