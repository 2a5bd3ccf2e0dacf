//! One mesh primitive -> world-space triangles.

use super::Ctx;
use crate::scene::Triangle;
use crate::{Result, SceneError};
use glam::{Mat3, Mat4, Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

/// Appends the primitive's triangles to `out`. Unsupported primitives are skipped with a
/// warning; unreadable or corrupt ones are errors.
pub(super) fn read(
    ctx: &mut Ctx,
    mesh: &gltf::Mesh,
    prim: &gltf::Primitive,
    world: &Mat4,
    normal_matrix: &Mat3,
    default_material: u32,
    out: &mut Vec<Triangle>,
) -> Result<()> {
    let mesh_name = match mesh.name() {
        Some(n) => format!("{} ('{n}')", mesh.index()),
        None => mesh.index().to_string(),
    };
    let err = |problem: String| SceneError::Primitive {
        path: ctx.path.to_path_buf(),
        mesh: mesh_name.clone(),
        primitive: prim.index(),
        problem,
    };
    if prim.mode() != Mode::Triangles {
        let mode = prim.mode();
        ctx.warnings.warn(&format!("mode:{mode:?}"), || {
            format!("primitives with mode {mode:?} skipped (only TRIANGLES is supported)")
        });
        return Ok(());
    }
    if prim.morph_targets().next().is_some() {
        ctx.warnings.warn("morph", || {
            "morph targets ignored: base shape is used".into()
        });
    }

    let buffers = ctx.buffers;
    let reader = prim.reader(|b| buffers.get(b.index()).map(|d| d.0.as_slice()));

    // Positions (required).
    let pos_acc = prim
        .get(&gltf::Semantic::Positions)
        .ok_or_else(|| err("has no POSITION attribute".into()))?;
    check_accessor(&pos_acc, &[Dimensions::Vec3], &[DataType::F32], buffers)
        .map_err(|p| err(format!("POSITION {p}")))?;
    let positions: Vec<Vec3> = reader
        .read_positions()
        .ok_or_else(|| err("POSITION data cannot be read".into()))?
        .map(Vec3::from)
        .collect();
    if positions.len() != pos_acc.count() {
        return Err(err("POSITION data is shorter than its count".into()));
    }
    let nonfinite = |vertex: usize, p: Vec3| SceneError::NonFinitePosition {
        path: ctx.path.to_path_buf(),
        mesh: mesh_name.clone(),
        primitive: prim.index(),
        vertex,
        position: p.to_array(),
    };
    if let Some((i, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(nonfinite(i, *p));
    }
    let world_pos: Vec<Vec3> = positions
        .iter()
        .map(|&p| world.transform_point3(p))
        .collect();
    if let Some((i, p)) = world_pos.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(nonfinite(i, *p));
    }
    let n_verts = positions.len();

    // Normals (optional; flat normals are generated when missing, as glTF requires).
    let mut normals: Option<Vec<Vec3>> = None;
    if let Some(acc) = prim.get(&gltf::Semantic::Normals) {
        let ok = check_accessor(&acc, &[Dimensions::Vec3], &[DataType::F32], buffers)
            .and_then(|_| same_count(&acc, n_verts))
            .and_then(|_| {
                let v: Vec<Vec3> = reader
                    .read_normals()
                    .ok_or("cannot be read")?
                    .map(Vec3::from)
                    .collect();
                if v.len() == n_verts {
                    Ok(v)
                } else {
                    Err("has the wrong count".into())
                }
            });
        match ok {
            Ok(v) => {
                normals = Some(
                    v.iter()
                        .map(|&n| (*normal_matrix * n).normalize_or_zero())
                        .collect(),
                )
            }
            Err(p) => ctx.warnings.warn("normals", || {
                format!("mesh {mesh_name}: NORMAL {p}; flat normals used instead")
            }),
        }
    }

    // TEXCOORD_0 (optional).
    let mut uvs: Option<Vec<Vec2>> = None;
    if let Some(acc) = prim.get(&gltf::Semantic::TexCoords(0)) {
        let ok = check_accessor(
            &acc,
            &[Dimensions::Vec2],
            &[DataType::F32, DataType::U8, DataType::U16],
            buffers,
        )
        .and_then(|_| same_count(&acc, n_verts))
        .and_then(|_| {
            let v: Vec<Vec2> = reader
                .read_tex_coords(0)
                .ok_or("cannot be read")?
                .into_f32()
                .map(Vec2::from)
                .collect();
            if v.len() == n_verts {
                Ok(v)
            } else {
                Err("has the wrong count".into())
            }
        });
        match ok {
            Ok(v) => uvs = Some(v),
            Err(p) => ctx.warnings.warn("uv", || {
                format!("mesh {mesh_name}: TEXCOORD_0 {p}; zero UVs used instead")
            }),
        }
    }

    // Indices (optional: non-indexed geometry uses consecutive vertices).
    let indices: Vec<u32> = match prim.indices() {
        Some(acc) => {
            check_accessor(
                &acc,
                &[Dimensions::Scalar],
                &[DataType::U8, DataType::U16, DataType::U32],
                buffers,
            )
            .map_err(|p| err(format!("indices {p}")))?;
            let v: Vec<u32> = reader
                .read_indices()
                .ok_or_else(|| err("indices cannot be read".into()))?
                .into_u32()
                .collect();
            if let Some(&bad) = v.iter().find(|&&i| i as usize >= n_verts) {
                return Err(SceneError::IndexOutOfRange {
                    path: ctx.path.to_path_buf(),
                    mesh: mesh_name.clone(),
                    primitive: prim.index(),
                    index: bad,
                    vertex_count: n_verts,
                });
            }
            v
        }
        None => (0..n_verts as u32).collect(),
    };
    if indices.len() % 3 != 0 {
        ctx.warnings.warn("index-count", || {
            format!(
                "mesh {mesh_name}: index count {} is not a multiple of 3; the rest is ignored",
                indices.len()
            )
        });
    }

    let material = match prim.material().index() {
        Some(i) => i as u32,
        None => default_material,
    };
    let flip = world.determinant() < 0.0;
    for tri in indices.chunks_exact(3) {
        let mut ix = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
        if flip {
            ix.swap(1, 2);
        }
        let p = ix.map(|i| world_pos[i]);
        // In f64 so huge-but-finite coordinates do not overflow into a false "zero area".
        let face = (p[1] - p[0]).as_dvec3().cross((p[2] - p[0]).as_dvec3());
        let len = face.length();
        let has_area = len.is_finite() && len > 0.0;
        if !has_area {
            ctx.zero_area += 1;
            continue;
        }
        let face = (face / len).as_vec3();
        let n = match &normals {
            Some(ns) => ix.map(|i| {
                let n = ns[i];
                if n.is_finite() && n != Vec3::ZERO {
                    n
                } else {
                    face
                }
            }),
            None => [face; 3],
        };
        let uv = match &uvs {
            Some(us) => ix.map(|i| if us[i].is_finite() { us[i] } else { Vec2::ZERO }),
            None => [Vec2::ZERO; 3],
        };
        out.push(Triangle {
            positions: p,
            normals: n,
            uvs: uv,
            material,
        });
    }
    Ok(())
}

/// A vertex attribute must have one element per vertex; checked before it is read, since a
/// sparse accessor's count is not bounded by any data in the file.
fn same_count(acc: &gltf::Accessor, n_verts: usize) -> std::result::Result<(), String> {
    if acc.count() == n_verts {
        Ok(())
    } else {
        Err("has the wrong count".into())
    }
}

/// Checks type, count and that the accessor's bytes lie inside its buffer view and buffer, so
/// the reader can neither panic nor silently read garbage.
pub(super) fn check_accessor(
    acc: &gltf::Accessor,
    dims: &[Dimensions],
    types: &[DataType],
    buffers: &[gltf::buffer::Data],
) -> std::result::Result<(), String> {
    let i = acc.index();
    if !dims.contains(&acc.dimensions()) {
        return Err(format!(
            "accessor {i} has type {:?}, expected {dims:?}",
            acc.dimensions()
        ));
    }
    if !types.contains(&acc.data_type()) {
        return Err(format!(
            "accessor {i} has component type {:?}, expected {types:?}",
            acc.data_type()
        ));
    }
    if acc.count() == 0 {
        return Err(format!("accessor {i} has count 0"));
    }
    let view = match (acc.view(), acc.sparse()) {
        (Some(v), _) => v,
        (None, Some(_)) => return Ok(()), // sparse on zeros: the reader bounds-checks it
        (None, None) => {
            return Err(format!(
                "accessor {i} has neither bufferView nor sparse data"
            ));
        }
    };
    let elem = acc.size() as u64;
    let stride = view.stride().map(|s| s as u64).unwrap_or(elem);
    if stride < elem {
        return Err(format!(
            "accessor {i}: byteStride {stride} is smaller than an element ({elem})"
        ));
    }
    let end = (acc.count() as u64 - 1)
        .checked_mul(stride)
        .and_then(|x| x.checked_add(acc.offset() as u64 + elem));
    if end.is_none_or(|e| e > view.length() as u64) {
        return Err(format!(
            "accessor {i} reads past the end of bufferView {} ({} bytes)",
            view.index(),
            view.length()
        ));
    }
    let buf = view.buffer();
    let available = buffers
        .get(buf.index())
        .map(|d| d.len() as u64)
        .unwrap_or(0);
    if view.offset() as u64 + view.length() as u64 > available.min(buf.length() as u64) {
        return Err(format!(
            "bufferView {} extends past the end of buffer {} ({} bytes)",
            view.index(),
            buf.index(),
            buf.length()
        ));
    }
    Ok(())
}
