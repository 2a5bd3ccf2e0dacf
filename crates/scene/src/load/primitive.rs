//! One mesh primitive -> world-space triangles.
//!
//! Memory follows the file and the triangles kept, not the counts the file declares: sparse
//! accessors without a bufferView stay sparse (`accessor::Elements`), indices are read as a
//! stream, and only triangles with three distinct vertices are looked at further.

use super::Ctx;
use super::accessor::{self, Elements};
use crate::scene::Triangle;
use crate::{MAX_COORDINATE, Result, SceneError};
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
    let positions = accessor::check(&pos_acc, &[Dimensions::Vec3], &[DataType::F32], buffers)
        .and_then(|_| {
            let dense = || Some(reader.read_positions()?.map(Vec3::from).collect());
            accessor::read(&pos_acc, buffers, dense, accessor::vec3_f32, Vec3::ZERO)
        })
        .map_err(|p| err(format!("POSITION data cannot be read: {p}")))?;
    let bad_position = |world: bool, (vertex, p): (usize, Vec3)| SceneError::PositionOutOfRange {
        path: ctx.path.to_path_buf(),
        mesh: mesh_name.clone(),
        primitive: prim.index(),
        accessor: pos_acc.index(),
        vertex,
        position: p.to_array(),
        world,
    };
    let refused = |p: Vec3| !p.is_finite() || p.abs().cmpge(Vec3::splat(MAX_COORDINATE)).any();
    if let Some(bad) = positions.find(refused) {
        return Err(bad_position(false, bad));
    }
    let world_pos = positions.map(|p| world.transform_point3(p));
    if let Some(bad) = world_pos.find(refused) {
        return Err(bad_position(true, bad));
    }
    let n_verts = positions.count();

    // Normals (optional; flat normals are generated when missing, as glTF requires).
    let mut normals: Option<Elements<Vec3>> = None;
    if let Some(acc) = prim.get(&gltf::Semantic::Normals) {
        let read = accessor::check(&acc, &[Dimensions::Vec3], &[DataType::F32], buffers)
            .and_then(|_| accessor::same_count(&acc, n_verts))
            .and_then(|_| {
                let dense = || Some(reader.read_normals()?.map(Vec3::from).collect());
                accessor::read(&acc, buffers, dense, accessor::vec3_f32, Vec3::ZERO)
            });
        match read {
            Ok(v) => normals = Some(v.map(|n| (*normal_matrix * n).normalize_or_zero())),
            Err(p) => ctx.warnings.warn("normals", || {
                format!("mesh {mesh_name}: NORMAL {p}; flat normals used instead")
            }),
        }
    }

    // TEXCOORD_0 (optional).
    let mut uvs: Option<Elements<Vec2>> = None;
    if let Some(acc) = prim.get(&gltf::Semantic::TexCoords(0)) {
        let read = accessor::check(
            &acc,
            &[Dimensions::Vec2],
            &[DataType::F32, DataType::U8, DataType::U16],
            buffers,
        )
        .and_then(|_| accessor::same_count(&acc, n_verts))
        .and_then(|_| {
            let dense = || {
                Some(
                    reader
                        .read_tex_coords(0)?
                        .into_f32()
                        .map(Vec2::from)
                        .collect(),
                )
            };
            let decode = accessor::vec2_decoder(acc.data_type());
            accessor::read(&acc, buffers, dense, decode, Vec2::ZERO)
        });
        match read {
            Ok(v) => uvs = Some(v),
            Err(p) => ctx.warnings.warn("uv", || {
                format!("mesh {mesh_name}: TEXCOORD_0 {p}; zero UVs used instead")
            }),
        }
    }

    let material = match prim.material().index() {
        Some(i) => i as u32,
        None => default_material,
    };
    let mut emit = Emit {
        world_pos: &world_pos,
        normals: normals.as_ref(),
        uvs: uvs.as_ref(),
        material,
        flip: world.determinant() < 0.0,
        out,
        zero_area: 0,
    };

    // Indices (optional: non-indexed geometry uses consecutive vertices), read as a stream:
    // a sparse index accessor declares any number of zeros without storing them.
    let index_count = match prim.indices() {
        Some(acc) => {
            accessor::check(
                &acc,
                &[Dimensions::Scalar],
                &[DataType::U8, DataType::U16, DataType::U32],
                buffers,
            )
            .map_err(|p| err(format!("indices {p}")))?;
            let stream = reader
                .read_indices()
                .ok_or_else(|| {
                    err(format!(
                        "indices (accessor {}) cannot be read: the glTF reader found no data",
                        acc.index()
                    ))
                })?
                .into_u32();
            let mut tri = [0usize; 3];
            for (k, i) in stream.enumerate() {
                if i as usize >= n_verts {
                    return Err(SceneError::IndexOutOfRange {
                        path: ctx.path.to_path_buf(),
                        mesh: mesh_name.clone(),
                        primitive: prim.index(),
                        index: i,
                        vertex_count: n_verts,
                    });
                }
                tri[k % 3] = i as usize;
                if k % 3 == 2 {
                    emit.triangle(tri);
                }
            }
            acc.count()
        }
        None => {
            match &positions {
                Elements::Dense(_) => (0..n_verts / 3).for_each(|t| emit.consecutive(t)),
                // Only a triangle with two stored vertices can have area: the others have
                // two vertices at the same point. Each is counted, none is expanded.
                Elements::Sparse { indices, .. } => {
                    let mut candidates: Vec<usize> = indices
                        .iter()
                        .map(|&i| i as usize / 3)
                        .filter(|&t| t < n_verts / 3)
                        .collect();
                    candidates.dedup();
                    emit.zero_area += n_verts / 3 - candidates.len();
                    candidates.into_iter().for_each(|t| emit.consecutive(t));
                }
            }
            n_verts
        }
    };
    ctx.zero_area += emit.zero_area;
    if index_count % 3 != 0 {
        ctx.warnings.warn("index-count", || {
            format!(
                "mesh {mesh_name}: index count {index_count} is not a multiple of 3; the rest \
                 is ignored"
            )
        });
    }
    Ok(())
}

