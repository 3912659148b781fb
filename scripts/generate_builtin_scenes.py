import math, struct, zlib, os
# Regenerates the small OBJ/MTL files and checker.png of the built-in scenes in scenes/.
# Usage: python3 scripts/generate_builtin_scenes.py
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'scenes')

def quad(vs, a, b, c, d):
    """Append a quad (counter-clockwise seen from the side it faces)."""
    base = len(vs) + 1
    vs.extend([a, b, c, d])
    return (base, base + 1, base + 2, base + 3)

def write_obj(name, header, groups, mtllib, uv_groups=()):
    # groups: list of (group name, material, [quads as 4 points])
    lines = [f'# {header}', f'mtllib {mtllib}']
    vi = 1
    vti = 1
    for gname, mat, quads in groups:
        lines.append(f'o {gname}')
        lines.append(f'usemtl {mat}')
        for q in quads:
            for p in q:
                lines.append('v {:.4f} {:.4f} {:.4f}'.format(*p))
            if gname in uv_groups:
                reps = uv_groups[gname]
                for uv in [(0, 0), (reps, 0), (reps, reps), (0, reps)]:
                    lines.append('vt {:.3f} {:.3f}'.format(*uv))
                lines.append('f ' + ' '.join(f'{vi + k}/{vti + k}' for k in range(4)))
                vti += 4
            else:
                lines.append(f'f {vi} {vi + 1} {vi + 2} {vi + 3}')
            vi += 4
    open(os.path.join(out, name), 'w').write('\n'.join(lines) + '\n')

def box_room(x0, x1, y0, y1, z0, z1, front=False):
    """Inward-facing quads of an axis-aligned room."""
    floor = [(x0, y0, z1), (x1, y0, z1), (x1, y0, z0), (x0, y0, z0)]
    ceiling = [(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)]
    back = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)]
    left = [(x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1)]
    right = [(x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0)]
    frontq = [(x1, y0, z1), (x0, y0, z1), (x0, y1, z1), (x1, y1, z1)]
    return floor, ceiling, back, left, right, frontq

# --- cube.obj: unit cube, x,z in [-0.5, 0.5], y in [0, 1], outward faces
c = [(-0.5, 0, 0.5), (0.5, 0, 0.5), (0.5, 1, 0.5), (-0.5, 1, 0.5),
     (-0.5, 0, -0.5), (0.5, 0, -0.5), (0.5, 1, -0.5), (-0.5, 1, -0.5)]
faces = [(0, 1, 2, 3), (5, 4, 7, 6), (4, 0, 3, 7), (1, 5, 6, 2), (3, 2, 6, 7), (4, 5, 1, 0)]
write_obj('cube.obj', 'fovrt unit cube (x, z in [-0.5, 0.5], y in [0, 1]); scale/translate it in the scene file',
          [('cube', 'cube_white', [[c[i] for i in f] for f in faces])], 'cube.mtl')
open(os.path.join(out, 'cube.mtl'), 'w').write('# fovrt: white diffuse for cube.obj\nnewmtl cube_white\nKd 0.75 0.75 0.75\nKs 0 0 0\nNs 10\n')

# --- cornell_room.obj: 2 m Cornell box (x in [-1, 1], y in [0, 2], z in [-1, 1]), open at +z
floor, ceiling, back, left, right, _ = box_room(-1, 1, 0, 2, -1, 1)
light = [(-0.25, 1.98, -0.2), (0.25, 1.98, -0.2), (0.25, 1.98, 0.2), (-0.25, 1.98, 0.2)]
write_obj('cornell_room.obj', 'fovrt Cornell box room: 2 m cube open towards +z, ceiling light 0.5 x 0.4 m',
          [('floor', 'white', [floor]), ('ceiling', 'white', [ceiling]), ('back', 'white', [back]),
           ('left', 'red', [left]), ('right', 'green', [right]), ('light', 'light', [light])], 'cornell_room.mtl')
open(os.path.join(out, 'cornell_room.mtl'), 'w').write('''# fovrt Cornell box materials (diffuse; light radiance in W/(m^2 sr))
newmtl white
Kd 0.73 0.71 0.68
Ks 0 0 0
Ns 10

newmtl red
Kd 0.63 0.065 0.05
Ks 0 0 0
Ns 10

newmtl green
Kd 0.14 0.45 0.091
Ks 0 0 0
Ns 10

newmtl light
Kd 0.78 0.78 0.78
Ks 0 0 0
Ke 17 12 4
''')

