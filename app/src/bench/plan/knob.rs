//! A cost curve's knob (`--knob NAME=V1,V2,...`): every configuration once per value, and
//! the check that each point renders what it names (docs/src/measured/how-the-bench-measures.md,
//! "Equal error").

use anyhow::{Context, bail};
use restir_render::Renderer;

use super::configs::Config;

/// `--knob NAME=V1,V2,...`: each configuration of `list` once per value, as
/// `CONFIG[NAME=V]`, or `CONFIG[its own;NAME=V]` where it has parameters already (a
/// configuration name `--configs` parses back, so the points run as jobs too).
pub fn expand_knob(list: &str, knob: &str) -> anyhow::Result<String> {
    let (name, values) = knob
        .split_once('=')
        .filter(|(n, v)| !n.trim().is_empty() && !v.trim().is_empty())
        .with_context(|| format!("--knob '{knob}': expected NAME=V1,V2,..."))?;
    let values: Vec<&str> = values
        .split(',')
        .map(str::trim)
        .filter(|v| !v.is_empty())
        .collect();
    if values.len() < 2 {
        bail!("--knob '{knob}': a cost curve needs two values at least");
    }
    let items: Vec<String> = list
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .flat_map(|c| {
            values.iter().map(move |v| match c.strip_suffix(']') {
                Some(own) => format!("{own};{}={v}]", name.trim()),
                None => format!("{c}[{}={v}]", name.trim()),
            })
        })
        .collect();
    Ok(items.join(","))
}

/// The parameter a `--knob NAME=V1,...` sweeps (`expand_knob` has checked its form).
pub fn name(knob: &str) -> &str {
    knob.split_once('=').map_or(knob, |(n, _)| n).trim()
}

/// Refuses a sweep whose knob the renderer overrides at some point (auto's light BVH
/// draws at most `AUTO_BVH_CANDIDATES`; `nee` draws one candidate): such points render the
/// same frames under different names, and the cost curve would be a flat line that says
/// nothing. Checked on one renderer before anything is rendered.
pub fn check_knob_points(
    renderer: &mut Renderer,
    configs: &[Config],
    knob: &str,
) -> anyhow::Result<()> {
    let name = name(knob);
    for c in configs {
        renderer.set_mode(c.mode);
        renderer.set_settings(c.settings.clone());
        let asked = c.settings.get(name);
        let ran = renderer.effective_settings().get(name);
        if asked != ran {
            let show = |v: Option<restir_render::settings::ParamValue>| {
                v.map_or("-".to_string(), |v| v.to_string())
            };
            bail!(
                "--knob {name}: configuration '{}' asks for {name} = {} but would render with \
                 {} (its mode or `auto` chooses it: auto's light BVH draws at most {} \
                 candidates); name the choice (e.g. --set light_sampler=bvh) or leave the \
                 configuration out of the sweep",
                c.name,
                show(asked),
                show(ran),
                restir_render::effects::AUTO_BVH_CANDIDATES,
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_knob_runs_each_configuration_once_per_value() {
        assert_eq!(
            expand_knob("ris,restir", "light_candidates=2,8").unwrap(),
            "ris[light_candidates=2],ris[light_candidates=8],restir[light_candidates=2],restir[light_candidates=8]"
        );
        assert_eq!(
            expand_knob("restir[m_cap=4]", "light_candidates=2,8").unwrap(),
            "restir[m_cap=4;light_candidates=2],restir[m_cap=4;light_candidates=8]"
        );
        assert!(expand_knob("ris", "light_candidates=2").is_err());
        assert!(expand_knob("ris", "=2,3").is_err());
        assert_eq!(name(" light_candidates =2,8"), "light_candidates");
    }
}
