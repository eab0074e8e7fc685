#!/usr/bin/python3
"""Rays out of steps, per shipped scene and preset: how many ran past max_steps, how many were left
unresolved, and how many pixels differ from the same preset with a budget of 20000 steps because of
them. Renders 480x270, one sample a pixel, at each scene's own view; the EXRs are kept in WORKDIR and
reused. Needs python3-numpy and python3-openimageio (Debian).
Usage: out_of_steps.py FATHOM WORKDIR TAG [scene,scene,...]  (FATHOM's tree: FATHOM/../..)"""
import json, math, os, subprocess, sys
import numpy as np
import OpenImageIO as oiio

BIN, WORK, TAG = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
SCENES = sys.argv[4].split(',') if len(sys.argv) > 4 else \
    ['csg', 'himalaya', 'jacksboro', 'mandelbox', 'mandelbulb', 'menger', 'noise', 'spray', 'dem']
TREE = os.path.dirname(os.path.dirname(BIN))
W, H = 480, 270


def render(scene, preset, extra, kind):
    out = os.path.join(WORK, '%s-%s-%s-%s.exr' % (TAG, scene, preset, kind))
    if not os.path.exists(out):
        subprocess.run([BIN, '--scene', scene, '--quality', preset, '--spp', '1', '--size', '%dx%d' % (W, H),
                        '--aov', 'depth,steps', '--quiet', '--output', out] + extra, cwd=TREE, check=True,
                       capture_output=True)
    buf = oiio.ImageBuf(out)
    spec = buf.spec()
    px = buf.get_pixels(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)
    return px[..., names.index('Z')], px[..., names.index('steps')]


def define(scene, preset, name):
    text = subprocess.run([BIN, '--scene', scene, '--quality', preset, '--print-variant'], cwd=TREE,
                          capture_output=True, text=True, check=True).stdout
    return float([l.split()[2] for l in text.splitlines() if l.startswith('#define %s ' % name)][0])


def silhouette(z):
    """Pixels whose reference neighbour (4-connected) misses where they hit, or lies 5 % away."""
    hit = np.isfinite(z)
    zz = np.where(hit, z, 0.0)
    edge = np.zeros_like(hit)
    for dy, dx in ((0, 1), (0, -1), (1, 0), (-1, 0)):
        n_hit = np.roll(np.roll(hit, dy, 0), dx, 1)
        n_z = np.roll(np.roll(zz, dy, 0), dx, 1)
        edge |= (n_hit != hit) | (hit & n_hit & (np.abs(n_z - zz) > 0.05 * np.maximum(zz, 1e-30)))
    return edge


print('| scene | preset | ran past max_steps | left unresolved (%s) | surface where the reference misses | '
      'miss, unflagged, where it hits | depth off by more than the tail\'s 4 thresholds | of these columns, on a '
      'silhouette |' % ('drawn as their best guess' if TAG == 'old' else 'flagged, drawn as a miss'))
print('|---|---|---|---|---|---|---|---|')
for sc in SCENES:
    try:
        fov = json.load(open(os.path.join(TREE, 'scenes', sc + '.json')))['camera']['fov']
    except (KeyError, OSError, TypeError):
        fov = None
    for pr in ['draft', 'interactive', 'final']:
        zt, st = render(sc, pr, [], 'test')
        zr, sr = render(sc, pr, ['--set', 'quality.max_steps=20000'], 'ref')
        budget, hit_k = define(sc, pr, 'MAX_STEPS'), define(sc, pr, 'HIT_K')
        pixel_angle = 2 * math.tan(math.radians(fov or 50) / 2) / H
        out = (st > budget) | (st < 0) | ((st == budget) & (TAG == 'old'))
        flagged = st < 0
        ht, hr = np.isfinite(zt), np.isfinite(zr)
        edge = silhouette(zr)
        false_hit = out & ht & ~hr
        false_miss = out & ~ht & hr & ~flagged
        both = out & ht & hr
        tol = np.maximum(0.01, 4 * hit_k * pixel_angle) * np.where(hr, zr, 0)
        deep = both & (np.abs(np.where(both, zt - zr, 0)) > tol)
        wrong = false_hit | false_miss | deep
        print('| %s | %s | %d | %d | %d | %d | %d | %d |' % (sc, pr, out.sum(), flagged.sum(), false_hit.sum(),
              false_miss.sum(), deep.sum(), (wrong & edge).sum()), flush=True)
