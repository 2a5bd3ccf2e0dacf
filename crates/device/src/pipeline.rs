//! Compute pipelines whose declared bindings are checked against the SPIR-V.
//!
//! Every pass declares its bindings explicitly (set 0, binding number, kind, and the name the
//! GLSL gives the resource). At creation the declaration is compared with what the SPIR-V
//! itself declares, names included, so a shader/host mismatch (two buffers of one kind swapped
//! included) is an error naming the shader, set and binding instead of garbage on screen.
//! Dispatches then bind resources by those names ([`crate::Recorder::dispatch`]).
use crate::device::Device;
use crate::error::{DeviceError, Result, VkContext};
use ash::vk;
use rspirv_reflect::rspirv::dr::{Instruction, Module, Operand};
use rspirv_reflect::spirv::{Decoration, Op};
use rspirv_reflect::{BindingCount, DescriptorType, Reflection};

/// The kind of resource at a binding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BindingKind {
    StorageBuffer,
    UniformBuffer,
    StorageImage,
}

impl BindingKind {
    pub(crate) fn vk(self) -> vk::DescriptorType {
        match self {
            Self::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
            Self::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
            Self::StorageImage => vk::DescriptorType::STORAGE_IMAGE,
        }
    }
    fn from_reflect(t: DescriptorType) -> Option<Self> {
        match t {
            DescriptorType::STORAGE_BUFFER => Some(Self::StorageBuffer),
            DescriptorType::UNIFORM_BUFFER => Some(Self::UniformBuffer),
            DescriptorType::STORAGE_IMAGE => Some(Self::StorageImage),
            _ => None,
        }
    }
}

/// One declared binding of set 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Binding {
    pub binding: u32,
    pub kind: BindingKind,
    /// The resource's name in the shader: the variable's, or for a block without an instance
    /// name its first member's (`buffer Seeds { uint seeds[]; }` is `seeds`).
    pub name: &'static str,
}

/// Shorthand constructors.
impl Binding {
    pub const fn storage(binding: u32, name: &'static str) -> Self {
        Self {
            binding,
            kind: BindingKind::StorageBuffer,
            name,
        }
    }
    pub const fn uniform(binding: u32, name: &'static str) -> Self {
        Self {
            binding,
            kind: BindingKind::UniformBuffer,
            name,
        }
    }
    pub const fn image(binding: u32, name: &'static str) -> Self {
        Self {
            binding,
            kind: BindingKind::StorageImage,
            name,
        }
    }
}

/// What the SPIR-V declares, as used by the check.
#[derive(Debug, Clone)]
pub struct ShaderInterface {
    /// (set, binding, kind or None for an unsupported kind, name as in [`Binding::name`])
    pub bindings: Vec<(u32, u32, Option<BindingKind>, String)>,
    pub push_constant_size: u32,
    pub workgroup_size: (u32, u32, u32),
    /// Bindings of set 0 the shader declares `readonly` (never written): what a dispatch may
    /// share with other readers without a barrier.
    pub read_only: Vec<u32>,
}

/// Reflects set/binding/kind, push-constant size and workgroup size from SPIR-V words.
pub fn reflect(shader: &str, spirv: &[u32]) -> Result<ShaderInterface> {
    let err = |detail: String| DeviceError::Shader {
        shader: shader.to_string(),
        detail,
    };
    let refl = Reflection::new_from_spirv(bytemuck::cast_slice(spirv))
        .map_err(|e| err(format!("SPIR-V reflection failed: {e:?}")))?;
    let sets = refl
        .get_descriptor_sets()
        .map_err(|e| err(format!("reading descriptor sets: {e:?}")))?;
    let mut bindings = Vec::new();
    let mut read_only = Vec::new();
    for (set, map) in sets {
        for (binding, info) in map {
            if info.binding_count != BindingCount::One {
                return Err(DeviceError::BindingMismatch {
                    shader: shader.to_string(),
                    set,
                    binding,
                    detail: "arrays of descriptors are not supported (no descriptor indexing on lavapipe)".into(),
                });
            }
            if set == 0 && never_written(&refl.0, binding) {
                read_only.push(binding);
            }
            let name = resource_name(&refl.0, set, binding).unwrap_or(info.name);
            bindings.push((set, binding, BindingKind::from_reflect(info.ty), name));
        }
    }
    let push_constant_size = refl
        .get_push_constant_range()
        .map_err(|e| err(format!("reading push constants: {e:?}")))?
        .map_or(0, |p| p.offset + p.size);
    let workgroup_size = refl.get_compute_group_size().unwrap_or((1, 1, 1));
    Ok(ShaderInterface {
        bindings,
        push_constant_size,
        workgroup_size,
        read_only,
    })
}

