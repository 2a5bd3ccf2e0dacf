//! The spelled-out form of a permutation method, for experiments: `PRESET:field=value,...`,
//! e.g. `sort-retarget:transport=none` (the paper's sort alone). Each field overrides the
//! preset's.
use crate::method::{
    Grouping, Key, MaskDims, Method, Motion, Pairs, Permutation, Points, Target, Transport, Without,
};

/// (field, values in order of their enum) of every field, for parsing and help.
const FIELDS: [(&str, &[&str]); 9] = [
    ("key", &["raw", "demod", "history"]),
    ("grouping", &["blocks", "surfaces", "still-surfaces"]),
    ("transport", &["none", "retarget", "grid"]),
    ("motion", &["none", "reproject"]),
    ("pairs", &["off", "thin", "adaptive", "all"]),
    ("points", &["fixed", "cycle"]),
    ("mask", &["none", "jitter", "motion", "vertex"]),
    ("target", &["screen", "follow"]),
    (
        "without",
        &[
            "none",
            "sample-keys",
            "texture-jitter",
            "sobol-jitter",
            "still-volume",
            "motion-volume",
            "white-depth",
        ],
    ),
];

/// (field, value) of each field of `p`, in the order of [`FIELDS`].
pub(crate) fn fields(p: &Permutation) -> [(&'static str, &'static str); 9] {
    let idx = [
        p.key as usize,
        p.grouping as usize,
        p.transport as usize,
        p.motion as usize,
        p.pairs as usize,
        p.points as usize,
        p.mask as usize,
        p.target as usize,
        p.without as usize,
    ];
    std::array::from_fn(|i| (FIELDS[i].0, FIELDS[i].1[idx[i]]))
}

fn set(p: &mut Permutation, field: &str, value: &str) -> Result<(), String> {
    let Some((_, values)) = FIELDS.iter().find(|(f, _)| *f == field) else {
        let known: Vec<&str> = FIELDS.iter().map(|(f, _)| *f).collect();
        return Err(format!(
            "unknown field '{field}' (fields: {})",
            known.join(", ")
        ));
    };
    let Some(i) = values.iter().position(|v| *v == value) else {
        return Err(format!(
            "unknown {field} '{value}' ({field}: {})",
            values.join(", ")
        ));
    };
    match field {
        "key" => p.key = [Key::Raw, Key::Demodulated, Key::History][i],
        "grouping" => {
            p.grouping = [
                Grouping::Blocks,
                Grouping::Surfaces,
                Grouping::StillSurfaces,
            ][i]
        }
        "transport" => p.transport = [Transport::None, Transport::Retarget, Transport::Grid][i],
        "motion" => p.motion = [Motion::None, Motion::Reproject][i],
        "pairs" => p.pairs = [Pairs::Off, Pairs::Thin, Pairs::Adaptive, Pairs::All][i],
        "points" => p.points = [Points::Fixed, Points::Cycle][i],
        "mask" => {
            p.mask = [
                MaskDims::None,
                MaskDims::Jitter,
                MaskDims::Motion,
                MaskDims::Vertex,
            ][i]
        }
        "target" => p.target = [Target::Screen, Target::Follow][i],
        _ => {
            p.without = [
                Without::Nothing,
                Without::SampleKeys,
                Without::TextureJitter,
                Without::SobolJitter,
                Without::StillVolume,
                Without::MotionVolume,
                Without::WhiteDepth,
            ][i]
        }
    }
    Ok(())
}

