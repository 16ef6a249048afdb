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
}

/// The extensions this loader knows. Everything else is ignored when optional and refused
/// when required. Transmission is the thin-layer model (docs/src/transparency.md, "The
/// thin-layer model").
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
    // Compressed files decode in pure Rust (compressed, draco, meshopt, ktx2 modules). When a
    // file also carries uncompressed data, the compressed data is read, as the extensions ask
    // of a loader that supports them.
    // Draco: draco-core; the attributes this renderer reads (POSITION, NORMAL, TEXCOORD_n).
    ("KHR_draco_mesh_compression", Support::Full),
    // meshopt: meshoptimizer-rs; ATTRIBUTES, TRIANGLES and INDICES, filters OCTAHEDRAL,
    // QUATERNION and EXPONENTIAL (all that EXT_meshopt_compression has).
    ("EXT_meshopt_compression", Support::Full),
    (
        "KHR_texture_basisu",
        Support::Partial(
            "ETC1S and UASTC LDR transcoded to 8-bit RGBA (basisu); only the base mip level is read",
        ),
    ),
    // WebP: the image crate's pure-Rust decoder, lossy and lossless, alpha.
    ("EXT_texture_webp", Support::Full),
];

/// Extensions a file may require and still load: all the table's.
pub(super) fn supported_when_required() -> Vec<&'static str> {
    TABLE.iter().map(|(name, _)| *name).collect()
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
    fn compression_is_decoded_whether_used_or_required() {
        let all = [
            "KHR_draco_mesh_compression",
            "EXT_meshopt_compression",
            "KHR_texture_basisu",
            "EXT_texture_webp",
        ];
        let required = report(&names(&all), &names(&all));
        assert_eq!(refusal(&required), None);
        let shown: Vec<String> = required.iter().map(|e| e.to_string()).collect();
        assert_eq!(
            shown,
            [
                "KHR_draco_mesh_compression (required): used",
                "EXT_meshopt_compression (required): used",
                "KHR_texture_basisu (required): partly used — ETC1S and UASTC LDR transcoded \
                 to 8-bit RGBA (basisu); only the base mip level is read",
                "EXT_texture_webp (required): used",
            ]
        );
        assert!(all.iter().all(|e| supported_when_required().contains(e)));
        // A compression this build does not know is still one line naming it.
        let unknown = report(
            &names(&["EXT_unknown_compression"]),
            &names(&["EXT_unknown_compression"]),
        );
        let line = refusal(&unknown).unwrap();
        assert!(
            line.starts_with("uses EXT_unknown_compression (not implemented"),
            "{line}"
        );
        assert!(line.contains("KHR_draco_mesh_compression") && !line.contains('\n'));
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