/// Whether the set-0 resource at `binding` is `NonWritable`: the variable itself (images), or
/// every member of its block (GLSL's `readonly buffer`).
fn never_written(m: &Module, binding: u32) -> bool {
    let Some(var) = binding_variable(m, 0, binding) else {
        return false;
    };
    let non_writable = |i: &Instruction, at: usize| {
        matches!(
            i.operands.get(at),
            Some(Operand::Decoration(Decoration::NonWritable))
        )
    };
    let Some(id) = var.result_id else {
        return false;
    };
    if m.annotations
        .iter()
        .any(|a| a.class.opcode == Op::Decorate && operand_is(a, 0, id) && non_writable(a, 1))
    {
        return true;
    }
    let Some(block) = pointee(m, var) else {
        return false;
    };
    let members = m
        .types_global_values
        .iter()
        .find(|i| i.class.opcode == Op::TypeStruct && i.result_id == Some(block))
        .map_or(0, |i| i.operands.len());
    let read_only = m
        .annotations
        .iter()
        .filter(|a| {
            a.class.opcode == Op::MemberDecorate && operand_is(a, 0, block) && non_writable(a, 2)
        })
        .count();
    members > 0 && read_only == members
}

/// The `OpVariable` decorated with (set, binding).
fn binding_variable(m: &Module, set: u32, binding: u32) -> Option<&Instruction> {
    let decorated = |id: u32, d: Decoration, v: u32| {
        m.annotations.iter().any(|a| {
            operand_is(a, 0, id)
                && matches!(a.operands.get(1), Some(Operand::Decoration(x)) if *x == d)
                && matches!(a.operands.get(2), Some(Operand::LiteralBit32(x)) if *x == v)
        })
    };
    m.types_global_values.iter().find(|i| {
        i.class.opcode == Op::Variable
            && i.result_id.is_some_and(|id| {
                decorated(id, Decoration::DescriptorSet, set)
                    && decorated(id, Decoration::Binding, binding)
            })
    })
}

/// The type a variable's pointer type points to.
fn pointee(m: &Module, var: &Instruction) -> Option<u32> {
    let pointer = var.result_type?;
    m.types_global_values
        .iter()
        .find(|i| i.class.opcode == Op::TypePointer && i.result_id == Some(pointer))
        .and_then(|i| match i.operands.get(1) {
            Some(Operand::IdRef(t)) => Some(*t),
            _ => None,
        })
}

/// Whether operand `at` of `i` is the id `id`.
fn operand_is(i: &Instruction, at: usize, id: u32) -> bool {
    matches!(i.operands.get(at), Some(Operand::IdRef(x)) if *x == id)
}

/// The name of the resource at (set, binding): the variable's OpName, else (an anonymous block)
/// the OpMemberName of its block's first member.
fn resource_name(m: &Module, set: u32, binding: u32) -> Option<String> {
    let var = binding_variable(m, set, binding)?;
    let id = var.result_id?;
    let string = |i: &Instruction, at: usize| match i.operands.get(at) {
        Some(Operand::LiteralString(s)) if !s.is_empty() => Some(s.clone()),
        _ => None,
    };
    let named = m
        .debug_names
        .iter()
        .find(|i| i.class.opcode == Op::Name && operand_is(i, 0, id))
        .and_then(|i| string(i, 1));
    if named.is_some() {
        return named;
    }
    let block = pointee(m, var)?;
    m.debug_names
        .iter()
        .find(|i| {
            i.class.opcode == Op::MemberName
                && operand_is(i, 0, block)
                && matches!(i.operands.get(1), Some(Operand::LiteralBit32(0)))
        })
        .and_then(|i| string(i, 2))
}

/// Compares a declaration with the reflected interface; the first difference is the error.
pub fn check_bindings(
    shader: &str,
    iface: &ShaderInterface,
    declared: &[Binding],
    push_size: u32,
) -> Result<()> {
    let mismatch = |set, binding, detail: String| DeviceError::BindingMismatch {
        shader: shader.to_string(),
        set,
        binding,
        detail,
    };
    for (set, binding, kind, var) in &iface.bindings {
        if *set != 0 {
            return Err(mismatch(
                *set,
                *binding,
                format!("'{var}' uses set {set}; passes use set 0 only"),
            ));
        }
        let Some(decl) = declared.iter().find(|d| d.binding == *binding) else {
            return Err(mismatch(
                0,
                *binding,
                format!("shader declares '{var}' but the host declares nothing there"),
            ));
        };
        if *var != decl.name {
            return Err(mismatch(
                0,
                *binding,
                format!(
                    "the shader names it '{var}', the pass binds '{}' there",
                    decl.name
                ),
            ));
        }
        if *kind != Some(decl.kind) {
            return Err(mismatch(
                0,
                *binding,
                format!(
                    "shader has '{var}' as {kind:?}, host declares '{}' as {:?}",
                    decl.name, decl.kind
                ),
            ));
        }
    }
    for d in declared {
        if !iface.bindings.iter().any(|b| b.0 == 0 && b.1 == d.binding) {
            return Err(mismatch(
                0,
                d.binding,
                format!(
                    "host declares '{}' ({:?}) but the shader has no such binding",
                    d.name, d.kind
                ),
            ));
        }
    }
    if iface.push_constant_size > push_size {
        return Err(DeviceError::Shader {
            shader: shader.to_string(),
            detail: format!(
                "push constants: shader uses {} bytes, host provides {push_size}",
                iface.push_constant_size
            ),
        });
    }
    Ok(())
}

