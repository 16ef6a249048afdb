//! KHR_animation_pointer channels, read from the raw JSON. The gltf crate (1.4) requires
//! `target.node` on every channel and knows only TRS/weights paths, so a file with pointer
//! channels fails its deserialisation outright: those channels are taken out of the JSON
//! before the crate sees it and kept here, with the pointer parsed into what this renderer
//! animates (material emission, punctual light colour and intensity).

use serde_json::Value;

use super::super::validate::{SceneError, one_line};

/// What a pointer names (JSON pointer paths of KHR_animation_pointer).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PointerTarget {
    /// `/materials/M/emissiveFactor`
    EmissiveFactor(usize),
    /// `/materials/M/extensions/KHR_materials_emissive_strength/emissiveStrength`
    EmissiveStrength(usize),
    /// `/extensions/KHR_lights_punctual/lights/L/color`
    LightColor(usize),
    /// `/extensions/KHR_lights_punctual/lights/L/intensity`
    LightIntensity(usize),
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PointerChannel {
    pub animation: usize,
    pub sampler: usize,
    pub target: PointerTarget,
}

/// Parses `/materials/3/emissiveFactor` and friends; `None` for anything else.
pub(crate) fn parse_pointer(pointer: &str) -> Option<PointerTarget> {
    let parts: Vec<&str> = pointer.strip_prefix('/')?.split('/').collect();
    let index = |s: &str| s.parse::<usize>().ok();
    match parts.as_slice() {
        ["materials", m, "emissiveFactor"] => Some(PointerTarget::EmissiveFactor(index(m)?)),
        [
            "materials",
            m,
            "extensions",
            "KHR_materials_emissive_strength",
            "emissiveStrength",
        ] => Some(PointerTarget::EmissiveStrength(index(m)?)),
        ["extensions", "KHR_lights_punctual", "lights", l, "color"] => {
            Some(PointerTarget::LightColor(index(l)?))
        }
        [
            "extensions",
            "KHR_lights_punctual",
            "lights",
            l,
            "intensity",
        ] => Some(PointerTarget::LightIntensity(index(l)?)),
        _ => None,
    }
}

/// Removes every channel without `target.node` from `json` (pointer channels and broken
/// ones) and returns the pointer channels this renderer understands. A pointer to
/// anything else is skipped with a warning; a channel that is neither is an error.
pub(crate) fn take_pointer_channels(
    file: &str,
    json: &mut Value,
) -> Result<Vec<PointerChannel>, SceneError> {
    let mut taken = Vec::new();
    let Some(animations) = json.get_mut("animations").and_then(Value::as_array_mut) else {
        return Ok(taken);
    };
    for (a, animation) in animations.iter_mut().enumerate() {
        let Some(channels) = animation.get_mut("channels").and_then(Value::as_array_mut) else {
            continue;
        };
        let mut kept = Vec::with_capacity(channels.len());
        for (c, channel) in std::mem::take(channels).into_iter().enumerate() {
            let target = &channel["target"];
            if target.get("node").is_some() {
                kept.push(channel);
                continue;
            }
            let pointer = target
                .pointer("/extensions/KHR_animation_pointer/pointer")
                .and_then(Value::as_str);
            let Some(pointer) = pointer else {
                return Err(SceneError::Parse {
                    file: file.to_string(),
                    detail: one_line(format!(
                        "animations[{a}].channels[{c}] has neither target.node nor a \
                         KHR_animation_pointer pointer"
                    )),
                });
            };
            let sampler = channel["sampler"].as_u64().map(|s| s as usize);
            match (parse_pointer(pointer), sampler) {
                (Some(target), Some(sampler)) => taken.push(PointerChannel {
                    animation: a,
                    sampler,
                    target,
                }),
                (None, _) => log::warn!(
                    "{file}: animations[{a}].channels[{c}]: ignoring pointer '{pointer}' \
                     (animated here: material emissiveFactor and emissiveStrength, punctual \
                     light color and intensity)"
                ),
                (_, None) => {
                    return Err(SceneError::Parse {
                        file: file.to_string(),
                        detail: format!("animations[{a}].channels[{c}] has no sampler index"),
                    });
                }
            }
        }
        *channels = kept;
    }
    Ok(taken)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pointers_parse_to_targets() {
        assert_eq!(
            parse_pointer("/materials/3/emissiveFactor"),
            Some(PointerTarget::EmissiveFactor(3))
        );
        assert_eq!(
            parse_pointer(
                "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength"
            ),
            Some(PointerTarget::EmissiveStrength(0))
        );
        assert_eq!(
            parse_pointer("/extensions/KHR_lights_punctual/lights/2/intensity"),
            Some(PointerTarget::LightIntensity(2))
        );
        assert_eq!(
            parse_pointer("/extensions/KHR_lights_punctual/lights/1/color"),
            Some(PointerTarget::LightColor(1))
        );
        for other in [
            "/materials/x/emissiveFactor",
            "/materials/1/baseColorFactor",
            "materials/1/emissiveFactor",
            "/nodes/0/translation",
        ] {
            assert_eq!(parse_pointer(other), None, "{other}");
        }
    }

    #[test]
    fn pointer_channels_are_taken_out_and_node_channels_stay() {
        let mut json: Value = serde_json::from_str(
            r#"{"animations":[{"samplers":[{},{}],"channels":[
                {"sampler":0,"target":{"node":0,"path":"translation"}},
                {"sampler":1,"target":{"path":"pointer","extensions":{"KHR_animation_pointer":
                    {"pointer":"/materials/0/emissiveFactor"}}}},
                {"sampler":1,"target":{"path":"pointer","extensions":{"KHR_animation_pointer":
                    {"pointer":"/cameras/0/perspective/yfov"}}}}]}]}"#,
        )
        .unwrap();
        let taken = take_pointer_channels("f.gltf", &mut json).unwrap();
        assert_eq!(
            taken,
            vec![PointerChannel {
                animation: 0,
                sampler: 1,
                target: PointerTarget::EmissiveFactor(0)
            }]
        );
        assert_eq!(
            json["animations"][0]["channels"].as_array().unwrap().len(),
            1
        );
        let mut broken: Value =
            serde_json::from_str(r#"{"animations":[{"channels":[{"sampler":0,"target":{}}]}]}"#)
                .unwrap();
        assert!(take_pointer_channels("f.gltf", &mut broken).is_err());
    }
}
