//! Shader variants: one GLSL body compiled several times with different `#define`s.
//!
//! llvmpipe runs both sides of every branch, so code a method or scene never uses is compiled
//! out instead of skipped at run time. This list is the single source of the variants: the
//! shaders crate's build script compiles each one, and the passes name the one they need
//! through the same types, so the two cannot drift apart.
use blueshift_sampling::Sampler;

/// One compiled variant: `body` (a path under `shaders/`) with `defines` set before it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ShaderVariant {
    /// The name passes look the SPIR-V up by, e.g. `"trace/trace_sobol_mask"`.
    pub name: String,
    pub body: &'static str,
    pub defines: Vec<(&'static str, String)>,
}

/// A path-tracer pipeline (`trace/trace_body.glsl`). All variants share one binding table and
/// push-constant block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TraceVariant {
    pub sampler: Sampler,
    /// Blue-noise mask modes (`TraceParams::mask_mode != MASK_MODE_NONE`).
    pub mask: bool,
    /// Material textures (some material has one).
    pub textures: bool,
    /// The Lambert-only BRDF (every material has metallic = specular = 0).
    pub lambert: bool,
    /// Punctual lights and environment maps (the scene has some).
    pub lights: bool,
    /// Count loop iterations (`--loop-stats`): every other choice is made at run time then, so
    /// only the sampler's key table (HBO+19 or not) selects among these.
    pub loop_stats: bool,
}

impl TraceVariant {
    /// The shader name: `trace/trace_<sampler>[_mask][_tex][_lambert][_lights]`, or
    /// `trace/trace_loop_stats[_hbo19]`.
    pub fn shader(self) -> String {
        let flag = |on: bool, suffix: &'static str| if on { suffix } else { "" };
        if self.loop_stats {
            let hbo19 = self.sampler == Sampler::Hbo19;
            return format!("trace/trace_loop_stats{}", flag(hbo19, "_hbo19"));
        }
        format!(
            "trace/trace_{}{}{}{}{}",
            self.sampler.name(),
            flag(self.mask, "_mask"),
            flag(self.textures, "_tex"),
            flag(self.lambert, "_lambert"),
            flag(self.lights, "_lights"),
        )
    }

    fn variant(self) -> ShaderVariant {
        let hbo19 = self.sampler == Sampler::Hbo19;
        let bit = |on: bool| u32::from(on).to_string();
        let kind = if self.loop_stats && !hbo19 {
            "P.sampler_kind".to_string() // the run-time choice: one shader counts them all
        } else {
            format!("SAMPLER_{}", self.sampler.name().to_uppercase())
        };
        let mut defines = if self.loop_stats {
            vec![
                ("TRACE_SAMPLER_KIND", kind),
                ("TRACE_MASK", bit(true)),
                ("TRACE_TEXTURES", bit(true)),
                ("TRACE_LIGHTS", bit(true)),
                ("TRACE_LOOP_STATS", bit(true)),
            ]
        } else {
            vec![
                ("TRACE_SAMPLER_KIND", kind),
                ("TRACE_MASK", bit(self.mask)),
                ("TRACE_TEXTURES", bit(self.textures)),
                ("TRACE_LAMBERT", bit(self.lambert)),
                ("TRACE_LIGHTS", bit(self.lights)),
            ]
        };
        defines.push(("TRACE_HBO19", bit(hbo19)));
        ShaderVariant {
            name: self.shader(),
            body: "trace/trace_body.glsl",
            defines,
        }
    }

    /// Every distinct variant: the canonical form of every combination of choices.
    pub fn all() -> Vec<TraceVariant> {
        let mut out = Vec::new();
        for sampler in Sampler::ALL {
            for bits in 0..32u32 {
                let v = TraceVariant {
                    sampler,
                    mask: bits & 1 != 0,
                    textures: bits & 2 != 0,
                    lambert: bits & 4 != 0,
                    lights: bits & 16 != 0,
                    loop_stats: bits & 8 != 0,
                }
                .canonical();
                if !out.contains(&v) {
                    out.push(v);
                }
            }
        }
        out
    }

    /// The variant that serves these choices (loop statistics ignore all but HBO+19 or not).
    pub fn canonical(self) -> TraceVariant {
        if !self.loop_stats {
            return self;
        }
        let hbo19 = self.sampler == Sampler::Hbo19;
        TraceVariant {
            sampler: if hbo19 {
                Sampler::Hbo19
            } else {
                Sampler::White
            },
            mask: true,
            textures: true,
            lambert: false,
            lights: true,
            loop_stats: true,
        }
    }
}