/// Turns vertex triples into triangles, counting the zero-area ones.
struct Emit<'a> {
    world_pos: &'a Elements<Vec3>,
    normals: Option<&'a Elements<Vec3>>,
    uvs: Option<&'a Elements<Vec2>>,
    material: u32,
    /// A mirroring transform: the winding is flipped to keep the front face.
    flip: bool,
    out: &'a mut Vec<Triangle>,
    zero_area: usize,
}

impl Emit<'_> {
    /// Triangle `t` of non-indexed geometry.
    fn consecutive(&mut self, t: usize) {
        self.triangle([3 * t, 3 * t + 1, 3 * t + 2]);
    }

    fn triangle(&mut self, mut ix: [usize; 3]) {
        if ix[0] == ix[1] || ix[1] == ix[2] || ix[0] == ix[2] {
            self.zero_area += 1; // a repeated vertex
            return;
        }
        if self.flip {
            ix.swap(1, 2);
        }
        let p = ix.map(|i| self.world_pos.get(i));
        // In f64 so huge-but-finite coordinates do not overflow into a false "zero area".
        let face = (p[1] - p[0]).as_dvec3().cross((p[2] - p[0]).as_dvec3());
        let len = face.length();
        if !(len.is_finite() && len > 0.0) {
            self.zero_area += 1;
            return;
        }
        let face = (face / len).as_vec3();
        let n = match self.normals {
            Some(ns) => ix.map(|i| {
                let n = ns.get(i);
                if n.is_finite() && n != Vec3::ZERO {
                    n
                } else {
                    face
                }
            }),
            None => [face; 3],
        };
        let uv = match self.uvs {
            Some(us) => ix.map(|i| {
                let uv = us.get(i);
                if uv.is_finite() { uv } else { Vec2::ZERO }
            }),
            None => [Vec2::ZERO; 3],
        };
        self.out.push(Triangle {
            positions: p,
            normals: n,
            uvs: uv,
            material: self.material,
        });
    }
}
