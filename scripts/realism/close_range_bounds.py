#!/usr/bin/python3
"""close_range_bounds.py -- how close to its exemplar could copy-based synthesis come up close?

Constructions outside the synthesizer, scored as scripts/realism/realism_survey.py scores a synthesis (the
realism gate's five figures and the discriminator's copy-aware AUC, ../shared/realism), to tell what
a change to the synthesis could buy before it is built (docs/realism.md, "What the targets ask"):

  poisson  each kept synthesis of a survey (realism_survey.py --keep) with its heights solved again
           from its sources map, S fixed:
               minimise  sum over 4-neighbour pairs w_pq (h_q - h_p - t_pq)^2 + eps sum_p (h_p - h0_p)^2
           t_pq the exemplar's own step at the two sources (exact inside a coherent patch, the mean of
           both sources' steps across a seam), w = sigma^2 / (t^2 + sigma^2) with sigma = tan 5 deg x
           the spacing, h0 the synthesis; solved exactly (sparse LU). It is what the
           offset relaxation (runtime/src/synth/offset_relaxation.h) approaches with a few Jacobi
           iterations per level: the offset V as flat inside patches as the seams allow. No drainage
           step after it, so closed depressions the breach had drained may come back.
  quilt    image quilting (Efros & Freeman 2001) of the exemplar alone: BLOCK px blocks overlapping by
           OVERLAP, each the best of TRIES random exemplar blocks by its overlap's squared mismatch
           after a height offset, cut along the minimum-error boundary, then the same solve with level
           ground (flat_sources.level_flags) held rigid. Sequential, without constraints or drainage:
           a bound for a synthesizer that copies whole blocks, not one to ship.
  null     the discriminator's own noise: an exemplar's crops against its crops at other random
           offsets (discriminator.py controls, control b), --reps times; what a synthesis as real as
           the exemplar itself would score.

usage:
  scripts/realism/close_range_bounds.py poisson --survey /tmp/survey --work /tmp/bounds/poisson [--seeds 3,4]
  scripts/realism/close_range_bounds.py quilt --work /tmp/bounds/quilt [--seeds 3,4] [--block 192 --overlap 64 --tries 20]
  scripts/realism/close_range_bounds.py null [--reps 10]
common: [--only orom_alaska,orom_norway] [--jobs 2] [--json out.json]
Needs Debian's python3 with numpy, scipy, PIL and sklearn (the realism instrument's dependencies).
"""
import argparse
import concurrent.futures as cf
import json
import math
import os
import re
import statistics
import struct
import sys
import zlib

import numpy as np
import scipy.sparse as sparse
import scipy.sparse.linalg as sparse_linalg

import survey_outputs  # puts ../shared/realism on the path
import discriminator  # noqa: E402
import realism  # noqa: E402
from flat_sources import forward_links, level_flags  # noqa: E402
from realism_survey import LIMITS, REALISM, SHORT, discriminate, gate_figures, run  # noqa: E402

GENTLE_DEG = 5.0          # the offset relaxation's kRelaxFlatSlopeDegrees
STIFFNESS = 1e-4          # eps: reach of about 1/sqrt(eps) = 100 px
RIGID_LEVEL_WEIGHT = 1e3  # quilt: pairs of level sources move together
SIZE = 1024


# ---------------------------------------------------------------- the solve
def exemplar_steps(E, sx, sy):
    """Per 4-neighbour pair (p, q = p + (0, 1) or (1, 0)): flat indices of p and q, the target step t_pq,
    and per direction the sources (px, py, qx, qy) of its pairs."""
    H, W = sx.shape
    EH, EW = E.shape
    at = lambda y, x: E[np.clip(y, 0, EH - 1), np.clip(x, 0, EW - 1)]
    index = np.arange(H * W).reshape(H, W)
    ps, qs, ts, sources = [], [], [], []
    for dy, dx, p, q, coherent in forward_links(sx, sy):
        px, py, qx, qy = sx[p], sy[p], sx[q], sy[q]
        across = 0.5 * ((at(py + dy, px + dx) - at(py, px)) + (at(qy, qx) - at(qy - dy, qx - dx)))
        ts.append(np.where(coherent, at(qy, qx) - at(py, px), across).ravel())
        ps.append(index[p].ravel())
        qs.append(index[q].ravel())
        sources.append((px, py, qx, qy))
    return np.concatenate(ps), np.concatenate(qs), np.concatenate(ts), sources


