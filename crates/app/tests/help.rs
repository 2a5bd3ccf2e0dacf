//! `--help` of every rendering command lists every method preset and sampler of the tables the
//! code parses with (so a preset added to the table shows up without anyone editing the help),
//! with the defaults.
use blueshift_render::Method;
use blueshift_sampling::Sampler;
mod common;
use std::process::Command;

fn help(command: &str) -> String {
    let o = common::clean(Command::new(common::BIN))
        .args([command, "--help"])
        .output()
        .expect("run blueshift");
    assert!(o.status.success(), "{command} --help failed");
    String::from_utf8(o.stdout).expect("utf-8 help")
}

/// The help text of `flag` (from the flag to the next flag of the list).
fn flag_help<'a>(help: &'a str, flag: &str) -> &'a str {
    let start = help
        .find(&format!("  {flag} "))
        .unwrap_or_else(|| panic!("no {flag} in:\n{help}"));
    let rest = &help[start + flag.len() + 2..];
    let end = rest.find("\n  -").unwrap_or(rest.len());
    &rest[..end]
}

/// Whether `name` is one of the comma-separated possible values the help lists.
fn lists(text: &str, name: &str) -> bool {
    let Some(i) = text.find("[possible values: ") else {
        return false;
    };
    let values = &text[i + "[possible values: ".len()..];
    let values = &values[..values.find(']').unwrap_or(values.len())];
    values.split(',').any(|v| v.trim() == name)
}

#[test]
fn every_command_lists_every_preset_and_sampler_with_defaults() {
    for command in ["render", "view", "eval", "bench", "soak"] {
        let h = help(command);
        let methods = flag_help(
            &h,
            if command == "eval" {
                "--methods"
            } else {
                "--method"
            },
        );
        for (name, _) in Method::PRESETS {
            assert!(
                lists(methods, name),
                "{command}: preset {name} missing:\n{methods}"
            );
        }
        assert!(methods.contains("[default: "), "{command}:\n{methods}");
        let sampler = flag_help(&h, "--sampler");
        for s in Sampler::ALL {
            assert!(
                lists(sampler, s.name()),
                "{command}: sampler {} missing:\n{sampler}",
                s.name()
            );
        }
        // No single default: each method's own, which the help names for the odd ones out.
        assert!(
            sampler.contains("default: the method's"),
            "{command}:\n{sampler}"
        );
        let odd = Method::PRESETS
            .iter()
            .find(|(_, m)| m.default_sampler() == Sampler::BlockNet);
        let (name, _) = odd.expect("a preset uses the block-net sampler");
        assert!(
            sampler.contains(&format!("blocknet for {name}")),
            "{command}:\n{sampler}"
        );
        let sampling = flag_help(&h, "--environment-sampling");
        assert!(
            sampling.contains("[default: importance]"),
            "{command}:\n{sampling}"
        );
    }
}

#[test]
fn each_command_keeps_its_default_method() {
    for (command, default) in [
        ("render", Method::SORT_CYCLE),
        ("view", Method::SORT_CYCLE),
        ("bench", Method::White),
        ("soak", Method::SORT_CYCLE),
    ] {
        let h = help(command);
        let want = format!("[default: {}]", default.name());
        assert!(
            flag_help(&h, "--method").contains(&want),
            "{command}: {want}"
        );
    }
}
