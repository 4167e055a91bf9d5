#!/usr/bin/python3
"""hillshade_pairs.py -- side-by-side hillshades: exemplar | syntheses (docs/realism.md, issues 16, 17).

For each exemplar it synthesizes SIZE^2 from a one-exemplar database with each named build/setting
(`label=binary[:drainage]`), and writes one PNG: the exemplar's central SIZE^2 crop (or all of it
when smaller) next to each synthesis, all hillshaded the same way (sun from the north-west, 45 deg)
at the exemplar spacing, each panel downsampled to PANEL pixels.

usage:
  scripts/realism/hillshade_pairs.py --out docs/images --only wn_mackay,wn_big_butte \
      --run before=/tmp/base/terrasynth --run after=build/bin/terrasynth --run breach=build/bin/terrasynth:breach
  --fill tints red the cells that the steering instrument's depression filling raises (the
  `fill_pct` of issue 17), and --suffix names the sheets hillshade_<exemplar><suffix>.png.
Needs Debian's python3 with numpy and PIL.
"""
import argparse, json, os, subprocess, sys, tempfile

import numpy as np
from PIL import Image, ImageDraw

from survey_outputs import SHARED  # also puts the realism instrument on the import path


def hillshade(z, mpp):
    gy, gx = np.gradient(z.astype(np.float64), mpp)
    slope = np.arctan(np.hypot(gx, gy))
    aspect = np.arctan2(-gx, gy)
    azimuth, altitude = np.radians(315.0), np.radians(45.0)
    shade = np.sin(altitude) * np.cos(slope) + np.cos(altitude) * np.sin(slope) * np.cos(azimuth - aspect)
    return np.clip(255 * shade, 0, 255).astype(np.uint8)


def raised_cells(z):
    """Cells the realism instrument's Priority-Flood+epsilon raises (its fill_pct)."""
    import realism
    return realism.priority_flood_eps(z.astype(np.float64)) > z


def panel(z, mpp, size, label, fill=False):
    shade = hillshade(z, mpp)
    if fill:
        raised = raised_cells(z)
        rgb = np.repeat(shade[:, :, None], 3, axis=2).astype(np.float64)
        rgb[raised] = 0.45 * rgb[raised] + 0.55 * np.array([230.0, 30.0, 30.0])
        img = Image.fromarray(rgb.astype(np.uint8), 'RGB')
        label += f' ({100.0 * raised.mean():.1f}% filled)'
    else:
        img = Image.fromarray(shade)
    img = img.resize((size, size), Image.LANCZOS)
    ImageDraw.Draw(img).text((6, 4), label, fill=(255, 255, 255) if fill else 255)
    return img


def exemplar_crop(png, size):
    z = np.asarray(Image.open(png), dtype=np.float64)
    meta = json.load(open(png[:-4] + '.json'))
    lo, hi = meta['height_min_m'], meta['height_max_m']
    h, w = z.shape
    s = min(size, h, w)
    y0, x0 = (h - s) // 2, (w - s) // 2
    return lo + z[y0:y0 + s, x0:x0 + s] / 65535.0 * (hi - lo)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--only', required=True)
    p.add_argument('--run', action='append', required=True, help='label=binary[:drainage]')
    p.add_argument('--out', default='docs/images')
    p.add_argument('--size', type=int, default=1024)
    p.add_argument('--panel', type=int, default=320)
    p.add_argument('--seed', type=int, default=3)
    p.add_argument('--fill', action='store_true', help='tint the cells raised by depression filling')
    p.add_argument('--suffix', default='')
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix='hillshade_pairs_')
    for stem in args.only.split(','):
        png = os.path.join(SHARED, 'exemplars', stem + '.png')
        mpp = json.load(open(png[:-4] + '.json'))['meters_per_pixel'][0]
        panels = [panel(exemplar_crop(png, args.size), mpp, args.panel, 'exemplar ' + stem, args.fill)]
        for run in args.run:
            label, spec = run.split('=', 1)
            binary, _, drainage = spec.partition(':')
            db = os.path.join(work, f'{stem}_{abs(hash(os.path.abspath(binary)))}.tsdb')  # one per build
            if not os.path.exists(db):
                subprocess.run([binary, 'db', 'build', png, '-o', db, '-q'], check=True, capture_output=True)
            out = os.path.join(work, f'{stem}_{label}.f32')
            cmd = [binary, 'synth', '--db', db, '--size', f'{args.size}x{args.size}', '--seed', str(args.seed), '-o', out]
            if drainage:
                cmd += ['--drainage', drainage]
            subprocess.run(cmd, check=True, capture_output=True)
            z = np.fromfile(out, dtype='<f4').reshape(args.size, args.size)
            panels.append(panel(z, mpp, args.panel, label, args.fill))
        sheet = Image.new('RGB' if args.fill else 'L', (args.panel * len(panels) + 4 * (len(panels) - 1), args.panel), 0)
        for i, im in enumerate(panels):
            sheet.paste(im, (i * (args.panel + 4), 0))
        target = os.path.join(args.out, f'hillshade_{stem}{args.suffix}.png')
        if args.fill:  # a 64-colour palette keeps the sheet a third of the size, the tint readable
            sheet = sheet.quantize(colors=64)
        sheet.save(target, optimize=True)
        print(target)


if __name__ == '__main__':
    main()
