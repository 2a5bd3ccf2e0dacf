use super::*;
use crate::method::{Grouping, Permutation, Points};
use blueshift_layout::params::MASK_DIMS;

pub(super) const VIEWS: [ViewState; 2] = [ViewState::Still, ViewState::Moving];

pub(super) fn config(method: Method, block: Option<u32>) -> RenderConfig {
    RenderConfig {
        method,
        block: block.filter(|_| method.fixed_block().is_none()),
        ..RenderConfig::new(8, 8)
    }
}

/// The recipe of method `m` (a preset or a comparison method) at `bounces`.
pub(super) fn of(m: &str, view: ViewState, bounces: u32, textured: bool) -> FrameRecipe {
    let method = Method::parse_comparison(m).expect(m);
    let cfg = RenderConfig {
        bounces,
        ..config(method, None)
    };
    recipe(&cfg, view, textured)
}

/// Every named method and every spelled-out form the passes can run.
pub(super) fn every_method() -> Vec<(String, Method)> {
    let named = Method::named().map(|(n, m)| (n.to_string(), m));
    let forms = Method::all_permutations()
        .into_iter()
        .map(|m| (m.name(), m));
    named.chain(forms).collect()
}

/// Every valid form x {still, moving} (and the block sizes that change the variant) decodes
/// to a recipe whose passes come in dependency order, whose sort variant is a compiled
/// shader with exactly the inputs the passes make, and whose view-dependent rules are the
/// documented ones; the fields that do not depend on the view are equal in both recipes.
#[test]
fn every_form_decodes_to_a_consistent_recipe_in_both_view_states() {
    let forms = Method::all_permutations();
    for (name, m) in Method::PRESETS {
        assert!(!m.sorts() || forms.contains(&m), "{name} is a valid form");
    }
    let compiled = SortVariant::all();
    let mut checked = 0;
    for (name, m) in every_method() {
        for block in [None, Some(2), Some(8)] {
            let cfg = config(m, block);
            let [still, moving] = VIEWS.map(|v| recipe(&cfg, v, true));
            let same = |r: &FrameRecipe| {
                (
                    r.reproject,
                    r.surfaces,
                    r.cycle_history,
                    r.swap_seeds,
                    r.adapts_pairs,
                )
            };
            assert_eq!(same(&still), same(&moving), "{name}");
            for (view, r) in VIEWS.iter().zip([&still, &moving]) {
                let at = |p: fn(&Pass) -> bool| r.passes.iter().position(p);
                let trace = at(|p| *p == Pass::Trace).expect("a trace pass");
                assert_eq!(r.passes.first(), Some(&Pass::ClearStatus), "{name}");
                assert_eq!(r.passes.last(), Some(&Pass::Readback), "{name}");
                assert!(Some(trace) < at(|p| *p == Pass::Accumulate), "{name}");
                let Some(s) = r.sort else {
                    let reads = !r.trace.no_seeds;
                    assert!(
                        !(m.sorts() && reads),
                        "{name}: reads seeds it does not sort"
                    );
                    assert!(at(|p| *p == Pass::Sort).is_none(), "{name}");
                    continue;
                };
                let p: Permutation = m.permutation().expect("a sorting method");
                let v = s.variant;
                assert!(
                    compiled.contains(&v),
                    "{name} {view:?}: {} not compiled",
                    v.shader()
                );
                let sort = at(|p| *p == Pass::Sort).expect("a sort pass");
                assert!(trace < sort, "{name}");
                // The adaptive pairs: counts cleared before the sort, folded in after it.
                let clear = at(|p| *p == Pass::ClearSortStats);
                let gate = at(|p| *p == Pass::PairsGate);
                assert_eq!(clear.is_some(), m.adapts_pairs(), "{name}");
                assert_eq!(gate.is_some(), m.adapts_pairs(), "{name}");
                assert!(clear.is_none_or(|c| c < sort), "{name}");
                assert!(gate.is_none_or(|g| g == sort + 1), "{name}");
                assert_eq!(s.count_skew, m.adapts_pairs(), "{name}");
                assert_eq!(v.skew && v.pairs, m.adapts_pairs(), "{name}");
                let classify = at(|p| matches!(p, Pass::Classify { .. }));
                let per_block = at(|p| *p == Pass::ClassesPerBlock);
                assert_eq!(classify.is_some(), v.classes, "{name} {view:?}");
                assert!(classify.or(per_block).is_none_or(|c| c < sort), "{name}");
                assert!(!v.classes || r.surfaces, "{name}");
                // The view-dependent rules, one by one.
                let moves = *view == ViewState::Moving;
                let blocks = moves && p.grouping == Grouping::StillSurfaces;
                assert_eq!(per_block.is_some(), blocks, "{name} {view:?}");
                assert_eq!(v.classes, m.edge_aware() && !blocks, "{name} {view:?}");
                let keys = v.cycle && moves && p.without != crate::Without::SampleKeys;
                assert_eq!(v.sample_keys, keys, "{name} {view:?}");
                assert_eq!(s.sample_keys, v.sample_keys, "{name}");
                assert_eq!(v.retarget, r.swap_seeds, "{name}");
                assert_eq!(s.block, cfg.effective_block(), "{name}");
                assert_eq!(v.large, SortVariant::large_for(s.block), "{name}");
                checked += 1;
            }
        }
    }
    assert!(checked > 2 * 3 * 100, "{checked} recipes checked");
}