def solve_heights(E, h, sx, sy, z0, rigid=None):
    """The screened weighted Poisson of the module doc; `rigid` (level flags of E) weights pairs of level sources."""
    p, q, t, sources = exemplar_steps(E, sx, sy)
    sigma = math.tan(math.radians(GENTLE_DEG)) * h
    w = sigma ** 2 / (t ** 2 + sigma ** 2)
    if rigid is not None:
        EH, EW = E.shape
        lv = lambda y, x: rigid[np.clip(y, 0, EH - 1), np.clip(x, 0, EW - 1)]
        both = np.concatenate([(lv(py, px) & lv(qy, qx)).ravel() for px, py, qx, qy in sources])
        w = np.where(both, RIGID_LEVEL_WEIGHT, w)
    n, m = z0.size, len(p)
    rows = np.r_[np.arange(m), np.arange(m)]
    D = sparse.csr_matrix((np.r_[-np.ones(m), np.ones(m)], (rows, np.r_[p, q])), shape=(m, n))
    b = D.T @ (w * t) + STIFFNESS * z0.ravel()
    A = (D.T @ sparse.diags(w) @ D + STIFFNESS * sparse.identity(n)).tocsc()
    return sparse_linalg.spsolve(A, b, permc_spec='MMD_AT_PLUS_A').reshape(z0.shape)


# ---------------------------------------------------------------- quilting
def min_error_cut(cost):
    """Per row of an (h, w) cost, the column where the cheapest top-to-bottom 8-connected path crosses it."""
    h, w = cost.shape
    total, back = cost.copy(), np.zeros((h, w), int)
    for r in range(1, h):
        prev = total[r - 1]
        options = np.stack([np.r_[np.inf, prev[:-1]], prev, np.r_[prev[1:], np.inf]])
        k = np.argmin(options, 0)
        back[r] = np.arange(w) + k - 1
        total[r] += options[k, np.arange(w)]
    path = np.zeros(h, int)
    path[-1] = np.argmin(total[-1])
    for r in range(h - 1, 0, -1):
        path[r - 1] = back[r, path[r]]
    return path


def quilt(E, size, block, overlap, tries, rng):
    """Heights and sources (x, y) of a size^2 quilt of E (module doc)."""
    EH, EW = E.shape
    if block > min(EH, EW):
        raise ValueError(f'block {block} px is larger than the {EW}x{EH} exemplar')
    step = block - overlap
    blocks = (size - overlap + step - 1) // step
    full = overlap + blocks * step
    z = np.full((full, full), np.nan)
    sx = np.zeros((full, full), np.int64)
    sy = np.zeros((full, full), np.int64)
    for bi in range(blocks):
        for bj in range(blocks):
            window = (slice(bi * step, bi * step + block), slice(bj * step, bj * step + block))
            old = z[window]
            known = np.isfinite(old)
            best = None
            for _ in range(tries):
                oy, ox = int(rng.integers(0, EH - block + 1)), int(rng.integers(0, EW - block + 1))
                candidate = E[oy:oy + block, ox:ox + block]
                offset = float(np.mean(old[known] - candidate[known])) if known.any() else 0.0
                error = float(np.mean((old[known] - candidate[known] - offset) ** 2)) if known.any() else 0.0
                if best is None or error < best[0]:
                    best = (error, oy, ox, offset)
            _, oy, ox, offset = best
            candidate = E[oy:oy + block, ox:ox + block] + offset
            take = np.ones((block, block), bool)
            mismatch = np.nan_to_num((old - candidate) ** 2, nan=0.0)
            if bj > 0:
                for r, c in enumerate(min_error_cut(mismatch[:, :overlap])):
                    take[r, :c] = False
            if bi > 0:
                for c, r in enumerate(min_error_cut(mismatch[:overlap, :].T)):
                    take[:r, c] = False
            take |= ~known
            z[window] = np.where(take, candidate, old)
            sx[window] = np.where(take, ox + np.arange(block)[None, :], sx[window])
            sy[window] = np.where(take, oy + np.arange(block)[:, None], sy[window])
    return z[:size, :size], sx[:size, :size], sy[:size, :size]


# ---------------------------------------------------------------- files and scores
def write_png16_rgb(path, rgb):
    """A 16-bit RGB PNG (PIL writes 16 bits for one channel only): the sources map's format."""
    H, W, _ = rgb.shape
    raw = b''.join(b'\x00' + rgb[r].astype('>u2').tobytes() for r in range(H))
    chunk = lambda tag, data: (struct.pack('>I', len(data)) + tag + data +
                               struct.pack('>I', zlib.crc32(tag + data) & 0xffffffff))
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 16, 2, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))


def write_synthesis(work, name, seed, z, sx, sy, mpp, exemplar_png):
    """WORK/<name>_s<seed>.f32 + sidecar and _src.png + sidecar, as `terrasynth synth --sources` writes them."""
    base = os.path.join(work, f'{name}_s{seed}')
    z.astype('<f4').tofile(base + '.f32')
    with open(base + '.json', 'w') as f:
        json.dump({'file': os.path.basename(base) + '.f32', 'format': 'float32 little-endian, metres, row-major',
                   'width': z.shape[1], 'height': z.shape[0], 'meters_per_pixel': [mpp, mpp]}, f)
    write_png16_rgb(base + '_src.png', np.stack([sx, sy, np.zeros_like(sx)], -1))
    with open(base + '_src.json', 'w') as f:
        json.dump({'exemplar_meters_per_pixel': mpp, 'level': 0,
                   'exemplars': [{'index': 0, 'name': name, 'path': exemplar_png}]}, f)
    return base + '.f32', base + '_src.png'