/// Combinations the passes cannot run, with the reason.
pub(crate) fn check(p: &Permutation) -> Result<(), String> {
    if p.key == Key::History && p.motion != Motion::Reproject {
        return Err("key=history needs motion=reproject (histories follow their surface)".into());
    }
    if p.pairs != Pairs::Off && p.transport != Transport::Grid {
        return Err(format!(
            "pairs={} needs transport=grid (pairs replace the next frame's mask there)",
            fields(p)[4].1
        ));
    }
    if p.grouping == Grouping::StillSurfaces && p.motion != Motion::None {
        return Err(
            "grouping=still-surfaces needs motion=none (a reprojecting method traces the \
             G-buffer every frame anyway: use grouping=surfaces)"
                .into(),
        );
    }
    if p.points == Points::Cycle && (p.transport != Transport::None || p.motion != Motion::None) {
        return Err(
            "points=cycle needs transport=none and motion=none (a seed's history slots stay \
             valid only while it stays in its block)"
                .into(),
        );
    }
    let needs = match p.without {
        Without::Nothing => None,
        Without::SampleKeys => (p.points != Points::Cycle).then_some("points=cycle"),
        Without::TextureJitter | Without::SobolJitter => (p.mask == MaskDims::None)
            .then_some("a mask that drives the jitter (mask other than none)"),
        Without::StillVolume => (p.points != Points::Cycle || p.mask != MaskDims::Vertex)
            .then_some("points=cycle and mask=vertex"),
        Without::MotionVolume => (p.points != Points::Cycle || p.mask == MaskDims::None)
            .then_some("points=cycle and a mask (mask other than none)"),
        Without::WhiteDepth => (p.mask != MaskDims::Vertex).then_some("mask=vertex"),
    };
    if let Some(needs) = needs {
        return Err(format!(
            "without={} needs {needs} (the rule it switches off exists only there)",
            fields(p)[8].1
        ));
    }
    if p.target == Target::Follow && p.points != Points::Cycle {
        return Err(
            "target=follow needs points=cycle (only the point cycle sorts against the \
             spatio-temporal mask it moves)"
                .into(),
        );
    }
    Ok(())
}

/// Every permutation the passes can run (every combination of field values that
/// [`check`] accepts), in the order of [`FIELDS`]' values.
pub fn all_valid() -> Vec<Permutation> {
    let sizes = FIELDS.map(|(_, values)| values.len());
    let count: usize = sizes.iter().product();
    (0..count)
        .filter_map(|mut i| {
            let mut p = crate::Method::SORT_RETARGET.permutation()?;
            for ((field, values), n) in FIELDS.iter().zip(sizes) {
                set(&mut p, field, values[i % n]).ok()?;
                i /= n;
            }
            check(&p).ok().map(|()| p)
        })
        .collect()
}