/// A compute pipeline with its (push-descriptor) set layout.
pub struct ComputePipeline {
    dev: Device,
    pub name: String,
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    set_layout: vk::DescriptorSetLayout,
    pub bindings: Vec<Binding>,
    /// Per binding of `bindings`: whether the shader may write it (not `readonly`).
    pub writes: Vec<bool>,
    pub push_size: u32,
    pub workgroup_size: (u32, u32, u32),
}

impl std::fmt::Debug for ComputePipeline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ComputePipeline")
            .field("name", &self.name)
            .finish()
    }
}

impl ComputePipeline {
    /// Creates the pipeline after checking `bindings` and `push_size` against the SPIR-V.
    pub fn new(
        dev: &Device,
        name: &str,
        spirv: &[u32],
        bindings: &[Binding],
        push_size: u32,
    ) -> Result<Self> {
        let iface = reflect(name, spirv)?;
        check_bindings(name, &iface, bindings, push_size)?;
        let max_push = dev.info().max_push_constants_size;
        if push_size > max_push {
            return Err(DeviceError::Shader {
                shader: name.into(),
                detail: format!(
                    "{push_size} bytes of push constants exceed the device's {max_push}"
                ),
            });
        }
        let raw_dev = dev.raw();
        let layout_bindings: Vec<_> = bindings
            .iter()
            .map(|b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b.binding)
                    .descriptor_type(b.kind.vk())
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        let set_info = vk::DescriptorSetLayoutCreateInfo::default()
            .flags(vk::DescriptorSetLayoutCreateFlags::PUSH_DESCRIPTOR_KHR)
            .bindings(&layout_bindings);
        // SAFETY: valid create infos throughout; objects are destroyed in Drop.
        unsafe {
            let set_layout = raw_dev
                .create_descriptor_set_layout(&set_info, None)
                .vk("vkCreateDescriptorSetLayout")?;
            let ranges = [vk::PushConstantRange::default()
                .stage_flags(vk::ShaderStageFlags::COMPUTE)
                .offset(0)
                .size(push_size.max(4))];
            let set_layouts = [set_layout];
            let layout_info = vk::PipelineLayoutCreateInfo::default()
                .set_layouts(&set_layouts)
                .push_constant_ranges(if push_size > 0 { &ranges } else { &[] });
            let layout = raw_dev
                .create_pipeline_layout(&layout_info, None)
                .vk("vkCreatePipelineLayout")?;
            let module_info = vk::ShaderModuleCreateInfo::default().code(spirv);
            let module = raw_dev
                .create_shader_module(&module_info, None)
                .vk("vkCreateShaderModule")?;
            let stage = vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::COMPUTE)
                .module(module)
                .name(c"main");
            let info = vk::ComputePipelineCreateInfo::default()
                .stage(stage)
                .layout(layout);
            let created =
                raw_dev.create_compute_pipelines(vk::PipelineCache::null(), &[info], None);
            raw_dev.destroy_shader_module(module, None);
            let raw = created.map_err(|(_, r)| DeviceError::Vulkan {
                what: format!("vkCreateComputePipelines({name})"),
                result: r,
            })?[0];
            dev.set_name(raw, name);
            dev.set_name(layout, &format!("{name}.layout"));
            dev.set_name(set_layout, &format!("{name}.set0"));
            Ok(Self {
                dev: dev.clone(),
                name: name.to_string(),
                raw,
                layout,
                set_layout,
                bindings: bindings.to_vec(),
                writes: bindings
                    .iter()
                    .map(|b| !iface.read_only.contains(&b.binding))
                    .collect(),
                push_size,
                workgroup_size: iface.workgroup_size,
            })
        }
    }
}

impl Drop for ComputePipeline {
    fn drop(&mut self) {
        // SAFETY: no command buffer using the pipeline is pending (callers wait).
        unsafe {
            let d = self.dev.raw();
            d.destroy_pipeline(self.raw, None);
            d.destroy_pipeline_layout(self.layout, None);
            d.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}

/// Pipelines of one pass's shader variants, each created on first use (lavapipe compiles a
/// pipeline on its first dispatch, so variants a run never needs cost nothing).
#[derive(Debug)]
pub struct PipelineCache<K> {
    pipelines: Vec<(K, ComputePipeline)>,
}

impl<K> Default for PipelineCache<K> {
    fn default() -> Self {
        Self {
            pipelines: Vec::new(),
        }
    }
}

impl<K: PartialEq + Copy> PipelineCache<K> {
    /// The pipeline of `key`, made by `create` the first time it is asked for.
    pub fn get_or_create<E>(
        &mut self,
        key: K,
        create: impl FnOnce(K) -> std::result::Result<ComputePipeline, E>,
    ) -> std::result::Result<&ComputePipeline, E> {
        let i = match self.pipelines.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                self.pipelines.push((key, create(key)?));
                self.pipelines.len() - 1
            }
        };
        Ok(&self.pipelines[i].1)
    }
}
