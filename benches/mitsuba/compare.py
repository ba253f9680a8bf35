#!/usr/bin/env python3
"""facetlab's exact photograph against Mitsuba 3's path tracer (not run by CI).

One orthographic picture of a round brilliant at a fixed index (2.4173, no dispersion, no
polarization: what Mitsuba's `scalar_rgb` dielectric models) under a smooth grey environment
map written here, by `facetlab render --light env:MAP --hdr-out` and by Mitsuba 3 (a mesh with
a dielectric BSDF inside an `envmap` emitter, an orthographic sensor with a box filter, the
`path` integrator without Russian roulette), then their luminance compared pixel by pixel.
Mitsuba is rendered twice with different seeds: the difference between its two runs is its own
Monte Carlo noise, the yardstick for the difference from facetlab.

Usage (needs `pip install mitsuba numpy`; run from the repository):

    cargo build --release
    python3 benches/mitsuba/compare.py [--size 128] [--spp 512] [--view 30@0]
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np


def env_map(w=512):
    """A smooth grey environment (linear radiance), rows from the zenith; the middle column
    faces +x and columns to its right turn clockwise seen from above (facetlab's layout):
    a sky brightening toward the zenith, a dim floor and two broad soft lights."""
    h = w // 2
    e = (90.0 - 180.0 * (np.arange(h) + 0.5) / h)[:, None] * np.ones((1, w))
    az = (180.0 - 360.0 * (np.arange(w) + 0.5) / w)[None, :] * np.ones((h, 1))
    er, ar = np.radians(e), np.radians(az)
    d = np.stack([np.cos(er) * np.cos(ar), np.cos(er) * np.sin(ar), np.sin(er)], -1)
    z = d[..., 2]
    sky = np.where(z > 0, 0.25 + 0.75 * z, 0.08)
    for (el, a, amp, width) in [(40.0, 30.0, 3.0, 15.0), (20.0, 200.0, 2.0, 20.0)]:
        c = np.array([math.cos(math.radians(el)) * math.cos(math.radians(a)),
                      math.cos(math.radians(el)) * math.sin(math.radians(a)),
                      math.sin(math.radians(el))])
        ang = np.degrees(np.arccos(np.clip(d @ c, -1, 1)))
        sky = sky + amp * np.exp(-0.5 * (ang / width) ** 2)
    return np.repeat(sky[..., None], 3, axis=2).astype(np.float32)


def read_obj(path):
    verts, faces = [], []
    for line in open(path):
        p = line.split()
        if not p:
            continue
        if p[0] == 'v':
            verts.append([float(x) for x in p[1:4]])
        elif p[0] == 'f':
            faces.append([int(x.split('/')[0]) - 1 for x in p[1:]])
    return np.array(verts), faces


def canonical(verts, faces):
    """facetlab's canonical placement (geometry::canonical): the volume centroid at the origin,
    lengths divided by the diameter of the circle with the face-up outline's area (a bundled
    preset is not turned)."""
    vol, cen, up_area = 0.0, np.zeros(3), 0.0
    for f in faces:
        for i in range(1, len(f) - 1):
            a, b, c = verts[f[0]], verts[f[i]], verts[f[i + 1]]
            v = np.dot(a, np.cross(b, c)) / 6.0
            vol += v
            cen += v * (a + b + c) / 4.0
            n = np.cross(b - a, c - a) / 2.0
            if n[2] > 0:
                up_area += n[2]
    cen /= vol
    d = math.sqrt(4.0 * up_area / math.pi)
    return (verts - cen) / d


def luminance(rgb):
    return 0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--facetlab', default='target/release/facetlab')
    ap.add_argument('--size', type=int, default=128)
    ap.add_argument('--spp', type=int, default=512)
    ap.add_argument('--view', default='30@0')
    ap.add_argument('--out', default=None, help='folder for the pictures (default: a temporary one)')
    a = ap.parse_args()
    import mitsuba as mi
    mi.set_variant('scalar_rgb')
    out = a.out or tempfile.mkdtemp(prefix='facetlab-mitsuba-')
    os.makedirs(out, exist_ok=True)
    env = os.path.join(out, 'env.exr')
    mi.Bitmap(env_map()).write(env)
    obj = os.path.join(out, 'stone.obj')
    subprocess.run([a.facetlab, 'generate', 'tolkowsky', '-o', obj], check=True, capture_output=True)
    fl_exr = os.path.join(out, 'facetlab.exr')
    js = os.path.join(out, 'facetlab.json')
    subprocess.run([a.facetlab, 'render', 'tolkowsky', '--light', 'env:' + env, '--ri', '2.4173',
                    '--polarization', 'off', '--view', a.view, '--size', str(a.size), '--bare',
                    '--tone', 'clip', '--hdr-out', fl_exr, '--json', js, '--force', '--quiet',
                    '-o', os.path.join(out, 'facetlab.png')], check=True, capture_output=True)
    fl = np.array(mi.Bitmap(fl_exr))[..., :3]
    # The same placement and square as facetlab's picture.
    verts, faces = read_obj(obj)
    cv = canonical(verts, faces)
    half = np.max(np.linalg.norm(cv, axis=1)) * 1.001 * 1.25
    placed = os.path.join(out, 'placed.obj')
    with open(placed, 'w') as f:
        for v in cv:
            f.write('v %.17g %.17g %.17g\n' % tuple(v))
        for fc in faces:
            f.write('f ' + ' '.join(str(i + 1) for i in fc) + '\n')
    elev, az = (float(x) for x in (a.view.split('@') + ['0'])[:2])
    e, w_az = math.radians(elev), math.radians(az - 90.0)
    c = np.array([math.cos(e) * math.cos(w_az), math.cos(e) * math.sin(w_az), math.sin(e)])
    up = np.array([0.0, 0.0, 1.0]) if elev < 89.9 else np.array([-math.sin(w_az), math.cos(w_az), 0.0]) @ np.eye(3)
    if elev >= 89.9:
        right = np.array([-math.sin(w_az), math.cos(w_az), 0.0])
        up = np.cross(c, right)
    T = mi.ScalarTransform4f
    # facetlab's map layout in Mitsuba's envmap frame (y up, u = atan2(x, -z) / 2π): world
    # (X, Y, Z) = (z_l, x_l, y_l).
    env_to_world = mi.ScalarTransform4f([[0, 0, 1, 0], [1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]])
    scenes = []
    for seed in (1, 2):
        scene = mi.load_dict({
            'type': 'scene',
            'integrator': {'type': 'path', 'max_depth': 200, 'rr_depth': 200},
            'sensor': {
                'type': 'orthographic',
                'to_world': T().look_at(origin=(c * 10).tolist(), target=[0, 0, 0], up=up.tolist())
                @ T().scale([half, half, 1.0]),
                'film': {'type': 'hdrfilm', 'width': a.size, 'height': a.size,
                         'rfilter': {'type': 'box'}, 'pixel_format': 'rgb'},
                'sampler': {'type': 'independent', 'sample_count': a.spp, 'seed': seed},
            },
            'stone': {'type': 'obj', 'filename': placed, 'face_normals': True,
                      'bsdf': {'type': 'dielectric', 'int_ior': 2.4173, 'ext_ior': 1.0}},
            'light': {'type': 'envmap', 'filename': env, 'to_world': env_to_world},
        })
        scenes.append(np.array(mi.render(scene))[..., :3])
    m1, m2 = scenes
    yf, y1, y2 = luminance(fl), luminance(m1), luminance(m2)
    # Mitsuba's film's x runs opposite to facetlab's image right when seen from the camera?
    # Compare both ways and say which one fits (the scene is not mirror-symmetric).
    direct = np.mean(np.abs(yf - 0.5 * (y1 + y2)))
    mirrored = np.mean(np.abs(yf[:, ::-1] - 0.5 * (y1 + y2)))
    if mirrored < direct:
        yf = yf[:, ::-1]
    ym = 0.5 * (y1 + y2)
    diff = yf - ym
    noise = np.abs(y1 - y2) / 2.0  # the mean of two runs' own noise
    res = {
        'size': a.size, 'spp_per_run': a.spp, 'view': a.view,
        'orientation': 'mirrored' if mirrored < direct else 'direct',
        'mean_facetlab': float(yf.mean()), 'mean_mitsuba': float(ym.mean()),
        'mean_difference': float(diff.mean()),
        'mean_abs_difference': float(np.abs(diff).mean()),
        'rms_difference': float(np.sqrt((diff ** 2).mean())),
        'p99_abs_difference': float(np.percentile(np.abs(diff), 99)),
        'mitsuba_noise_mean_abs': float(noise.mean()),
        'mitsuba_noise_rms': float(np.sqrt((((y1 - y2) / 2.0) ** 2).mean())),
        'other_orientation_mean_abs': float(max(direct, mirrored)),
    }
    np.save(os.path.join(out, 'diff.npy'), diff)
    print(json.dumps(res, indent=2))
    print('pictures in', out, file=sys.stderr)


if __name__ == '__main__':
    main()