/// A sorting-pass pipeline (`permute/sort_seeds.glsl`): each extension of the paper's
/// sorting adds its bindings and code only where a method asks for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SortVariant {
    /// Rank within surface classes (`classes` binding); otherwise one class per block.
    pub classes: bool,
    /// Rank keys minus history means (`history` binding); otherwise raw keys.
    pub history: bool,
    /// Antithetic pairs (`SortParams::pairs` chooses which classes at run time).
    pub pairs: bool,
    /// Count skewed classes (`stats` binding, `SortParams::count_skew`).
    pub skew: bool,
    /// Blocks up to 8x8 (64 slots per block); otherwise up to 4x4 (16 slots), whose sorting
    /// networks are a tenth of the size.
    pub large: bool,
    /// Retarget on the way out (`seeds_out` binding, mask texels packed with D): the
    /// retargeting pass fused into the sort, saving a pass over every seed.
    pub retarget: bool,
    /// Run sort-cycle's point cycle on the way in (`cycle_history` and `accum` bindings,
    /// `SortParams::cycle_*`): the point cycle fused into the sort.
    pub cycle: bool,
    /// With `cycle`: the seeds rank by their next light sample
    /// (`SortParams::cycle_sample_keys`, a moving view). A shader of its own rather than a
    /// run-time branch: llvmpipe runs both sides of a uniform branch, so a still view would
    /// pay for keys it never uses.
    pub sample_keys: bool,
}

impl SortVariant {
    /// The paper's sorting: none of the extensions.
    pub const PAPER: SortVariant = SortVariant {
        classes: false,
        history: false,
        pairs: false,
        skew: false,
        large: false,
        retarget: false,
        cycle: false,
        sample_keys: false,
    };

    /// `permute/sort_seeds` for the paper (blocks up to 4x4), else with a suffix per
    /// extension, e.g. `permute/sort_seeds_classes_history_pairs_64`.
    pub fn shader(self) -> String {
        let flag = |on: bool, suffix: &'static str| if on { suffix } else { "" };
        format!(
            "permute/sort_seeds{}{}{}{}{}{}{}{}",
            flag(self.classes, "_classes"),
            flag(self.history, "_history"),
            flag(self.pairs, "_pairs"),
            flag(self.skew, "_skew"),
            flag(self.large, "_64"),
            flag(self.retarget, "_retarget"),
            flag(self.cycle, "_cycle"),
            flag(self.sample_keys, "_samplekeys"),
        )
    }

    /// Whether blocks of edge `block` need the 64-slot variant.
    pub fn large_for(block: u32) -> bool {
        block > 4
    }

    fn variant(self) -> ShaderVariant {
        let bit = |on: bool| u32::from(on).to_string();
        ShaderVariant {
            name: self.shader(),
            body: "permute/sort_seeds.glsl",
            defines: vec![
                ("SORT_CLASSES", bit(self.classes)),
                ("SORT_HISTORY", bit(self.history)),
                ("SORT_PAIRS", bit(self.pairs)),
                ("SORT_SKEW", bit(self.skew)),
                (
                    "SORT_SLOTS",
                    if self.large { "64" } else { "16" }.to_string(),
                ),
                ("SORT_RETARGET", bit(self.retarget)),
                ("SORT_CYCLE", bit(self.cycle)),
                ("SORT_SAMPLE_KEYS", bit(self.sample_keys)),
            ],
        }
    }

    /// Every combination a method can ask for: 56 (retargeting and the point cycle never
    /// meet pairs, skew counts or each other: pairs belong to the moving grid; sample keys
    /// belong to the point cycle).
    pub fn all() -> Vec<SortVariant> {
        (0..256u32)
            .map(|b| SortVariant {
                classes: b & 1 != 0,
                history: b & 2 != 0,
                pairs: b & 4 != 0,
                skew: b & 8 != 0,
                large: b & 16 != 0,
                retarget: b & 32 != 0,
                cycle: b & 64 != 0,
                sample_keys: b & 128 != 0,
            })
            .filter(|v| !((v.retarget || v.cycle) && (v.pairs || v.skew)))
            .filter(|v| !(v.retarget && v.cycle))
            .filter(|v| v.cycle || !v.sample_keys)
            .collect()
    }
}

/// Every generated shader variant, for the shaders crate's build script.
pub fn shader_variants() -> Vec<ShaderVariant> {
    let trace = TraceVariant::all().into_iter().map(TraceVariant::variant);
    let sort = SortVariant::all().into_iter().map(SortVariant::variant);
    trace.chain(sort).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variant_names_are_unique() {
        let v = shader_variants();
        let mut names: Vec<&str> = v.iter().map(|s| s.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), v.len());
    }

    #[test]
    fn variants_are_the_specialised_ones_and_two_counting_shaders() {
        let all = TraceVariant::all();
        // Mask, textures, Lambert and lights on or off per sampler, plus the counting shaders.
        assert_eq!(all.len(), Sampler::ALL.len() * 16 + 2);
        let counting: Vec<_> = all.iter().filter(|v| v.loop_stats).collect();
        assert_eq!(counting.len(), 2);
        assert!(counting.iter().all(|v| v.canonical() == **v));
        assert_eq!(SortVariant::PAPER.shader(), "permute/sort_seeds");
        // Sample keys specialise only the point cycle's shaders: 48 sorting shaders without
        // them, and the 8 of the point cycle with them.
        let sorts = SortVariant::all();
        let keys = sorts.iter().filter(|v| v.sample_keys).count();
        assert!(sorts.iter().all(|v| v.cycle || !v.sample_keys));
        assert_eq!((sorts.len(), keys), (56, 8));
        assert_eq!(shader_variants().len(), all.len() + sorts.len());
    }
}
