#!/usr/bin/env python3
"""Random rooms for RAE training data: each seed writes one fovrt scene (TOML + OBJ + MTL + PNG).

The built-in training scenes are four, all lit directly; the held-out veach-ajar is lit through a
door, so that 95 % of its 1-spp pixels are black, and the network trained on the four loses 86 %
of its energy there (training/README.md). Each scene here is a closed room with random size, wall
colours, checker-textured floor, 3-8 boxes of random diffuse, glossy or metal material (one of them
moving), a camera dolly, and one of three lightings:
  ceiling  an emissive ceiling panel of random colour temperature, often in view
  ajar     a partition wall with a door gap; the only light is behind it (indirect lighting)
  spots    one or two coloured spot lights and a dim ceiling panel
Everything is drawn from random.Random(seed): the same seed writes the same files.

  python3 training/procedural_scenes.py --out out/procedural --seeds 1-8
  fovrt dataset ... --scenes cornell,pillars,room,box,out/procedural/proc-0001/scene.toml,...
"""
import argparse
import colorsys
import math
import os
import random
import struct
import zlib


def write_png(path, rgb_rows):
    """8-bit RGB PNG from rows of (r, g, b) tuples."""
    h, w = len(rgb_rows), len(rgb_rows[0])
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rgb_rows)

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


class Obj:
    """An OBJ being written: quads, each with its material."""

    def __init__(self, mtllib):
        self.lines = [f"mtllib {mtllib}"]
        self.n = 0

    def quad(self, material, corners, uv=False):
        self.lines.append(f"usemtl {material}")
        for x, y, z in corners:
            self.lines.append(f"v {x:.4f} {y:.4f} {z:.4f}")
        if uv:
            for u, v in ((0, 0), (uv, 0), (uv, uv), (0, uv)):
                self.lines.append(f"vt {u:.4f} {v:.4f}")
            i = self.n
            self.lines.append("f " + " ".join(f"{i + k + 1}/{i + k + 1}" for k in range(4)))
        else:
            self.lines.append("f " + " ".join(str(self.n + k + 1) for k in range(4)))
        self.n += 4

    def box(self, material, lo, hi, yaw=0.0):
        """An axis-aligned box turned by `yaw` degrees about its vertical centre line, faces outwards."""
        cx, cz = (lo[0] + hi[0]) / 2, (lo[2] + hi[2]) / 2
        c, s = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))

        def p(x, y, z):
            dx, dz = x - cx, z - cz
            return (cx + c * dx + s * dz, y, cz - s * dx + c * dz)

        (x0, y0, z0), (x1, y1, z1) = lo, hi
        for quad in (((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)),   # +z
                     ((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)),   # -z
                     ((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)),   # -x
                     ((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)),   # +x
                     ((x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)),   # +y
                     ((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))):  # -y
            self.quad(material, [p(*v) for v in quad])

    def text(self):
        return "\n".join(self.lines) + "\n"


def random_colour(rng, saturation=(0.0, 0.9), value=(0.2, 0.85)):
    r, g, b = colorsys.hsv_to_rgb(rng.random(), rng.uniform(*saturation), rng.uniform(*value))
    return (r, g, b)


def light_colour(rng):
    """A warm-to-cool white (roughly 2700-9000 K) or, one time in five, a saturated hue."""
    if rng.random() < 0.2:
        return random_colour(rng, (0.4, 0.8), (1.0, 1.0))
    t = rng.random()
    return (1.0, 0.75 + 0.25 * t, 0.45 + 0.55 * t)


def fmt3(v):
    return "[" + ", ".join(f"{x:.4f}" for x in v) + "]"