/// Every method whose samples are not a progressive sequence is salted per frame (else its
/// deeper dimensions would repeat every frame); `mask-rot`'s Sobol runs on instead, and a
/// sampler given by hand puts the rotating mask back on white noise.
#[test]
fn the_rotating_masks_run_a_sequence_behind_them() {
    let flags = |method: Method, sampler: Option<Sampler>| {
        let c = RenderConfig {
            method,
            sampler,
            ..RenderConfig::new(8, 8)
        };
        let f = method_flags(&c);
        (
            f & TRACE_FLAG_SALT_FRAME != 0,
            f & TRACE_FLAG_ADVANCE_INDEX != 0,
        )
    };
    for m in [Method::MaskRot, Method::MaskRotFollow] {
        assert_eq!(m.default_sampler(), Sampler::Sobol, "{m}");
        assert_eq!(flags(m, None), (false, true), "{m}");
        assert_eq!(flags(m, Some(Sampler::White)), (true, false), "{m}");
    }
    for m in [Method::White, Method::MaskR2, Method::Stbn, Method::Fast] {
        assert_eq!(flags(m, None), (true, false), "{m}");
        assert_eq!(flags(m, Some(Sampler::Sobol)), (true, false), "{m}");
    }
    assert_eq!(flags(Method::Sobol, None), (false, true));
}

/// The trace pass reads anchors only in its mask variants (`#if TRACE_MASK`), so every
/// anchored method must run one.
#[test]
fn anchored_methods_have_a_mask_mode() {
    let anchored: Vec<_> = every_method()
        .into_iter()
        .filter(|(_, m)| m.anchors_mask())
        .collect();
    assert!(!anchored.is_empty());
    for (name, m) in anchored {
        for view in VIEWS {
            let r = recipe(&config(m, None), view, true);
            assert_ne!(r.trace.mask_mode, MASK_MODE_NONE, "{name}");
            assert_ne!(r.trace.flags & TRACE_FLAG_MASK_ANCHORED, 0, "{name}");
        }
    }
}

/// A method whose seeds leave some dimensions to the mask runs a mask variant in every
/// state, within the dimensions the mask modes drive (the flag's bits above them would be
/// ignored by the shader, and a method would silently lose them).
#[test]
fn mask_dimensions_have_a_mask_mode() {
    let mut some = 0;
    for (name, m) in every_method() {
        for view in VIEWS {
            let moving = view == ViewState::Moving;
            let r = recipe(&config(m, None), view, true);
            let dims = m.mask_dims(moving);
            assert_eq!(
                r.trace.flags >> TRACE_FLAG_MASK_DIMS_SHIFT & dims,
                dims,
                "{name}"
            );
            if dims != 0 {
                some += 1;
                assert_ne!(r.trace.mask_mode, MASK_MODE_NONE, "{name}");
                assert_eq!(dims >> MASK_DIMS, 0, "{name}");
                assert_eq!(dims & 3, 3, "{name}: the jitter comes first");
            }
            // Textured pixels' jitter is chosen only where the mask drives the jitter.
            assert_eq!(m.jitter_flags(moving) != 0, dims & 3 != 0, "{name}");
        }
    }
    assert!(some > 0, "no method leaves dimensions to the mask");
}

