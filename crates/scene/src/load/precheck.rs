//! Checks the glTF reader relies on but does not make itself (fuzz findings): it panics on
//! these instead of reporting them. Run on the parsed JSON before the reader's validation;
//! problems are reported like the reader's own validation errors.

use gltf::json::{Path, Root, mesh::Semantic, validation::Checked, validation::Error};

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
