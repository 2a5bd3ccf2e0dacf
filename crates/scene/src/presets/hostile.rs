//! Small files that would cost the loader far more than their size if it trusted them: node
//! graphs that are not trees, instancing beyond any device, an image header declaring
//! billions of texels. The tests and the fuzz seeds use them; the loader refuses each (or
//! skips the image) without expanding it.

use super::shapes::rectangle;
use super::{GltfBuilder, MeshData};
use serde_json::json;

/// A `.glb` whose node `i` has the children `children[i]` and draws one quad (two triangles);
/// `roots` are the roots of its scene.
pub fn node_graph(children: &[Vec<usize>], roots: &[usize]) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("quad", &rectangle(1.0), None);
    for c in children {
        b.add_node(json!({ "mesh": mesh, "children": c }));
    }
    for &r in roots {
        b.add_root(r);
    }
    b.to_glb()
}

/// Node 2 is a child of nodes 0 and 1, both roots.
pub fn two_parents() -> Vec<u8> {
    node_graph(&[vec![2], vec![2], vec![]], &[0, 1])
}

/// `depth` nodes, each listing the next twice: 2^(depth - 1) paths to the last one.
pub fn shared_chain(depth: usize) -> Vec<u8> {
    let children: Vec<Vec<usize>> = (0..depth)
        .map(|i| {
            if i + 1 < depth {
                vec![i + 1; 2]
            } else {
                vec![]
            }
        })
        .collect();
    node_graph(&children, &[0])
}

/// A `.glb` with `nodes` roots that all draw one mesh of `triangles` triangles (one triangle
/// indexed over and over): `nodes * triangles` triangles after instancing, in about
/// `12 * triangles + 30 * nodes` bytes.
pub fn instanced(nodes: usize, triangles: usize) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let one = MeshData {
        positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        indices: Some([0, 1, 2].repeat(triangles)),
        ..MeshData::default()
    };
    let mesh = b.add_mesh("instanced", &one, None);
    for i in 0..nodes {
        let n = b.add_node(json!({ "mesh": mesh, "translation": [0.0, 0.0, -(i as f64)] }));
        b.add_root(n);
    }
    b.to_glb()
}

/// A PNG that is only a header: `IHDR` declaring `width x height` RGBA8 texels, a truncated
/// `IDAT` and `IEND`. It cannot be decoded; its size can be read.
pub fn png_header(width: u32, height: u32) -> Vec<u8> {
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&width.to_be_bytes());
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, 6, 0, 0, 0]); // 8 bits, RGBA, deflate, no filter, no interlace
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    for (tag, data) in [
        (b"IHDR", &ihdr[..]),
        (b"IDAT", &[0x78, 0x9c][..]),
        (b"IEND", &[][..]),
    ] {
        png.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let start = png.len();
        png.extend_from_slice(tag);
        png.extend_from_slice(data);
        let crc = crc32(&png[start..]);
        png.extend_from_slice(&crc.to_be_bytes());
    }
    png
}

/// A `.glb`: a quad whose base colour texture is [`png_header`]`(width, height)`.
pub fn huge_texture(width: u32, height: u32) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let tex = b.add_png_texture("huge", &png_header(width, height), json!({}));
    let material = b.add_material(json!({
        "pbrMetallicRoughness": { "baseColorTexture": { "index": tex } }
    }));
    let mesh = b.add_mesh("quad", &rectangle(1.0), Some(material));
    let n = b.add_node(json!({ "mesh": mesh }));
    b.add_root(n);
    b.to_glb()
}

/// CRC-32 (ISO-HDLC, as PNG chunks use), bit by bit: these files are tiny.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_check_value() {
        // The standard check value of CRC-32/ISO-HDLC.
        assert_eq!(crc32(b"123456789"), 0xcbf4_3926);
    }

    #[test]
    fn png_header_declares_the_size() {
        let png = png_header(60_000, 50_000);
        let reader = image::ImageReader::new(std::io::Cursor::new(&png))
            .with_guessed_format()
            .expect("guess");
        assert_eq!(reader.into_dimensions().expect("header"), (60_000, 50_000));
    }
}
