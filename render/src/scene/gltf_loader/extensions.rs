//! What this loader does with each glTF extension: the one table (`TABLE`), the report of a
//! file's extensions (`Scene::extensions`, shown by the viewer's Scene panel and written by
//! `render --stats`) and the refusal of a file that requires what cannot be shown.

/// How the loader treats an extension a file lists.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(tag = "status", content = "detail", rename_all = "snake_case")]
pub enum ExtensionStatus {
    /// Read and rendered as specified.
    Used,
    /// Read, with the named parts ignored.
    PartlyUsed(String),
    /// Not read (the file does not require it, so it renders without it).
    Ignored,
    /// Required but not implemented: the file is not loaded. The text says how to convert it.
    Refused(String),
}

/// One extension of a file's `extensionsUsed` / `extensionsRequired`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct ExtensionUse {
    pub name: String,
    pub required: bool,
    #[serde(flatten)]
    pub status: ExtensionStatus,
}

impl std::fmt::Display for ExtensionUse {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let required = if self.required { " (required)" } else { "" };
        match &self.status {
            ExtensionStatus::Used => write!(f, "{}{required}: used", self.name),
            ExtensionStatus::PartlyUsed(what) => {
                write!(f, "{}{required}: partly used — {what}", self.name)
            }
            ExtensionStatus::Ignored => write!(f, "{}{required}: ignored", self.name),
            ExtensionStatus::Refused(why) => write!(f, "{}{required}: refused — {why}", self.name),
        }
    }
}

/// What the loader implements of one extension.
enum Support {
    Full,
    /// Implemented except the named parts.
    Partial(&'static str),
    /// Its data is not decoded: a file that requires it is refused with this advice; a file
    /// that only uses it carries uncompressed fallback data (both compression extensions
    /// demand that), which is read instead.
    FallbackOnly(&'static str),
}

/// The extensions this loader knows. Everything else is ignored when optional and refused
/// when required. Transmission is the thin-layer model of README's conventions.
const TABLE: &[(&str, Support)] = &[
    (
        "KHR_animation_pointer",
        Support::Partial(
            "only emissive factor and strength and punctual light colour and intensity are animated",
        ),
    ),
    ("KHR_lights_punctual", Support::Full),
    ("KHR_materials_emissive_strength", Support::Full),
    (
        "KHR_materials_specular",
        Support::Partial("specularTexture, specularColorFactor and specularColorTexture ignored"),
    ),
    ("KHR_texture_transform", Support::Full),
    ("KHR_mesh_quantization", Support::Full),
    ("KHR_materials_unlit", Support::Full),
    (
        "KHR_materials_transmission",
        Support::Partial(
            "thin-walled: no refraction or rough transmission; the glass reflects direct light only",
        ),
    ),
    (
        "KHR_materials_ior",
        Support::Partial("ior ignored, F0 from KHR_materials_specular"),
    ),
    (
        "KHR_materials_volume",
        Support::Partial("thickness and attenuation ignored (thin-walled)"),
    ),
    (
        "KHR_draco_mesh_compression",
        Support::FallbackOnly(
            "Draco-compressed meshes are not decoded; decompress it first: \
             `npx @gltf-transform/cli copy in.glb out.glb`",
        ),
    ),
    (
        "EXT_meshopt_compression",
        Support::FallbackOnly(
            "meshopt-compressed buffers are not decoded; decompress it first: \
             `gltfpack -i in.glb -o out.glb` (a gltfpack from 2024 or later reads meshopt input; \
             leave out -c)",
        ),
    ),
];

/// Extensions a file may require and still load.
pub(super) fn supported_when_required() -> Vec<&'static str> {
    TABLE
        .iter()
        .filter(|(_, s)| !matches!(s, Support::FallbackOnly(_)))
        .map(|(name, _)| *name)
        .collect()
}

/// The status of every extension the file lists (used ones in file order, then required
/// ones it forgot to list as used).
pub(super) fn report(used: &[String], required: &[String]) -> Vec<ExtensionUse> {
    let mut names: Vec<&String> = used.iter().collect();
    names.extend(required.iter().filter(|r| !used.contains(r)));
    names
        .into_iter()
        .map(|name| {
            let required = required.contains(name);
            let support = TABLE.iter().find(|(n, _)| n == name).map(|(_, s)| s);
            let status = match (support, required) {
                (Some(Support::Full), _) => ExtensionStatus::Used,
                (Some(Support::Partial(what)), _) => ExtensionStatus::PartlyUsed(what.to_string()),
                (Some(Support::FallbackOnly(how)), true) => {
                    ExtensionStatus::Refused(how.to_string())
                }
                (Some(Support::FallbackOnly(_)), false) => ExtensionStatus::PartlyUsed(
                    "compressed data ignored, the file's uncompressed fallback is read".to_string(),
                ),
                (None, false) => ExtensionStatus::Ignored,
                (None, true) => ExtensionStatus::Refused(format!(
                    "not implemented (supported when required: {})",
                    supported_when_required().join(", ")
                )),
            };
            ExtensionUse {
                name: name.clone(),
                required,
                status,
            }
        })
        .collect()
}

/// The one-line refusal of a file, naming its first refused extension.
pub(super) fn refusal(report: &[ExtensionUse]) -> Option<String> {
    report.iter().find_map(|e| match &e.status {
        ExtensionStatus::Refused(why) => Some(format!("uses {} ({why})", e.name)),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn optional_compression_reads_the_fallback_and_required_is_refused() {
        let used = names(&["EXT_meshopt_compression", "KHR_draco_mesh_compression"]);
        let optional = report(&used, &[]);
        assert!(
            optional
                .iter()
                .all(|e| matches!(e.status, ExtensionStatus::PartlyUsed(_)))
        );
        assert_eq!(refusal(&optional), None);
        let required = report(&used, &names(&["KHR_draco_mesh_compression"]));
        assert!(matches!(required[0].status, ExtensionStatus::PartlyUsed(_)));
        let line = refusal(&required).unwrap();
        assert!(
            line.starts_with("uses KHR_draco_mesh_compression (Draco-compressed"),
            "{line}"
        );
        assert!(
            line.contains("npx @gltf-transform/cli copy in.glb out.glb"),
            "{line}"
        );
        assert!(!line.contains('\n'));
        assert!(!supported_when_required().contains(&"EXT_meshopt_compression"));
    }

    #[test]
    fn unknown_extensions_are_ignored_or_refused() {
        let r = report(
            &names(&["EXT_foo", "KHR_texture_transform"]),
            &names(&["EXT_bar"]),
        );
        let shown: Vec<String> = r.iter().map(|e| e.to_string()).collect();
        assert_eq!(shown[0], "EXT_foo: ignored");
        assert_eq!(shown[1], "KHR_texture_transform: used");
        assert!(
            shown[2].starts_with("EXT_bar (required): refused — not implemented"),
            "{}",
            shown[2]
        );
    }
}
