//! Checks the glTF reader relies on but does not make itself (fuzz findings): it panics on
//! these instead of reporting them. Run on the parsed JSON before the reader's validation;
//! problems are reported like the reader's own validation errors.

use crate::SceneError;
use gltf::json::{Path, Root, mesh::Semantic, validation::Checked, validation::Error};

/// Extensions the loader implements, so a file may require them (`extensionsRequired`).
/// Others it ignores with a warning, or reads in part (`KHR_texture_transform`: textures are
/// sampled without the transform), so a file that requires them is refused.
const IMPLEMENTED_EXTENSIONS: [&str; 3] = [
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_specular",
];

/// Rules refused with their own error, before the reader's validation: a glTF version other
/// than 2.x, a required extension the loader does not implement, and `byteStride` values the
/// specification forbids (a multiple of 4 in 4..=252; the reader checks only the range).
pub(crate) fn spec(path: &std::path::Path, root: &Root) -> Result<(), SceneError> {
    // A 2.x file may be read by a 2.0 loader unless its minVersion says it needs more.
    let asset = &root.asset;
    let refused = [
        ("version", Some(&asset.version).filter(|v| !is_2x(v))),
        (
            "minVersion",
            asset.min_version.as_ref().filter(|&v| v != "2.0"),
        ),
    ];
    if let Some((field, Some(v))) = refused.into_iter().find(|(_, v)| v.is_some()) {
        return Err(SceneError::Version {
            path: path.to_path_buf(),
            field,
            version: v.clone(),
        });
    }
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| !IMPLEMENTED_EXTENSIONS.contains(&e.as_str()))
    {
        return Err(SceneError::UnsupportedExtension {
            path: path.to_path_buf(),
            extension: ext.clone(),
        });
    }
    for (i, view) in root.buffer_views.iter().enumerate() {
        if let Some(stride) = view.byte_stride.map(|s| s.0)
            && (stride % 4 != 0 || !(4..=252).contains(&stride))
        {
            return Err(SceneError::Spec {
                path: path.to_path_buf(),
                problem: format!(
                    "bufferViews[{i}].byteStride is {stride}; it must be a multiple of 4 from 4 \
                     to 252"
                ),
            });
        }
    }
    Ok(())
}

/// For a file the reader cannot parse: the version error, if its `asset.version` can be read
/// and is not 2.x (a glTF 1.0 or 3.0 file fails for that reason, not for its layout).
pub(crate) fn version_of_unreadable(path: &std::path::Path, json: &[u8]) -> Option<SceneError> {
    let value: serde_json::Value = serde_json::from_slice(json).ok()?;
    let version = value.get("asset")?.get("version")?;
    let text = version
        .as_str()
        .map_or_else(|| version.to_string(), str::to_string);
    (!is_2x(&text)).then(|| SceneError::Version {
        path: path.to_path_buf(),
        field: "version",
        version: text,
    })
}

/// `2.0`, `2.1`, ...: what a glTF 2.0 loader may read.
fn is_2x(version: &str) -> bool {
    version
        .strip_prefix("2.")
        .is_some_and(|minor| !minor.is_empty() && minor.bytes().all(|b| b.is_ascii_digit()))
}

/// Every problem as a (JSON path, error) pair, in the reader's validation format.
pub(crate) fn check(root: &Root) -> Vec<(Path, Error)> {
    let mut problems = Vec::new();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            // The reader's validation hook indexes the accessors with POSITION unchecked.
            let position = prim.attributes.get(&Checked::Valid(Semantic::Positions));
            if let Some(index) = position
                && index.value() >= root.accessors.len()
            {
                let path = Path::new()
                    .field("meshes")
                    .index(m)
                    .field("primitives")
                    .index(p)
                    .field("attributes")
                    .key("POSITION");
                problems.push((path, Error::IndexOutOfBounds));
            }
        }
    }
    for (i, image) in root.images.iter().enumerate() {
        // `Image::source` unwraps these (the spec requires them).
        let path = Path::new().field("images").index(i);
        match (&image.buffer_view, &image.uri) {
            (Some(_), _) if image.mime_type.is_none() => {
                problems.push((path.field("mimeType"), Error::Missing));
            }
            (None, None) => problems.push((path.field("uri"), Error::Missing)),
            _ => {}
        }
    }
    problems
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root(json: &str) -> Root {
        gltf::json::deserialize::from_str(json).expect("json")
    }

    #[test]
    fn out_of_range_position_accessor_and_incomplete_images_are_reported() {
        let r = root(
            r#"{"asset":{"version":"2.0"},
            "meshes":[{"primitives":[{"attributes":{"POSITION":5}}]}],
            "images":[{"bufferView":0},{"name":"nothing"},{"uri":"a.png"}]}"#,
        );
        let got: Vec<String> = check(&r).iter().map(|(p, e)| format!("{p}: {e}")).collect();
        assert_eq!(
            got,
            [
                "meshes[0].primitives[0].attributes[\"POSITION\"]: Index out of bounds",
                "images[0].mimeType: Missing data",
                "images[1].uri: Missing data",
            ]
        );
    }
}
