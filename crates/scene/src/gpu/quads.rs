//! Emissive parallelograms: two triangles of one material that share an edge and together
//! form a parallelogram are sampled as one light, q = o + u s + v t over the whole quad.
//!
//! Why: a triangle light maps its 2D sample (u, v) radially from its first vertex (sqrt(u)),
//! and a quad split into two triangles is chosen by the first dimension, stretched into each
//! half. Both maps depend on how the file happens to order the indices: the same Cornell box
//! light written `0 1 2 2 3 0` instead of `0 1 2 0 2 3` put neighbouring pixels' blue-noise
//! samples on unrelated parts of the light, and `mask-r2` lost most of its blue noise (per
//! frame P1 0.86 against 0.56). The affine map of the whole quad keeps a 2D point set's
//! structure on the light, and its frame (o, s, t) is chosen from the four corners' positions
//! alone, so every index order and split of the same quad samples the same points.
use super::GpuTriangle;
use glam::{DVec3, Vec3};
use std::cmp::Ordering;
use std::collections::HashMap;

/// `GpuLight::triangle` of a parallelogram: the first triangle's index in the low
/// `LIGHT_QUAD_SHIFT` bits, and above them the quad's frame (`QuadFrame::code`).
pub const LIGHT_QUAD_SHIFT: u32 = 25;
/// Mask of a light's triangle index (below the frame bits and `LIGHT_PARAMS_BIT`).
pub const LIGHT_TRIANGLE_MASK: u32 = (1 << LIGHT_QUAD_SHIFT) - 1;

/// Corners closer than this, relative to the longer side, count as one (shared vertices of
/// an indexed mesh are bit-equal; this only forgives rounding in a file's fourth corner).
const CORNER_TOLERANCE: f64 = 1e-5;

/// One emissive triangle as the pairing sees it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Emitter {
    /// Index in BVH order.
    pub index: u32,
    pub positions: [Vec3; 3],
    pub material: u32,
    /// Face normal turned to the side the shading normals are on (the side `triangle_light_point`
    /// calls the front).
    pub facing: Vec3,
    /// Whether the emission is textured (then the quad's texture coordinates would be needed).
    pub textured: bool,
}

/// How a parallelogram's frame is built from its first triangle's vertices (a0, a1, a2):
/// c = a_k (the corner opposite the shared edge), p = a_(k+1), r = a_(k+2), S = p - c,
/// T = r - c; o = c + i S + j T, s = -+S, t = -+T (minus where i or j is set), swapped when
/// `swap`. Bits of `code`: 1 (a quad), k << 1, i << 3, j << 4, swap << 5.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QuadFrame {
    pub k: u32,
    pub i: bool,
    pub j: bool,
    pub swap: bool,
}

impl QuadFrame {
    /// The frame bits above `LIGHT_QUAD_SHIFT`.
    pub fn code(self) -> u32 {
        1 | self.k << 1
            | u32::from(self.i) << 3
            | u32::from(self.j) << 4
            | u32::from(self.swap) << 5
    }

    /// The frame of a `GpuLight::triangle`, if it is a parallelogram.
    pub fn of_light(triangle: u32) -> Option<Self> {
        let code = triangle >> LIGHT_QUAD_SHIFT & 63;
        (code & 1 != 0).then_some(QuadFrame {
            k: code >> 1 & 3,
            i: code & 8 != 0,
            j: code & 16 != 0,
            swap: code & 32 != 0,
        })
    }

    /// (o, s, t) from the first triangle as the GPU holds it, in the shader's operations
    /// (CPU twin of `triangle_light_point`'s quad branch).
    pub fn frame(self, t: &GpuTriangle) -> (Vec3, Vec3, Vec3) {
        let a = [t.v0, t.v0 + t.e1, t.v0 + t.e2];
        let k = self.k as usize;
        let (c, p, r) = (a[k], a[(k + 1) % 3], a[(k + 2) % 3]);
        let (big_s, big_t) = (p - c, r - c);
        let o =
            c + if self.i { big_s } else { Vec3::ZERO } + if self.j { big_t } else { Vec3::ZERO };
        let s = if self.i { -big_s } else { big_s };
        let tt = if self.j { -big_t } else { big_t };
        if self.swap { (o, tt, s) } else { (o, s, tt) }
    }

