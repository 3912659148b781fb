#!/usr/bin/env python3
"""Times `fovrt vdp` against the FovVideoVDP reference implementation on the same frames.

The reference (gfxdisp/FovVideoVDP, licence CC BY-NC 4.0) is not part of fovrt: pass a checkout
of it with --reference-dir (it runs under Debian's python3-torch / python3-scipy /
python3-imageio; the two modules it imports but does not need for arrays, `ffmpeg` and
`imageio.v2`, are stubbed here). Frames: the golden cases' pattern (tests/vdp_golden_cases.h)
with uniform noise, written as 8-bit grey PNG folders; both metrics read the same 8-bit values,
sRGB EOTF, 100 cd/m² peak, 0.1 cd/m² black, 20 pixels per degree, foveated at a fixed gaze.
Sizes (--sizes, WxHxFRAMES): the issue's range, 320×180 to a headset eye's 2064×2208, each timed
for both (the reference on fewer frames where it takes minutes a frame), and 1280×720 × 60 for
fovrt alone (its CPU-seconds per frame end to end); a size given as WxHxFRAMES! is fovrt's only.

    /usr/bin/python3 scripts/bench-vdp.py --fovrt build/src/app/fovrt --reference-dir /path/to/FovVideoVDP
"""
import argparse, math, os, resource, subprocess, sys, tempfile, time, types
import numpy as np
import imageio


def frames(w, h, n, seed):
    y, x = np.mgrid[0:h, 0:w].astype(np.float64)
    rng = np.random.default_rng(seed)
    ref, test = [], []
    for f in range(n):
        X = x + f
        chk = np.where((np.floor(X / 16) + np.floor(y / 16)) % 2 == 0, 1.0, -1.0)
        r = 0.45 + 0.2 * np.sin(2 * np.pi * X / 13.0) * np.cos(2 * np.pi * y / 9.0) + 0.15 * chk
        t = np.clip(r + 0.05 * (rng.random((h, w)) - 0.5), 0, 1)
        ref.append(np.round(r * 255).astype(np.uint8))
        test.append(np.round(t * 255).astype(np.uint8))
    return test, ref


def write(folder, images):
    os.makedirs(folder, exist_ok=True)
    for i, im in enumerate(images):
        imageio.imwrite(os.path.join(folder, f"{i:04d}.png"), im)


def time_fovrt(fovrt, d, n, gaze, repeats):
    cmd = [fovrt, "vdp", f"{d}/test", f"{d}/ref", "--fps", "30", "--ppd", "20", "--peak", "100",
           "--black", "0.1", "--eotf", "srgb", "--gaze", gaze]
    best, cpu, out = math.inf, math.inf, ""
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        best = min(best, time.perf_counter() - t0)
        cpu = min(cpu, c1.ru_utime + c1.ru_stime - c0.ru_utime - c0.ru_stime)
    return best, cpu, out.split("\n")[0], " ".join(cmd)


def time_reference(ref_dir, test, ref, fix, repeats):
    sys.modules["ffmpeg"] = types.ModuleType("ffmpeg")
    sys.modules["imageio.v2"] = imageio
    imageio.v2 = imageio
    sys.path.insert(0, ref_dir)
    import torch, pyfvvdp
    from pyfvvdp.fvvdp_display_model import fvvdp_display_photo_eotf, fvvdp_display_geometry
    torch.set_num_threads(os.cpu_count())
    h, w = ref[0].shape
    geom = fvvdp_display_geometry((w, h), fov_horizontal=2 * math.degrees(math.atan(w * math.tan(math.radians(0.5 / 20)))))
    m = pyfvvdp.fvvdp(display_photometry=fvvdp_display_photo_eotf(100, contrast=1000, EOTF="sRGB", E_ambient=0),
                      display_geometry=geom, foveated=True, quiet=True, device=torch.device("cpu"))
    T = np.stack(test).astype(np.float32) / 255
    R = np.stack(ref).astype(np.float32) / 255
    best, cpu, q = math.inf, math.inf, None
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        with torch.no_grad():
            q, _ = m.predict(T, R, dim_order="FHW", frames_per_second=30, fixation_point=torch.tensor(fix))
        best = min(best, time.perf_counter() - t0)
        cpu = min(cpu, time.process_time() - c0)
    return best, cpu, float(q)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fovrt", required=True)
    ap.add_argument("--reference-dir", help="checkout of gfxdisp/FovVideoVDP (omit to time fovrt only)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sizes", default="320x180x30,1280x720x8,2064x2208x4,1280x720x60!",
                    help="comma-separated WxHxFRAMES; a trailing ! times fovrt alone")
    a = ap.parse_args()
    cpu = [l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")]
    print(f"CPU: {cpu[0]} x {len(cpu)} logical cores; load average {os.getloadavg()[0]:.1f}; best of {a.repeats}")
    with tempfile.TemporaryDirectory() as tmp:
        for size in a.sizes.split(","):
            with_ref = not size.endswith("!")
            w, h, n = (int(v) for v in size.rstrip("!").split("x"))
            d = f"{tmp}/{w}x{h}x{n}"
            test, ref = frames(w, h, n, 1)
            write(f"{d}/test", test)
            write(f"{d}/ref", ref)
            fix = [w * 0.3, h * 0.4]
            with open(f"{d}/gaze.csv", "w") as g:
                g.write("frame,x,y\n")
                g.writelines(f"{f},{fix[0]},{fix[1]}\n" for f in range(n))
            secs, cpu, line, cmd = time_fovrt(a.fovrt, d, n, f"{d}/gaze.csv", a.repeats)
            print(f"{w}x{h} x {n} frames, fovrt vdp (incl. PNG reading): {secs:.2f} s wall, {cpu:.2f} s CPU "
                  f"({cpu / n:.4f} per frame)  [{line}]  load {os.getloadavg()[0]:.1f}")
            print(f"  command: {cmd}")
            if with_ref and a.reference_dir:
                rs, rcpu, rq = time_reference(a.reference_dir, test, ref, fix, a.repeats)
                print(f"{w}x{h} x {n} frames, reference (arrays in memory): {rs:.2f} s wall, {rcpu:.2f} s CPU  [{rq:.4f} JOD]"
                      f"  -> fovrt {rs / secs:.1f}x faster (wall), {rcpu / cpu:.1f}x less CPU  load {os.getloadavg()[0]:.1f}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