/// Every field with its values, `key=raw|demod|history, grouping=...`.
pub(crate) fn syntax() -> String {
    FIELDS
        .iter()
        .map(|(f, v)| format!("{f}={}", v.join("|")))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A preset name or a spelled-out permutation method.
pub(crate) fn parse(s: &str) -> Result<Method, String> {
    let unknown = || {
        format!(
            "unknown method '{s}' (presets: {}; or PRESET:field=value,... with {})",
            Method::names(),
            syntax()
        )
    };
    let (base, spec) = s.split_once(':').unwrap_or((s, ""));
    let preset = Method::PRESETS
        .iter()
        .find(|(n, _)| *n == base)
        .map(|(_, m)| *m)
        .ok_or_else(unknown)?;
    if spec.is_empty() && !s.contains(':') {
        return Ok(preset);
    }
    let Some(mut p) = preset.permutation() else {
        return Err(format!(
            "'{base}' is not a permutation method; only the sort presets take fields"
        ));
    };
    for item in spec.split(',') {
        let Some((field, value)) = item.split_once('=') else {
            return Err(format!(
                "in method '{s}': expected field=value, got '{item}'"
            ));
        };
        set(&mut p, field.trim(), value.trim()).map_err(|e| format!("in method '{s}': {e}"))?;
    }
    check(&p).map_err(|e| format!("in method '{s}': {e}"))?;
    Ok(Method::Permute(p))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comparisons_parse_where_compared_only() {
        for (name, m) in Method::COMPARISONS {
            assert_eq!(Method::parse_comparison(name), Ok(m));
            assert!(name.parse::<Method>().is_err(), "{name}");
        }
        let e = Method::parse_comparison("mask-rot-fast").expect_err("unknown");
        assert!(e.contains("for comparisons also: hbo19"), "{e}");
        for (name, m) in Method::PRESETS {
            assert_eq!(Method::parse_comparison(name), Ok(m));
        }
    }

    #[test]
    fn presets_round_trip_by_name() {
        for (name, m) in Method::named() {
            assert_eq!(m.name(), name);
            assert_eq!(Method::parse_comparison(name), Ok(m));
            if let Some(p) = m.permutation() {
                assert_eq!(check(&p), Ok(()), "{name}");
            }
        }
    }

    #[test]
    fn spelled_out_forms_name_presets_and_experiments() {
        let history: Method = "sort-grid-adaptive:pairs=thin".parse().expect("valid");
        assert_eq!(history, Method::SORT_GRID_HISTORY);
        assert_eq!(history.name(), "sort-grid-adaptive:pairs=thin");
        let sort: Method = "sort-retarget:transport=none".parse().expect("valid");
        assert_eq!(
            (sort, sort.name().as_str()),
            (Method::SORT, "sort-retarget:transport=none")
        );
        let m: Method = "sort-retarget:transport=grid,key=demod"
            .parse()
            .expect("valid");
        assert_eq!(m.name(), "sort-retarget:key=demod,transport=grid");
        // Named after the nearest preset, whichever preset it was written from.
        let near: Method = "sort-retarget:transport=none,points=cycle,grouping=surfaces,\
                            mask=vertex,target=follow"
            .parse()
            .expect("valid");
        assert_eq!(near.name(), "sort-cycle:grouping=surfaces");
        assert_eq!(m.name().parse::<Method>(), Ok(m));
        assert!(m.shifts_grid() && m.demodulates() && !m.history_keys());
        let c: Method = "sort-retarget:transport=none,points=cycle,grouping=still-surfaces,\
                         mask=vertex,target=follow"
            .parse()
            .expect("valid");
        assert_eq!(c, Method::SORT_CYCLE);
        assert!(c.cycles_points() && c.advances_index() && c.block(Some(4)) == crate::GRID_BLOCK);
        assert_eq!(c.default_sampler(), blueshift_sampling::Sampler::BlockNet);
        let plain: Method = "sort-cycle:mask=none".parse().expect("valid");
        assert_eq!(plain.name(), "sort-cycle:mask=none");
        assert_eq!(plain.name().parse::<Method>(), Ok(plain));
        assert_eq!((plain.mask_dims(false), plain.mask_dims(true)), (0, 0));
        // Still, the mask takes the jitter only; moving, every dimension up to the second
        // vertex.
        let (still, moving) = (c.mask_dims(false), c.mask_dims(true));
        assert_eq!(
            still,
            "sort-cycle:mask=jitter"
                .parse::<Method>()
                .unwrap()
                .mask_dims(true)
        );
        let all = (1 << blueshift_layout::params::MASK_DIMS) - 1;
        assert_eq!(moving, all);
        // `mask=motion`: the same while still; moving, the first vertex's BSDF sample (four
        // dimensions) but not its light sample.
        let motion: Method = "sort-cycle:mask=motion".parse().expect("valid");
        assert_eq!(motion.name(), "sort-cycle:mask=motion");
        assert_eq!(motion.name().parse::<Method>(), Ok(motion));
        assert_eq!(motion.mask_dims(false), still);
        assert_eq!((motion.mask_dims(true) & !still).count_ones(), 4);
        // The ablations of the view-state rules are named after the default, and only where
        // their rule exists.
        for rule in [
            "sample-keys",
            "texture-jitter",
            "sobol-jitter",
            "still-volume",
            "motion-volume",
            "white-depth",
        ] {
            let form = format!("sort-cycle:without={rule}");
            let a: Method = form.parse().expect("valid");
            assert_eq!(a.name(), form);
            assert_ne!(a, c);
        }
        for bad in [
            "sort-cycle:mask=motion,without=still-volume",
            "sort-cycle:mask=none,without=sobol-jitter",
            "sort-retarget:without=sample-keys",
        ] {
            let e = bad.parse::<Method>().expect_err(bad);
            assert!(e.contains("without=") && e.contains("needs"), "{bad}: {e}");
        }
        let screen: Method = "sort-cycle:target=screen".parse().expect("valid");
        assert_eq!(screen.name(), "sort-cycle:target=screen");
        assert!(c.follows_target() && !screen.follows_target());
    }

    #[test]
    fn bad_forms_name_the_problem() {
        let err = |s: &str| s.parse::<Method>().expect_err(s);
        assert!(err("sort-grid-oracle").contains("unknown method"));
        // Comparison baselines are no presets: eval and bench take them by name only.
        assert!(err("stbn").contains("unknown method"));
        assert!(err("sort").contains("unknown method"));
        assert!(err("sort-retarget:key=oracle").contains("unknown key 'oracle'"));
        assert!(err("sort-retarget:colour=red").contains("unknown field 'colour'"));
        assert!(err("sort-retarget:key").contains("expected field=value"));
        assert!(err("sort-retarget:key=history").contains("needs motion=reproject"));
        assert!(err("sort-retarget:pairs=thin").contains("needs transport=grid"));
        assert!(err("white:key=raw").contains("not a permutation method"));
        assert!(err("sort-retarget:points=cycle").contains("needs transport=none"));
        assert!(err("sort-cycle:points=loop").contains("points: fixed, cycle"));
        assert!(err("sort-grid-adaptive:grouping=still-surfaces").contains("needs motion=none"));
        assert!(err("sort-retarget:target=follow").contains("needs points=cycle"));
    }
}
