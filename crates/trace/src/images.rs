//! The scene as storage images for the trace pass (layout: `blueshift_scene::gpu::texels`):
//! each texel array is uploaded to a staging buffer and copied into its `rgba32ui` image by
//! `scene/upload_texels`, once per scene.
use crate::{Result, TraceError};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Image, Recorder, vk};
use blueshift_scene::SceneGpu;
use blueshift_scene::gpu::TexelArray;

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

impl SceneImages {
    /// Packs `scene` into texels and uploads them (one submission, waited on).
    pub fn new(dev: &Device, scene: &SceneGpu) -> Result<Self> {
        let t = scene.texels();
        let max = dev.info().max_image_dimension_2d;
        if t.max_extent() > max {
            return Err(TraceError::Scene(format!(
                "the scene needs a {}-texel image side, over the device's maxImageDimension2D {max}",
                t.max_extent()
            )));
        }
        let upload = blueshift_shaders::pipeline(
            dev,
            "scene/upload_texels",
            &[Binding::storage(0, "src"), Binding::image(1, "dst")],
            4,
        )?;
        let mut rec = Recorder::new(dev, "scene.upload")?;
        rec.begin()?;
        rec.begin_pass("upload_texels")?;
        let mut staging = Vec::new();
        let mut image = |a: &TexelArray| -> Result<Image> {
            let (w, h) = a.extent();
            let img = Image::new(dev, a.name, w, h, vk::Format::R32G32B32A32_UINT)?;
            let src = Buffer::from_slice(dev, &format!("{}.staging", a.name), &a.texels)?;
            rec.init_image(&img)?;
            upload_texels(&mut rec, &upload, &src, &img, a.texels.len() as u32)?;
            staging.push(src);
            Ok(img)
        };
        let images = Self {
            nodes: image(&t.nodes)?,
            triangles: image(&t.triangles)?,
            shading: image(&t.shading)?,
            materials: image(&t.materials)?,
            textures: image(&t.textures)?,
            texels: image(&t.texels)?,
            lights: image(&t.lights)?,
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
        };
        rec.submit_and_wait()?;
        drop(staging);
        Ok(images)
    }
}

/// Records the copy of `count` texels from `src` into the scene image `dst`.
fn upload_texels(
    rec: &mut Recorder,
    pipeline: &ComputePipeline,
    src: &Buffer,
    dst: &Image,
    count: u32,
) -> Result<()> {
    let groups = count.div_ceil(64);
    let x = groups.min(rec.device().info().max_compute_work_group_count[0]);
    rec.dispatch(
        pipeline,
        &[("src", src.into()), ("dst", dst.into())],
        bytemuck::bytes_of(&count),
        [x, groups.div_ceil(x), 1],
    )?;
    Ok(())
}
