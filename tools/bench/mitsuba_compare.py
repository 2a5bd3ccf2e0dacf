#!/usr/bin/env python3
"""Blueshift vs Mitsuba 3 on the Cornell box: throughput and converged-image agreement.

Not run by the tests. Needs Mitsuba 3 (pip `mitsuba`, 3.9.1 / drjit 1.5.0 measured), numpy and
the `OpenEXR` module in the Python running this, and a release build of `blueshift`:

    python3 -m venv /root/.cache/peer/.venv-peer
    /root/.cache/peer/.venv-peer/bin/pip install mitsuba numpy OpenEXR
    apt-get install -y libllvm19   # Debian 12's default LLVM aborts drjit's llvm variant
    export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1
    cargo build --release -p blueshift
    /root/.cache/peer/.venv-peer/bin/python tools/bench/mitsuba_compare.py

Scene: Mitsuba's built-in `mi.cornell_box()` against Blueshift's bundled `cornell-box` preset,
which reproduces it (same walls, boxes, reflectances, one-sided area light of the same
radiance, camera at (0, 0, 3.9) with a 39.3077 degree field of view on the smaller axis).

Depth convention. Mitsuba's `max_depth` counts path segments including the camera ray:
1 = only directly visible emitters, 2 = direct illumination. Blueshift's `--bounces` counts
path vertices after the camera that scatter: 0 = only directly visible emitters, 1 = direct
illumination (the first hit's emission plus light sampled at that hit). So
`--bounces = max_depth - 1`: Mitsuba `max_depth 8` <-> Blueshift `--bounces 7`. The script
checks this on two low depths too (`--check-depths`).

Throughput: 512x512, box filter, 16 spp, one warm-up render and the
median of 3 timed renders for Mitsuba (llvm_ad_rgb); `blueshift bench` (one warm-up frame,
median of 3 frames, GPU-timestamp time of the trace pass, i.e. CPU wall time on lavapipe) with
the same settings. The two alternate A B A B and the script prints each run, the load average
and the process CPU time, then the ratio of the medians.

Agreement: both render the box at `--ref-size`^2 with `--ref-spp` samples per pixel
(Blueshift: the Owen-Sobol method, one frame of ref-spp samples, whose raw estimate the EXR
holds); the images are compared on 32x32-pixel block means: mean |A - B| over blocks and
channels, relative to the mean of B (goal < 1%). The image orientation is checked first (the
unflipped image must fit best).
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]


def loadavg():
    with open("/proc/loadavg") as f:
        return f.read().split()[0]


def find_blueshift(arg):
    if arg:
        return Path(arg)
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    return target / "release" / "blueshift"


def read_exr_rgb(path):
    import OpenEXR

    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        if "RGB" in ch:
            return np.asarray(ch["RGB"].pixels, dtype=np.float64)
        if "RGBA" in ch:
            return np.asarray(ch["RGBA"].pixels, dtype=np.float64)[..., :3]
        return np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in "RGB"], -1)


class Mitsuba:
    def __init__(self, variant):
        import drjit as dr
        import mitsuba as mi

        mi.set_variant(variant)
        self.mi, self.dr = mi, dr
        self.variant = variant

    def scene(self, size, spp, max_depth):
        mi = self.mi
        d = mi.cornell_box()
        d["sensor"]["film"] = {
            "type": "hdrfilm",
            "width": size,
            "height": size,
            "rfilter": {"type": "box"},
            "pixel_format": "rgb",
            "component_format": "float32",
        }
        d["sensor"]["sampler"] = {"type": "independent", "sample_count": spp}
        d["integrator"] = {"type": "path", "max_depth": max_depth}
        return mi.load_dict(d)

    def render(self, scene, spp, seed=0):
        """(image as HxWx3 float64, wall seconds)."""
        t = time.perf_counter()
        img = self.mi.render(scene, spp=spp, seed=seed)
        self.dr.eval(img)
        self.dr.sync_thread()
        t = time.perf_counter() - t
        return np.array(img, dtype=np.float64), t

    def render_chunked(self, scene, size, spp, chunk):
        """Mean of renders of `chunk` spp each (bounded memory for high spp)."""
        acc, n, seed = np.zeros((size, size, 3)), 0, 0
        while n < spp:
            k = min(chunk, spp - n)
            img, _ = self.render(scene, k, seed=seed)
            acc += img * k
            n += k
            seed += 1
        return acc / spp


def cpu_seconds():
    t = os.times()
    return t.children_user + t.children_system


def blueshift_bench(exe, size, spp, bounces, method, frames=3):
    """(median trace ms, Msamples/s, CPU seconds of the process)."""
    cmd = [str(exe), "bench", "--scene", "cornell-box", "--width", str(size), "--height",
           str(size), "--spp", str(spp), "--bounces", str(bounces), "--method", method,
           "--frames", str(frames)]
    c0 = cpu_seconds()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True,
                         env={**os.environ, "XDG_RUNTIME_DIR": os.environ.get("XDG_RUNTIME_DIR", "/tmp")}).stdout
    cpu = cpu_seconds() - c0
    line = next(l for l in out.splitlines() if l.startswith("trace median"))
    ms = float(line.split()[2])
    return ms, size * size * spp / ms / 1e3, cpu


def blueshift_render(exe, size, spp, bounces, out_dir):
    """Linear image of one frame of `spp` Owen-Sobol samples (the raw estimate)."""
    cmd = [str(exe), "render", "--scene", "cornell-box", "--width", str(size), "--height",
           str(size), "--spp", str(spp), "--bounces", str(bounces), "--method", "sobol",
           "--frames", "1", "--out", str(out_dir)]
    subprocess.run(cmd, check=True, capture_output=True, text=True,
                   env={**os.environ, "XDG_RUNTIME_DIR": os.environ.get("XDG_RUNTIME_DIR", "/tmp")})
    return read_exr_rgb(Path(out_dir) / "frame_00000.exr")


def block_means(img, block=32):
    h, w, c = img.shape
    h, w = h - h % block, w - w % block
    return img[:h, :w].reshape(h // block, block, w // block, block, c).mean(axis=(1, 3))


def block_difference(a, b, block=32):
    """Mean |block means of a - block means of b| over blocks and channels / mean of b."""
    ba, bb = block_means(a, block), block_means(b, block)
    return float(np.abs(ba - bb).mean() / bb.mean()), ba, bb


def throughput(args, mit, exe):
    size, spp, depth = args.size, args.spp, args.max_depth
    bounces = depth - 1
    print(f"\n== Throughput: cornell box {size}x{size}, box filter, {spp} spp, Mitsuba "
          f"max_depth {depth} <-> Blueshift --bounces {bounces} (method {args.method})")
    scene = mit.scene(size, spp, depth)
    _, t = mit.render(scene, spp)  # warm-up (JIT compilation, cached in ~/.drjit)
    print(f"  mitsuba warm-up {t:.3f} s")
    mi_runs, bs_runs = [], []
    for rnd in range(args.rounds):
        c0 = time.process_time()
        times = [mit.render(scene, spp, seed=rnd * 10 + i)[1] for i in range(3)]
        cpu = time.process_time() - c0
        med = statistics.median(times)
        mi_runs.append(size * size * spp / med / 1e6)
        print(f"  A mitsuba {mit.variant}: renders {', '.join(f'{x:.3f}' for x in times)} s, "
              f"median {med:.3f} s = {mi_runs[-1]:.3f} Msamples/s (cpu {cpu:.1f} s, load {loadavg()})")
        ms, msps, cpu = blueshift_bench(exe, size, spp, bounces, args.method)
        bs_runs.append(msps)
        print(f"  B blueshift bench: trace median {ms:.1f} ms = {msps:.3f} Msamples/s "
              f"(process cpu {cpu:.1f} s, load {loadavg()})")
    mi_med, bs_med = statistics.median(mi_runs), statistics.median(bs_runs)
    print(f"  median: mitsuba {mi_med:.3f} Msamples/s, blueshift {bs_med:.3f} Msamples/s; "
          f"blueshift / mitsuba = {bs_med / mi_med:.3f} (mitsuba is {mi_med / bs_med:.2f}x faster)")
    return mi_med, bs_med


def agreement(args, mit, exe, tmp):
    size, spp, depth = args.ref_size, args.ref_spp, args.max_depth
    print(f"\n== Agreement: {size}x{size}, {spp} spp each, max_depth {depth} / --bounces {depth - 1}")
    t = time.perf_counter()
    ref = mit.render_chunked(mit.scene(size, min(spp, args.chunk), depth), size, spp, args.chunk)
    print(f"  mitsuba: {time.perf_counter() - t:.0f} s, mean rgb {ref.reshape(-1, 3).mean(0)}")
    t = time.perf_counter()
    ours = blueshift_render(exe, size, spp, depth - 1, Path(tmp) / "agree")
    print(f"  blueshift: {time.perf_counter() - t:.0f} s, mean rgb {ours.reshape(-1, 3).mean(0)}")
    if args.save:
        np.save(Path(args.save) / "mitsuba.npy", ref)
        np.save(Path(args.save) / "blueshift.npy", ours)
    fits = {name: block_difference(f(ours), ref)[0] for name, f in [
        ("as is", lambda x: x), ("flipped left-right", lambda x: x[:, ::-1]),
        ("flipped up-down", lambda x: x[::-1])]}
    for name, d in fits.items():
        print(f"  orientation {name}: block difference {100 * d:.2f}%")
    best = min(fits, key=fits.get)
    if best != "as is":
        print(f"  WARNING: the images fit best {best}")
    d, ba, bb = block_difference(ours, ref)
    ratio = ours.reshape(-1, 3).mean(0) / ref.reshape(-1, 3).mean(0)
    signed = float((ba - bb).mean() / bb.mean())
    print(f"  32x32 block means: mean |blueshift - mitsuba| / mean(mitsuba) = {100 * d:.3f}% "
          f"(goal < 1%); signed mean difference {100 * signed:+.3f}%; "
          f"mean ratio per channel {np.array2string(ratio, precision=4)}")
    # Noise floor: the same comparison between two halves of the Mitsuba budget.
    if args.noise_floor:
        half = max(spp // 2, 1)
        a = mit.render_chunked(mit.scene(size, min(half, args.chunk), depth), size, half, args.chunk)
        print(f"  noise floor (mitsuba {half} spp vs {spp} spp): "
              f"{100 * block_difference(a, ref)[0]:.3f}%")
    return d


def depth_check(args, mit, exe, tmp):
    """Means of both renderers at low depths: they agree only if the conventions match."""
    print("\n== Depth convention (mean radiance, 64x64, 256 spp)")
    for depth in (1, 2, 3):
        ref = mit.render_chunked(mit.scene(64, 256, depth), 64, 256, 256).reshape(-1, 3).mean(0)
        row = []
        for b in (depth - 2, depth - 1, depth):
            if b < 0:
                continue
            ours = blueshift_render(exe, 64, 256, b, Path(tmp) / f"depth{b}").reshape(-1, 3).mean(0)
            row.append(f"--bounces {b}: {np.array2string(ours / ref, precision=3)}")
        print(f"  mitsuba max_depth {depth}: blueshift/mitsuba mean ratio " + "; ".join(row))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--blueshift", help="blueshift binary (default: $CARGO_TARGET_DIR or target/, release)")
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--max-depth", type=int, default=8, help="Mitsuba max_depth (bounces = this - 1)")
    p.add_argument("--method", default="white", help="blueshift bench method (white = independent)")
    p.add_argument("--rounds", type=int, default=2, help="A B rounds of the throughput comparison")
    p.add_argument("--ref-size", type=int, default=256)
    p.add_argument("--ref-spp", type=int, default=1024)
    p.add_argument("--chunk", type=int, default=256, help="Mitsuba spp per render call")
    p.add_argument("--skip-throughput", action="store_true")
    p.add_argument("--skip-agreement", action="store_true")
    p.add_argument("--check-depths", action="store_true")
    p.add_argument("--noise-floor", action="store_true")
    p.add_argument("--save", help="directory for the two agreement images (.npy)")
    args = p.parse_args()

    exe = find_blueshift(args.blueshift)
    if not exe.exists():
        sys.exit(f"no blueshift binary at {exe} (cargo build --release -p blueshift, or --blueshift)")
    mit = Mitsuba(args.variant)
    import mitsuba

    print(f"mitsuba {mitsuba.__version__} ({args.variant}), blueshift {exe}, "
          f"{os.cpu_count()} CPUs, load {loadavg()}")
    with tempfile.TemporaryDirectory() as tmp:
        if args.check_depths:
            depth_check(args, mit, exe, tmp)
        if not args.skip_throughput:
            throughput(args, mit, exe)
        if not args.skip_agreement:
            agreement(args, mit, exe, tmp)


if __name__ == "__main__":
    main()