    /// The canonical frame of the parallelogram spanned at a_k of `a`: o is the corner first
    /// in (x, y, z) order, s leads to the neighbour of o first in that order.
    fn canonical(a: [Vec3; 3], k: usize) -> Self {
        let d = |v: Vec3| v.as_dvec3();
        let (c, p, r) = (d(a[k]), d(a[(k + 1) % 3]), d(a[(k + 2) % 3]));
        let (s, t) = (p - c, r - c);
        let corner = |i: bool, j: bool| {
            c + if i { s } else { DVec3::ZERO } + if j { t } else { DVec3::ZERO }
        };
        let mut best = (false, false);
        for ij in [(true, false), (false, true), (true, true)] {
            if lex(corner(ij.0, ij.1), corner(best.0, best.1)) == Ordering::Less {
                best = ij;
            }
        }
        let (i, j) = best;
        let o = corner(i, j);
        let ns = o + if i { -s } else { s };
        let nt = o + if j { -t } else { t };
        QuadFrame {
            k: k as u32,
            i,
            j,
            swap: lex(nt, ns) == Ordering::Less,
        }
    }
}

fn lex(a: DVec3, b: DVec3) -> Ordering {
    a.x.total_cmp(&b.x)
        .then(a.y.total_cmp(&b.y))
        .then(a.z.total_cmp(&b.z))
}

/// A light of the light list: one triangle, or two forming a parallelogram (the first is the
/// one whose index and frame `GpuLight::triangle` holds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Emissive {
    Triangle(usize),
    Quad(usize, usize, QuadFrame),
}

/// Pairs `emitters` (indices into it) into parallelograms where they form one, greedily in
/// order: each triangle takes the first unpaired partner over any of its edges.
pub(super) fn pair_emitters(emitters: &[Emitter]) -> Vec<Emissive> {
    let key = |e: &Emitter, k: usize| {
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        let (p, r) = (
            bits(e.positions[(k + 1) % 3]),
            bits(e.positions[(k + 2) % 3]),
        );
        (e.material, p.min(r), p.max(r))
    };
    let mut by_edge: HashMap<_, Vec<usize>> = HashMap::new();
    for (n, e) in emitters.iter().enumerate() {
        if e.textured || e.index > LIGHT_TRIANGLE_MASK {
            continue;
        }
        for k in 0..3 {
            by_edge.entry(key(e, k)).or_default().push(n);
        }
    }
    let mut paired = vec![false; emitters.len()];
    let mut out = Vec::with_capacity(emitters.len());
    for (n, e) in emitters.iter().enumerate() {
        if paired[n] {
            continue;
        }
        paired[n] = true;
        let partner = (0..3).find_map(|k| {
            let candidates = by_edge.get(&key(e, k))?;
            let m = *candidates
                .iter()
                .find(|&&m| !paired[m] && forms_parallelogram(e, k, &emitters[m]))?;
            Some((m, k))
        });
        out.push(match partner {
            Some((m, k)) => {
                paired[m] = true;
                Emissive::Quad(n, m, QuadFrame::canonical(e.positions, k))
            }
            None => Emissive::Triangle(n),
        });
    }
    out
}

