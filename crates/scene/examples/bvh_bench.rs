//! BVH build benchmark: `cargo run --release -p blueshift-scene --example bvh_bench [N]`.
//!
//! Builds the binned-SAH BVH over N (default 1 000 000) random small triangles and over a
//! tessellated "terrain" surface, prints build times, node count, depth and SAH cost, then
//! traces random rays through the first BVH and checks a sample against brute force.

use blueshift_scene::{Aabb, Bvh, GpuTriangle, Ray, closest_hit, closest_hit_brute_force};
use glam::Vec3;
use rayon::prelude::*;
use std::time::Instant;

struct Rng(u64);
impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.f32(), self.f32(), self.f32())
    }
}

/// Process CPU time (user + system) in seconds, from /proc (Linux); 0 elsewhere.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the ")" of the command name: state is field 3, utime 14, stime 15.
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|x| x.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}

fn report(name: &str, tris: &[[Vec3; 3]]) -> Bvh {
    // Warm-up build (thread pool start, page faults), then the timed best of 3.
    let _ = Bvh::build(&tris[..tris.len().min(10_000)]);
    let mut best = f64::INFINITY;
    let mut cpu = 0.0;
    let mut bvh = Bvh::default();
    for _ in 0..3 {
        let (t0, c0) = (Instant::now(), cpu_seconds());
        bvh = Bvh::build(tris);
        let dt = t0.elapsed().as_secs_f64();
        if dt < best {
            best = dt;
            cpu = cpu_seconds() - c0;
        }
    }
    let bounds: Vec<Aabb> = tris.iter().map(|t| Aabb::from_points(t)).collect();
    let valid = bvh.validate(&bounds);
    println!(
        "{name}: {} triangles, build {:.3} s wall / {:.2} s CPU (best of 3, {} threads), \
         {} nodes, depth {}, SAH cost {:.1}, valid: {:?}",
        tris.len(),
        best,
        cpu,
        rayon::current_num_threads(),
        bvh.nodes.len(),
        bvh.depth,
        bvh.sah_cost(),
        valid.map(|_| "yes")
    );
    bvh
}

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let soup: Vec<[Vec3; 3]> = (0..n)
        .map(|_| {
            let c = rng.vec3() * 100.0;
            let s = 0.5;
            [c + rng.vec3() * s, c + rng.vec3() * s, c + rng.vec3() * s]
        })
        .collect();
    let bvh = report("random soup", &soup);

    // A height-field surface: the typical "mesh" case (shared edges, uneven density).
    let side = ((n / 2) as f64).sqrt() as usize;
    let h = |x: usize, z: usize| {
        let (fx, fz) = (x as f32 * 0.05, z as f32 * 0.05);
        Vec3::new(x as f32, (fx.sin() * fz.cos()) * 20.0, z as f32)
    };
    let mut terrain = Vec::with_capacity(2 * side * side);
    for z in 0..side {
        for x in 0..side {
            terrain.push([h(x, z), h(x + 1, z), h(x + 1, z + 1)]);
            terrain.push([h(x, z), h(x + 1, z + 1), h(x, z + 1)]);
        }
    }
    report("terrain", &terrain);

    // Trace through the soup BVH.
    let tris: Vec<GpuTriangle> = bvh
        .order
        .iter()
        .map(|&i| {
            let p = soup[i as usize];
            GpuTriangle {
                v0: p[0],
                e1: p[1] - p[0],
                e2: p[2] - p[0],
            }
        })
        .collect();
    let rays: Vec<Ray> = (0..200_000)
        .map(|_| {
            let o = rng.vec3() * 100.0;
            let d = (rng.vec3() - 0.5).normalize_or(Vec3::X);
            Ray::new(o, d, 0.0, f32::MAX)
        })
        .collect();
    let t0 = Instant::now();
    let hits: Vec<_> = rays
        .par_iter()
        .map(|r| closest_hit(&bvh.nodes, &tris, r))
        .collect();
    let dt = t0.elapsed().as_secs_f64();
    println!(
        "traced {} rays in {:.3} s ({:.2} Mrays/s), {} hits",
        rays.len(),
        dt,
        rays.len() as f64 / dt / 1e6,
        hits.iter().flatten().count()
    );
    let mismatches = rays
        .iter()
        .zip(&hits)
        .take(50)
        .filter(|(r, h)| closest_hit_brute_force(&tris, r) != **h)
        .count();
    println!("brute-force check on 50 rays: {mismatches} mismatches");
}