# --- pillars: floor + backdrop, a large tilted area light
floor = [(-5, 0, 5), (5, 0, 5), (5, 0, -5), (-5, 0, -5)]
backdrop = [(-5, 0, -4), (5, 0, -4), (5, 4, -4), (-5, 4, -4)]
write_obj('pillars_stage.obj', 'fovrt pillars stage: 10 x 10 m floor and a backdrop wall at z = -4',
          [('floor', 'stage_floor', [floor]), ('backdrop', 'stage_wall', [backdrop])], 'pillars_stage.mtl')
open(os.path.join(out, 'pillars_stage.mtl'), 'w').write('''# fovrt pillars stage materials
newmtl stage_floor
Kd 0.7 0.7 0.7
Ks 0 0 0
Ns 10

newmtl stage_wall
Kd 0.4 0.45 0.5
Ks 0 0 0
Ns 10
''')
# 1.6 m x 1 m panel centred at (0, 2.4, -3), facing down and towards +z (normal (0, -0.6, 0.8)).
n = (0, -0.6, 0.8)
u = (1, 0, 0)
v = (0, 0.8, 0.6)  # in-plane, perpendicular to u and n
cx = (0, 2.4, -3)
def P(a, b):
    return tuple(cx[i] + a * u[i] + b * v[i] for i in range(3))
panel = [P(-0.8, 0.5), P(0.8, 0.5), P(0.8, -0.5), P(-0.8, -0.5)]
# orientation check: (b-a) x (c-a) must point along n
a, b, cc = panel[0], panel[1], panel[2]
e1 = [b[i] - a[i] for i in range(3)]; e2 = [cc[i] - a[i] for i in range(3)]
cr = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
if sum(cr[i] * n[i] for i in range(3)) < 0:
    panel = panel[::-1]
write_obj('pillars_light.obj', 'fovrt pillars area light: 1.6 x 1 m panel above and behind the pillars',
          [('panel', 'panel_light', [panel])], 'pillars_light.mtl')
open(os.path.join(out, 'pillars_light.mtl'), 'w').write('newmtl panel_light\nKd 0 0 0\nKs 0 0 0\nKe 25 25 25\n')

# --- room: 5 x 2.6 x 5 m closed room, textured floor, ceiling lamp as its own file
floor, ceiling, back, left, right, front = box_room(-2.5, 2.5, 0, 2.6, -2.5, 2.5)
write_obj('room.obj', 'fovrt room: closed 5 x 2.6 x 5 m room, checker-textured floor (uv repeats 5x)',
          [('floor', 'room_floor', [floor]), ('ceiling', 'room_white', [ceiling]), ('back', 'room_blue', [back]),
           ('left', 'room_white', [left]), ('right', 'room_white', [right]), ('front', 'room_white', [front])],
          'room.mtl', uv_groups={'floor': 5})
open(os.path.join(out, 'room.mtl'), 'w').write('''# fovrt room materials
newmtl room_floor
Kd 1 1 1
Ks 0 0 0
Ns 10
map_Kd checker.png

newmtl room_white
Kd 0.75 0.74 0.72
Ks 0 0 0
Ns 10

newmtl room_blue
Kd 0.15 0.25 0.6
Ks 0 0 0
Ns 10
''')
lamp = [(-0.4, 2.58, -0.4), (0.4, 2.58, -0.4), (0.4, 2.58, 0.4), (-0.4, 2.58, 0.4)]
write_obj('room_lamp.obj', 'fovrt room lamp: 0.8 x 0.8 m ceiling panel facing down',
          [('lamp', 'lamp_light', [lamp])], 'room_lamp.mtl')
open(os.path.join(out, 'room_lamp.mtl'), 'w').write('newmtl lamp_light\nKd 0 0 0\nKs 0 0 0\nKe 12 10 8\n')

# --- checker.png: 16 x 16 sRGB checker, 4 x 4 px cells, (200, 200, 200) / (60, 40, 30)
W = 16
rows = b''
for y in range(W):
    rows += b'\x00'
    for x in range(W):
        on = ((x // 4) + (y // 4)) % 2 == 0
        rows += bytes((200, 200, 200) if on else (60, 40, 30))
def chunk(t, d):
    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, W, 8, 2, 0, 0, 0)) + \
      chunk(b'IDAT', zlib.compress(rows, 9)) + chunk(b'IEND', b'')
open(os.path.join(out, 'checker.png'), 'wb').write(png)