/// Whether `b` completes `a` (whose edge opposite a_k it shares) to a parallelogram facing
/// the same way: b's third vertex is p + r - c.
fn forms_parallelogram(a: &Emitter, k: usize, b: &Emitter) -> bool {
    let d = |v: Vec3| v.as_dvec3();
    let (c, p, r) = (
        d(a.positions[k]),
        d(a.positions[(k + 1) % 3]),
        d(a.positions[(k + 2) % 3]),
    );
    let on_edge = |v: Vec3| v == a.positions[(k + 1) % 3] || v == a.positions[(k + 2) % 3];
    let Some(third) = b.positions.iter().find(|&&v| !on_edge(v)) else {
        return false;
    };
    let side = (p - c).length().max((r - c).length());
    let gap = (d(*third) - (p + r - c)).length();
    side > 0.0 && gap <= CORNER_TOLERANCE * side && a.facing.dot(b.facing) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn emitter(index: u32, positions: [Vec3; 3]) -> Emitter {
        Emitter {
            index,
            positions,
            material: 0,
            facing: Vec3::Y,
            textured: false,
        }
    }

    fn gpu(a: [Vec3; 3]) -> GpuTriangle {
        GpuTriangle {
            v0: a[0],
            e1: a[1] - a[0],
            e2: a[2] - a[0],
        }
    }

    /// The frame's four corners, o first.
    fn corners(a: [Vec3; 3], f: QuadFrame) -> [Vec3; 4] {
        let (o, s, t) = f.frame(&gpu(a));
        [o, o + s, o + t, o + s + t]
    }

    #[test]
    fn every_index_order_and_split_of_a_quad_gives_one_frame() {
        // Corners of a parallelogram (not a rectangle) in the xz plane.
        let q = [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(2.0, 1.0, 0.5),
            Vec3::new(2.5, 1.0, 1.5),
            Vec3::new(0.5, 1.0, 1.0),
        ];
        let tri = |i: [usize; 3]| i.map(|k| q[k]);
        // Both diagonals, each with the two files' orders and every rotation of each triangle.
        let splits = [
            ([0, 1, 2], [2, 3, 0]),
            ([0, 1, 2], [0, 2, 3]),
            ([1, 2, 3], [3, 0, 1]),
            ([3, 0, 1], [1, 2, 3]),
        ];
        let mut frames = Vec::new();
        for (a, b) in splits {
            for rot in 0..3 {
                let rotate = |t: [usize; 3]| [t[rot], t[(rot + 1) % 3], t[(rot + 2) % 3]];
                let es = [emitter(0, tri(rotate(a))), emitter(1, tri(b))];
                let lights = pair_emitters(&es);
                let [Emissive::Quad(0, 1, f)] = lights[..] else {
                    panic!("{a:?}/{b:?}: {lights:?}");
                };
                frames.push(corners(es[0].positions, f));
            }
        }
        for f in &frames {
            for (x, y) in f.iter().zip(&frames[0]) {
                assert!((*x - *y).length() < 1e-6, "{f:?} vs {:?}", frames[0]);
            }
        }
        // The frame spans the quad: o is a corner, o + s + t the opposite one.
        let f = frames[0];
        assert_eq!(f[0], q[0]);
        assert!((f[3] - q[2]).length() < 1e-6);
    }

    #[test]
    fn only_parallelograms_of_one_material_facing_one_way_pair() {
        let a = [Vec3::ZERO, Vec3::X, Vec3::Z];
        let square = [Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z];
        let kite = [Vec3::X, Vec3::new(1.5, 0.0, 1.5), Vec3::Z];
        let one = |b: Emitter| pair_emitters(&[emitter(0, a), b]).len();
        assert_eq!(one(emitter(1, square)), 1);
        assert_eq!(one(emitter(1, kite)), 2, "not a parallelogram");
        let other = Emitter {
            material: 1,
            ..emitter(1, square)
        };
        assert_eq!(one(other), 2, "another material");
        let flipped = Emitter {
            facing: Vec3::NEG_Y,
            ..emitter(1, square)
        };
        assert_eq!(one(flipped), 2, "facing the other way");
        let textured = Emitter {
            textured: true,
            ..emitter(1, square)
        };
        assert_eq!(one(textured), 2, "textured emission");
        // A strip of three: the first two pair, the third stays a triangle.
        let third = [Vec3::Z, Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, 0.0, 2.0)];
        let lights = pair_emitters(&[emitter(0, a), emitter(1, square), emitter(2, third)]);
        assert!(matches!(
            lights[..],
            [Emissive::Quad(0, 1, _), Emissive::Triangle(2)]
        ));
    }

    #[test]
    fn frame_bits_round_trip_below_the_params_bit() {
        for code in 0..48u32 {
            let f = QuadFrame {
                k: code % 3,
                i: code & 4 != 0,
                j: code & 8 != 0,
                swap: code & 16 != 0,
            };
            let light = LIGHT_TRIANGLE_MASK | f.code() << LIGHT_QUAD_SHIFT;
            assert_eq!(light & super::super::LIGHT_PARAMS_BIT, 0);
            assert_eq!(QuadFrame::of_light(light), Some(f));
            assert_eq!(light & LIGHT_TRIANGLE_MASK, LIGHT_TRIANGLE_MASK);
        }
        assert_eq!(QuadFrame::of_light(12345), None);
    }
}
