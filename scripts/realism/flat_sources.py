#!/usr/bin/python3
"""flat_sources.py -- does a synthesis keep its exemplar's flats flat? (docs/realism.md; docs/realism_log.md)

For one-exemplar syntheses written by `terrasynth synth -o OUT.f32 --sources SRC.png` (as
scripts/realism/realism_survey.py --keep leaves them: WORK/<exemplar>_s<seed>.f32 and _src.png), it reads
each output pixel's source in the exemplar and reports
  * flat sources: the share of output pixels copied from exemplar pixels under FLAT_DEG (the
    discriminator's `flat_abs` threshold), against the exemplar's own share of such pixels;
  * kept flat: of those output pixels, the share still under FLAT_DEG in the output;
  * grad V inside patches: the median slope, in degrees, of the offset V = output - E(source) at flat
    sources two pixels or more from any incoherent link (a neighbour whose source is not the
    neighbouring exemplar pixel): the tilt V gives the interior of coherent patches.
  * level steps: of the pairs of 8-neighbours that both copy level ground of the same height (the
    synthesizer's rule, runtime/src/synth/level_ground.h: all 8 source neighbours within
    tan 0.5 deg x spacing), the share whose output heights differ by over 10 m: one connected
    water surface should come out at one height;
  * spikes: the share of pixels above or below all four edge neighbours by over 2 m, output against
    exemplar (a checkered step reads as a line of spikes);
  * patch side: how large the coherent patches are, the square root of their area-weighted mean
    area in pixels (a patch: 4-connected pixels whose sources continue each other's, S - p constant),
    and the share of the output in patches of at least 32 x 32 pixels' area.
Slopes are the realism instrument's (../shared/realism/realism.py, Zevenbergen & Thorne).

usage:
  scripts/realism/flat_sources.py --work /tmp/survey [--seed 3] [--only orom_alaska,orom_norway]
Needs Debian's python3 with numpy, scipy, PIL and sklearn (the realism instrument's dependencies).
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from scipy import ndimage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

import survey_outputs  # puts ../shared/realism on the path
import discriminator  # noqa: E402  (read_png16: PIL truncates 16-bit RGB)
import realism  # noqa: E402

FLAT_DEG = discriminator.FLAT_DEG
INTERIOR_PX = 2


def slope_tan(z, h):
    p, q, *_ = realism.derivatives(z, h)
    return np.hypot(p, q)


def neighbours(a):
    """(dy, dx, a shifted so that [y, x] holds a[y + dy, x + dx]) for the 8 neighbours; edges wrap (np.roll)."""
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dx or dy:
                yield dy, dx, np.roll(a, (-dy, -dx), (0, 1))


def incoherent_links(sx, sy):
    """1 where some 8-neighbour's source is not the exemplar pixel beside this one's (edges wrap: np.roll)."""
    out = np.zeros(sx.shape, bool)
    for (dy, dx, nx), (_, _, ny) in zip(neighbours(sx), neighbours(sy)):
        out |= (nx - sx != dx) | (ny - sy != dy)
    return out


LEVEL_DEG = 0.5
STEP_M = 10.0
SPIKE_M = 2.0


def level_flags(E, h):
    tol = math.tan(math.radians(LEVEL_DEG)) * h
    spread = np.zeros(E.shape)
    for _, _, n in neighbours(E):
        spread = np.maximum(spread, np.abs(n - E))
    level = spread <= tol
    level[0, :] = level[-1, :] = level[:, 0] = level[:, -1] = False
    return level, tol


def spike_share(z):
    c = z[1:-1, 1:-1]
    n = [z[:-2, 1:-1], z[2:, 1:-1], z[1:-1, :-2], z[1:-1, 2:]]
    up = np.all([c - x > SPIKE_M for x in n], axis=0)
    down = np.all([x - c > SPIKE_M for x in n], axis=0)
    return float((up | down).mean())


def level_steps(E, h, z, sx, sy):
    level, tol = level_flags(E, h)
    lev = level[sy, sx]
    own = E[sy, sx]
    pairs = steps = 0
    for (dy, dx, n_lev), (_, _, n_own), (_, _, n_z) in zip(neighbours(lev), neighbours(own), neighbours(z)):
        if (dy, dx) <= (0, 0):
            continue  # each unordered pair once
        both = lev & n_lev & (np.abs(n_own - own) <= tol)
        both[-1, :] = both[0, :] = both[:, -1] = both[:, 0] = False
        pairs += int(both.sum())
        steps += int((both & (np.abs(n_z - z) > STEP_M)).sum())
    return steps / pairs if pairs else float('nan')


def forward_links(sx, sy):
    """For the pairs (p, q = p + (dy, dx)) of the two forward 4-neighbour directions: (dy, dx, slices of
    the p and q pixels for any array of the output's shape, whether q's source continues p's)."""
    H, W = sx.shape
    for dy, dx in ((0, 1), (1, 0)):
        p, q = (slice(0, H - dy), slice(0, W - dx)), (slice(dy, H), slice(dx, W))
        yield dy, dx, p, q, (sx[q] - sx[p] == dx) & (sy[q] - sy[p] == dy)


def patch_sizes(sx, sy):
    """(side of the area-weighted mean patch in pixels, share of pixels in patches of >= 1024 pixels)."""
    H, W = sx.shape
    index = np.arange(H * W).reshape(H, W)
    a, b = [], []
    for _, _, p, q, coherent in forward_links(sx, sy):
        a.append(index[p][coherent])
        b.append(index[q][coherent])
    a, b = np.concatenate(a), np.concatenate(b)
    graph = coo_matrix((np.ones(len(a), np.int8), (a, b)), shape=(H * W, H * W))
    _, labels = connected_components(graph, directed=False)
    area = np.bincount(labels)
    return float(math.sqrt((area.astype(float) ** 2).sum() / area.sum())), float(area[area >= 1024].sum() / area.sum())


def survey(exemplar_png, out_f32, src_png):
    # Sources are pixels of the exemplar resampled to the database's spacing (the map's sidecar).
    h = json.load(open(os.path.splitext(src_png)[0] + '.json'))['exemplar_meters_per_pixel']
    E = realism.resample(realism.load(exemplar_png)[0], h)
    src = discriminator.read_png16(src_png).astype(np.int64)
    if src.shape[2] < 2:
        raise ValueError(f'{src_png}: not a sources map (RGB expected)')
    sx = np.clip(src[..., 0], 0, E.shape[1] - 1)
    sy = np.clip(src[..., 1], 0, E.shape[0] - 1)
    z = realism.load(out_f32)[0].z  # its sidecar gives the size
    if z.shape != sx.shape:
        raise ValueError(f'{out_f32}: {z.shape} heights, the sources map has {sx.shape}')
    flat = math.tan(math.radians(FLAT_DEG))
    g_exemplar = slope_tan(E, h)
    from_flat = g_exemplar[sy, sx] < flat
    g_out = slope_tan(z, h)
    g_offset = slope_tan(z - E[sy, sx], h)
    inside = from_flat & ~ndimage.binary_dilation(incoherent_links(sx, sy), iterations=INTERIOR_PX)
    side, large = patch_sizes(sx, sy)
    return {'exemplar_flat': float(np.nanmean(g_exemplar < flat)),
            'flat_sources': float(from_flat.mean()),
            'kept_flat': float(np.nanmean(g_out[from_flat] < flat)) if from_flat.any() else float('nan'),
            'grad_v_inside_deg': float(np.degrees(np.arctan(np.nanmedian(g_offset[inside])))) if inside.any() else float('nan'),
            'level_steps': level_steps(E, h, z, sx, sy),
            'spikes': spike_share(z), 'exemplar_spikes': spike_share(E), 'patch_side': side, 'in_large_patches': large}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    survey_outputs.add_arguments(ap)
    a = ap.parse_args()
    print('%-24s %9s %9s %9s %12s %11s %14s %11s %8s' % ('exemplar', 'ex flat', 'flat src', 'kept flat', 'grad V deg',
                                                          'lvl steps', 'spikes out/ex', 'patch side', '>=32^2'))
    for name in survey_outputs.exemplar_names(a):
        out = survey_outputs.synthesis_path(a, name)
        src = survey_outputs.synthesis_path(a, name, '_src.png')
        if not (os.path.exists(out) and os.path.exists(src)):
            print(f'{name}: no {out} with its sources map; skipped', file=sys.stderr)
            continue
        r = survey(survey_outputs.exemplar_path(a, name), out, src)
        print('%-24s %8.2f%% %8.2f%% %8.1f%% %12.2f %10.1f%% %6.2f/%.2f%% %8.0f px %7.0f%%' % (
            name, 100 * r['exemplar_flat'], 100 * r['flat_sources'], 100 * r['kept_flat'], r['grad_v_inside_deg'],
            100 * r['level_steps'], 100 * r['spikes'], 100 * r['exemplar_spikes'], r['patch_side'],
            100 * r['in_large_patches']))


if __name__ == '__main__':
    main()
