#!/usr/bin/python3
"""closeup_sheet.py -- 1:1 hillshade close-ups, exemplar | one synthesis per survey (docs/realism.md).

The discriminator (../shared/realism/discriminator.py) compares 128 px crops; this shows such crops
as a geomorphologist would look at them: one row per exemplar, its central CROP^2 pixels next to the
central CROP^2 of each synthesis, every panel hillshaded the same way (sun from the north-west at
45 deg, at the exemplar's spacing) and each pixel drawn as a SCALE x SCALE square (no filtering).
The syntheses are those `scripts/realism/realism_survey.py --keep` left in its work folders
(<exemplar>_s<seed>.f32 with its .json), so the sheet shows exactly what was scored.

usage:
  scripts/realism/closeup_sheet.py --out docs/images/closeup_median_offset.jpg --seed 3 \\
      --only orom_highlands,orom_sahara --survey before=/tmp/surv/base --survey after=/tmp/surv/new
Needs Debian's python3 with numpy and PIL.
"""
import argparse, os, sys

from PIL import Image, ImageDraw

from hillshade_pairs import SHARED, hillshade  # the same sun and the same exemplars as the sheets
import realism  # on the path through survey_outputs; its loader reads sidecars, sizes, finite heights

GAP = 4


def central(z, crop):
    h, w = z.shape
    if h < crop or w < crop:
        sys.exit(f'closeup_sheet: {h}x{w} is smaller than the {crop} px crop')
    y0, x0 = (h - crop) // 2, (w - crop) // 2
    return z[y0:y0 + crop, x0:x0 + crop]


def exemplar_heights(stem):
    dem = realism.load(os.path.join(SHARED, 'exemplars', stem + '.png'))[0]
    return dem.z, dem.dx


def synthesis_heights(folder, stem, seed):
    f32 = os.path.join(folder, f'{stem}_s{seed}.f32')
    if not os.path.exists(f32):
        sys.exit(f'closeup_sheet: {f32} is missing (run realism_survey.py --keep with seed {seed})')
    return realism.load(f32)[0].z  # its .json sidecar gives the size


def panel(z, mpp, crop, scale, label):
    img = Image.fromarray(hillshade(central(z, crop), mpp))
    img = img.resize((crop * scale, crop * scale), Image.NEAREST)
    ImageDraw.Draw(img).text((4, 2), label, fill=255)
    return img


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--only', required=True, help='exemplar names, comma-separated: one row each')
    p.add_argument('--survey', action='append', required=True, help='label=work folder of realism_survey.py --keep')
    p.add_argument('--seed', type=int, default=3)
    p.add_argument('--crop', type=int, default=128)
    p.add_argument('--scale', type=int, default=2)
    p.add_argument('--out', required=True, help='.png or .jpg')
    args = p.parse_args()
    surveys = [s.split('=', 1) for s in args.survey]
    rows = []
    for stem in args.only.split(','):
        z, mpp = exemplar_heights(stem)
        row = [panel(z, mpp, args.crop, args.scale, stem)]
        for label, folder in surveys:
            row.append(panel(synthesis_heights(folder, stem, args.seed), mpp, args.crop, args.scale, f'{label} s{args.seed}'))
        rows.append(row)
    side = args.crop * args.scale
    columns = len(rows[0])
    sheet = Image.new('L', (columns * side + (columns - 1) * GAP, len(rows) * side + (len(rows) - 1) * GAP), 0)
    for r, row in enumerate(rows):
        for c, img in enumerate(row):
            sheet.paste(img, (c * (side + GAP), r * (side + GAP)))
    if args.out.lower().endswith(('.jpg', '.jpeg')):
        sheet.save(args.out, quality=88, optimize=True)
    else:
        sheet.save(args.out, optimize=True)
    print(args.out)


if __name__ == '__main__':
    main()