/// Each `without=` ablation switches off its one rule in its one view state, and nothing else:
/// the other view state's recipe is the default's.
#[test]
fn each_ablation_drops_one_rule_in_one_view_state() {
    use blueshift_layout::params::{TRACE_FLAG_SEED_JITTER_ON_TEXTURES, TRACE_FLAG_SOBOL_JITTER};
    let of = |m: &str, view| recipe(&config(m.parse().expect(m), None), view, true);
    let still = of("sort-cycle", ViewState::Still);
    let moving = of("sort-cycle", ViewState::Moving);
    let sort = |r: &FrameRecipe| r.sort.expect("sort-cycle sorts");
    // The rules are on in the default: each ablation below would compare against nothing.
    assert!(sort(&moving).sample_keys);
    for (r, flag) in [
        (&still, TRACE_FLAG_SOBOL_JITTER),
        (&moving, TRACE_FLAG_SEED_JITTER_ON_TEXTURES),
    ] {
        assert_eq!(r.trace.flags & flag, flag);
    }
    // (ablation, view state it changes, whether the sort or only the trace flag `bit` changes)
    let cases = [
        ("sample-keys", ViewState::Moving, 0),
        (
            "texture-jitter",
            ViewState::Moving,
            TRACE_FLAG_SEED_JITTER_ON_TEXTURES,
        ),
        ("sobol-jitter", ViewState::Still, TRACE_FLAG_SOBOL_JITTER),
    ];
    for (rule, view, bit) in cases {
        let name = format!("sort-cycle:without={rule}");
        let (other, same, changed) = match view {
            ViewState::Still => (ViewState::Moving, &moving, &still),
            ViewState::Moving => (ViewState::Still, &still, &moving),
        };
        assert_eq!(
            &of(&name, other),
            same,
            "{name}: changed the other view state"
        );
        let r = of(&name, view);
        assert_ne!(&r, changed, "{name}: changed nothing");
        let mut expected = Some(sort(changed));
        let mut flags = changed.trace.flags & !bit;
        if rule == "sample-keys" {
            expected = expected.map(|mut s| {
                s.sample_keys = false;
                s.variant.sample_keys = false;
                s
            });
        } else if rule == "texture-jitter" {
            // No pixel takes the seeds' jitter then: the moving frame reads no seed at all
            // (`a_moving_frame_at_depth_reads_no_seed`).
            expected = None;
            flags |= TRACE_FLAG_SALT_FRAME;
            assert_eq!(r.trace.mask, MaskSource::Motion, "{name}");
        }
        assert_eq!(r.sort, expected, "{name}: sort plan");
        assert_eq!(r.trace.flags, flags, "{name}: trace flags");
    }
}

/// A frame sorts unless its trace reads no seed: a moving view of a form that takes the first
/// vertex from the mask where no pixel takes the seeds' jitter, in direct light or at depth
/// (`white-depth`; it keeps the trace plan of the frame that sorts but for the sampler, the
/// frame salt and the mask it reads), and a still view of the point cycle with that mask in
/// direct light in a scene without textures (it takes the volume instead, tested below). Such
/// a frame traces with the `white` sampler salted by the frame.
#[test]
fn a_frame_skips_the_sort_only_where_the_trace_reads_no_seed() {
    use crate::Without;
    let mut skipped = 0;
    for (name, m) in every_method() {
        for bounces in [0, 1, 2, 8] {
            for textured in [false, true] {
                for view in VIEWS {
                    let cfg = RenderConfig {
                        bounces,
                        ..config(m, None)
                    };
                    let r = recipe(&cfg, view, textured);
                    let moving = view == ViewState::Moving;
                    let vertex = m
                        .permutation()
                        .is_some_and(|p| p.mask == crate::MaskDims::Vertex);
                    let seed_jitter = textured && m.keeps(Without::TextureJitter);
                    let skips_moving = m.sorts()
                        && moving
                        && vertex
                        && (bounces <= 1 || m.keeps(Without::WhiteDepth))
                        && !seed_jitter;
                    let cycle = m.permutation().is_some_and(|p| p.points == Points::Cycle);
                    let skips_still = cycle
                        && vertex
                        && !moving
                        && bounces <= 1
                        && !textured
                        && m.keeps(Without::StillVolume);
                    let skips = skips_moving || skips_still;
                    assert_eq!(r.sort.is_none(), !m.sorts() || skips, "{name} b{bounces}");
                    assert_eq!(r.trace.no_seeds, skips, "{name} b{bounces}: white sampler");
                    if !skips {
                        continue;
                    }
                    skipped += 1;
                    let passes = [
                        Pass::ClearStatus,
                        Pass::Trace,
                        Pass::Accumulate,
                        Pass::Tonemap,
                        Pass::Readback,
                    ];
                    assert_eq!(r.passes, passes, "{name}: only the trace and the image");
                    let salt = TRACE_FLAG_SALT_FRAME;
                    assert_eq!(r.trace.flags & salt, salt * u32::from(skips_moving));
                    // The frame that sorts: at depth, with the rule switched off.
                    let Some(p) = m.permutation().filter(|p| p.without == Without::Nothing) else {
                        continue;
                    };
                    let ablation = Method::Permute(Permutation {
                        without: Without::WhiteDepth,
                        ..p
                    });
                    let sorting = recipe(
                        &RenderConfig {
                            bounces: 2,
                            ..config(ablation, None)
                        },
                        view,
                        textured,
                    );
                    assert!(
                        sorting.sort.is_some(),
                        "{name}: the ablation sorts at depth"
                    );
                    let own_sampler = TracePlan {
                        no_seeds: false,
                        flags: r.trace.flags & !salt,
                        mask_mode: sorting.trace.mask_mode,
                        mask: sorting.trace.mask,
                        ..r.trace
                    };
                    assert_eq!(
                        own_sampler == sorting.trace,
                        skips_moving,
                        "{name}: the trace"
                    );
                }
            }
        }
    }
    assert!(
        skipped > 0,
        "the default skips it in direct light, moving, untextured"
    );
}