def one(args, name, seed):
    png = survey_outputs.exemplar_path(args, name)
    if args.command == 'poisson':
        src_png = os.path.join(args.survey, f'{name}_s{seed}_src.png')
        mpp = json.load(open(src_png[:-4] + '.json'))['exemplar_meters_per_pixel']
        E = realism.resample(realism.load(png)[0], mpp)
        src = discriminator.read_png16(src_png).astype(np.int64)
        sx, sy = src[..., 0], src[..., 1]
        z0 = realism.load(os.path.join(args.survey, f'{name}_s{seed}.f32'))[0].z
        z = solve_heights(E, mpp, sx, sy, z0)
    else:
        dem = realism.load(png)[0]
        mpp = max(dem.dx, dem.dy)
        E = realism.resample(dem, mpp)
        z0, sx, sy = quilt(E, SIZE, args.block, args.overlap, args.tries, np.random.default_rng(seed))
        z = solve_heights(E, mpp, sx, sy, z0, rigid=level_flags(E, mpp)[0])
    out, src = write_synthesis(args.work, name, seed, z, sx, sy, mpp, png)
    figures = gate_figures(args, png, out, mpp)
    return {'exemplar': name, 'seed': seed, 'figures': figures,
            'pass': {k: figures[k] <= LIMITS[k] for k in LIMITS},
            'discriminator': discriminate(args, png, out, src, mpp)}


def construct(args, names, seeds):
    os.makedirs(args.work, exist_ok=True)
    rows = []
    with cf.ThreadPoolExecutor(args.jobs) as pool:
        for f in [pool.submit(one, args, n, s) for n in names for s in seeds]:
            r = f.result()
            rows.append(r)
            fig = ' '.join(f'{SHORT[k]}={v:.3g}{"" if r["pass"][k] else "!"}' for k, v in r['figures'].items())
            d = r['discriminator']
            print(f'{r["exemplar"]:24s} seed {r["seed"]}: {fig} AUC_src={d["auc_lr_src"]:.2f} top: ' +
                  ', '.join(f'{f}({a:.3g} vs {b:.3g})' for f, a, b in d['top']), flush=True)
    aucs = [r['discriminator']['auc_lr_src'] for r in rows]
    misses = [f'{r["exemplar"]} s{r["seed"]} ' + ','.join(SHORT[k] for k, ok in r['pass'].items() if not ok)
              for r in rows if not all(r['pass'].values())]
    print(f'{args.command}: mean {statistics.mean(aucs):.3f}, median {statistics.median(aucs):.3f}, worst '
          f'{max(aucs):.2f}, {sum(a > 0.70 for a in aucs)} of {len(aucs)} over 0.70; {len(misses)} runs over the '
          f'gate' + (': ' + '; '.join(misses) if misses else ''))
    return rows


def null(args, names):
    rows = []

    def controls(name):
        text = run(['/usr/bin/python3', os.path.join(REALISM, 'discriminator.py'), 'controls',
                    survey_outputs.exemplar_path(args, name), '--null-reps', str(args.reps)])
        reps = [float(v) for v in re.search(r'b reps: LR ([\d. ]+);', text).group(1).split()]
        return {'exemplar': name, 'auc_lr_reps': reps}

    with cf.ThreadPoolExecutor(args.jobs) as pool:
        for r in pool.map(controls, names):
            rows.append(r)
            v = r['auc_lr_reps']
            print(f'{r["exemplar"]:24s} mean {statistics.mean(v):.3f} sd {statistics.stdev(v):.3f} '
                  f'max {max(v):.2f}  ({" ".join(f"{a:.2f}" for a in v)})', flush=True)
    every = [a for r in rows for a in r['auc_lr_reps']]
    print(f'null: mean {statistics.mean(every):.3f}, sd {statistics.stdev(every):.3f}, {sum(a > 0.70 for a in every)} '
          f'of {len(every)} over 0.70, max {max(every):.2f}')
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('command', choices=('poisson', 'quilt', 'null'))
    ap.add_argument('--work', default='/tmp/close_range_bounds')
    ap.add_argument('--exemplars', default=os.path.join(survey_outputs.SHARED, 'exemplars'))
    ap.add_argument('--only', default='')
    ap.add_argument('--survey', help='poisson: the work folder of realism_survey.py --keep')
    ap.add_argument('--seeds', default='3,4')
    ap.add_argument('--block', type=int, default=192)
    ap.add_argument('--overlap', type=int, default=64)
    ap.add_argument('--tries', type=int, default=20)
    ap.add_argument('--reps', type=int, default=10)
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--json', default='')
    args = ap.parse_args()
    if args.command == 'poisson' and not args.survey:
        ap.error('poisson needs --survey (the work folder of realism_survey.py --keep)')
    args.size = SIZE  # what realism_survey's gate_figures and discriminate read
    names = survey_outputs.exemplar_names(args)
    seeds = [int(s) for s in args.seeds.split(',')]
    rows = null(args, names) if args.command == 'null' else construct(args, names, seeds)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(rows, f, indent=1)


if __name__ == '__main__':
    main()