def make_scene(seed, folder):
    rng = random.Random(seed)
    os.makedirs(folder, exist_ok=True)
    name = f"proc-{seed:04d}"
    W, D, H = rng.uniform(3.5, 7.0), rng.uniform(4.0, 7.0), rng.uniform(2.4, 3.4)
    lighting = rng.choice(["ceiling", "ajar", "ajar", "spots"])  # ajar twice: the held-out kind
    mtl = []

    def material(mname, kd, ks=(0, 0, 0), ns=10.0, ke=None, texture=None):
        mtl.append(f"newmtl {mname}")
        mtl.append("Kd " + " ".join(f"{c:.4f}" for c in kd))
        mtl.append("Ks " + " ".join(f"{c:.4f}" for c in ks))
        mtl.append(f"Ns {ns:.1f}")
        if ke:
            mtl.append("Ke " + " ".join(f"{c:.4f}" for c in ke))
        if texture:
            mtl.append(f"map_Kd {texture}")
        mtl.append("")

    # The room: walls of random colours (mostly pale), a checker floor.
    cells, a, b = rng.choice([4, 8, 16]), random_colour(rng, (0, 0.6)), random_colour(rng, (0, 0.6))
    size = 64
    rows = [[tuple(int(255 * c) for c in (a if ((x * cells // size) + (y * cells // size)) % 2 else b))
             for x in range(size)] for y in range(size)]
    write_png(os.path.join(folder, "floor.png"), rows)
    material("floor", (1, 1, 1), ns=rng.choice([10, 50, 200]), texture="floor.png")
    for k in range(4):
        material(f"wall{k}", random_colour(rng, (0, 0.7) if k == 0 else (0, 0.35), (0.4, 0.85)))
    material("ceiling", random_colour(rng, (0, 0.15), (0.6, 0.85)))
    room = Obj("scene.mtl")
    x0, x1, z0, z1 = -W / 2, W / 2, -D, 0.0
    room.quad("floor", [(x0, 0, z1), (x1, 0, z1), (x1, 0, z0), (x0, 0, z0)], uv=max(1, round(W)))
    room.quad("ceiling", [(x0, H, z0), (x1, H, z0), (x1, H, z1), (x0, H, z1)])
    room.quad("wall0", [(x0, 0, z0), (x1, 0, z0), (x1, H, z0), (x0, H, z0)])  # back, facing +z
    room.quad("wall1", [(x0, 0, z1), (x0, 0, z0), (x0, H, z0), (x0, H, z1)])  # left
    room.quad("wall2", [(x1, 0, z0), (x1, 0, z1), (x1, H, z1), (x1, H, z0)])  # right
    room.quad("wall3", [(x1, 0, z1), (x0, 0, z1), (x0, H, z1), (x1, H, z1)])  # front, behind the camera

    lights = []
    front = z0  # the lit part of the room starts here (ajar: at the partition)
    if lighting == "ajar":
        # A partition 1-1.5 m in front of the back wall with a door gap; the light is behind it.
        zp = z0 + rng.uniform(1.0, 1.5)
        gap, gx = rng.uniform(0.4, 1.1), rng.uniform(x0 + 0.8, x1 - 1.6)
        material("partition", random_colour(rng, (0, 0.3), (0.5, 0.8)))
        for a_, b_ in ((x0, gx), (gx + gap, x1)):
            room.box("partition", (a_, 0, zp - 0.05), (b_, H, zp + 0.05))
        room.box("partition", (gx, 2.0, zp - 0.05), (gx + gap, H, zp + 0.05))  # lintel
        ke = [c * rng.uniform(40, 200) for c in light_colour(rng)]
        material("light", (0.8, 0.8, 0.8), ke=ke)
        lx, lw = rng.uniform(x0 + 0.3, x1 - 1.3), rng.uniform(0.4, 1.0)
        room.quad("light", [(lx, H - 0.01, z0 + 0.2), (lx + lw, H - 0.01, z0 + 0.2),
                            (lx + lw, H - 0.01, z0 + 0.6), (lx, H - 0.01, z0 + 0.6)])
        front = zp
    else:
        ke = [c * rng.uniform(6, 30) for c in light_colour(rng)]
        if lighting == "spots":
            ke = [c * 0.15 for c in ke]
        material("light", (0.8, 0.8, 0.8), ke=ke)
        lw, ld = rng.uniform(0.4, 1.2), rng.uniform(0.3, 0.8)
        lx, lz = rng.uniform(x0 + 0.3, x1 - lw - 0.3), rng.uniform(z0 + 0.5, z1 - ld - 1.5)
        room.quad("light", [(lx, H - 0.01, lz), (lx + lw, H - 0.01, lz), (lx + lw, H - 0.01, lz + ld),
                            (lx, H - 0.01, lz + ld)])
        if lighting == "spots":
            for k in range(rng.randint(1, 2)):
                px, pz = rng.uniform(x0 + 0.3, x1 - 0.3), rng.uniform(front + 0.3, -1.0)
                tx, tz = rng.uniform(x0 + 0.5, x1 - 0.5), rng.uniform(front + 0.5, -1.5)
                lights.append(f"[[light]]\nname = \"spot{k}\"\ntype = \"spot\"\n"
                              f"color = {fmt3(random_colour(rng, (0.2, 0.9), (1, 1)))}\n"
                              f"intensity = {rng.uniform(3, 12):.2f}\n"
                              f"position = {fmt3((px, H - 0.1, pz))}\ntarget = {fmt3((tx, 0, tz))}\n"
                              f"inner_degrees = {rng.uniform(10, 25):.1f}\nouter_degrees = {rng.uniform(27, 40):.1f}\n")

    # Boxes on the floor of the lit part: diffuse, glossy dielectric or metal.
    for k in range(rng.randint(3, 8)):
        kind = rng.choice(["diffuse", "diffuse", "glossy", "metal"])
        if kind == "metal":
            material(f"box{k}", (0.02, 0.02, 0.02), random_colour(rng, (0, 0.6), (0.6, 0.95)),
                     ns=rng.choice([20, 100, 400]))
        elif kind == "glossy":
            material(f"box{k}", random_colour(rng), (0.04, 0.04, 0.04), ns=rng.choice([50, 200, 1000]))
        else:
            material(f"box{k}", random_colour(rng))
        sx, sy, sz = rng.uniform(0.2, 0.9), rng.uniform(0.2, 1.4), rng.uniform(0.2, 0.9)
        cx, cz = rng.uniform(x0 + 0.6, x1 - 0.6), rng.uniform(front + 0.6, -2.0)
        room.box(f"box{k}", (cx - sx / 2, 0, cz - sz / 2), (cx + sx / 2, sy, cz + sz / 2), rng.uniform(0, 90))
    with open(os.path.join(folder, "room.obj"), "w") as f:
        f.write(room.text())

    # One moving box (its own OBJ: an instance with keys).
    material("mover", random_colour(rng, (0.3, 0.9), (0.4, 0.9)))
    mover = Obj("scene.mtl")
    mover.box("mover", (-0.5, 0, -0.5), (0.5, 1, 0.5))
    with open(os.path.join(folder, "mover.obj"), "w") as f:
        f.write(mover.text())
    with open(os.path.join(folder, "scene.mtl"), "w") as f:
        f.write("\n".join(mtl))
    m0 = (rng.uniform(x0 + 0.7, x1 - 0.7), 0.0, rng.uniform(front + 0.7, -2.2))
    m1 = (rng.uniform(x0 + 0.7, x1 - 0.7), 0.0, rng.uniform(front + 0.7, -2.2))
    ms = rng.uniform(0.3, 0.6)

    # Camera: a dolly between two points near the front wall, looking into the room.
    def eye():
        return (rng.uniform(x0 + 0.5, x1 - 0.5), rng.uniform(1.2, min(2.0, H - 0.3)), rng.uniform(-1.0, -0.3))

    def target():
        return (rng.uniform(x0 + 1.0, x1 - 1.0), rng.uniform(0.3, 1.5), rng.uniform(z0 + 0.5, front + 1.5))

    e0, e1, t0, t1 = eye(), eye(), target(), target()
    toml = f"""# Procedural training room {seed} ({lighting} lighting): training/procedural_scenes.py --seeds {seed}
name = "{name}"
frame_rate = 30
background = [0, 0, 0]
fov = {rng.uniform(50, 90):.1f}

[camera]
keys = [
  {{ time = 0, position = {fmt3(e0)}, target = {fmt3(t0)} }},
  {{ time = 8, position = {fmt3(e1)}, target = {fmt3(t1)} }},
]

[[mesh]]
name = "room"
file = "room.obj"

[[mesh]]
name = "mover"
file = "mover.obj"
scale = {ms:.3f}
keys = [
  {{ time = 0, translate = {fmt3(m0)}, rotate = [0, 0, 0] }},
  {{ time = 4, translate = {fmt3(m1)}, rotate = [0, {rng.uniform(30, 180):.1f}, 0] }},
]

""" + "\n".join(lights)
    with open(os.path.join(folder, "scene.toml"), "w") as f:
        f.write(toml)
    return name, lighting


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        a, _, b = part.partition("-")
        seeds += list(range(int(a), int(b or a) + 1))
    return seeds


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, help="one folder proc-NNNN per seed is written here")
    ap.add_argument("--seeds", default="1-8", help="e.g. 1-8 or 1,5,9")
    args = ap.parse_args()
    paths = []
    for seed in parse_seeds(args.seeds):
        folder = os.path.join(args.out, f"proc-{seed:04d}")
        name, lighting = make_scene(seed, folder)
        paths.append(os.path.join(folder, "scene.toml"))
        print(f"{name}: {lighting}")
    print("scenes: " + ",".join(paths))


if __name__ == "__main__":
    main()
