#!/usr/bin/python3
"""deep_basins.py -- how much of a synthesis lies in deep closed basins? (docs/realism.md; docs/realism_log.md)

The realism gate's closed-depression figure counts every cell Priority-Flood raises, shallow pits and
regional basins alike. This splits it: for one-exemplar syntheses written by `terrasynth synth -o
OUT.f32` (as scripts/realism/realism_survey.py --keep leaves them: WORK/<exemplar>_s<seed>.f32) it reports,
for the synthesis and for its exemplar,
  * closed: the share of cells in closed depressions (raised by more than 1 cm by Priority-Flood);
  * deep: the share in depressions whose deepest cell lies more than DEEP_SHARE of the relief (1st to
    99th percentile of heights) below its spill. Fluvial exemplars have none; their syntheses'
    deep basins are what the breach leaves (a regional low with nothing lower within its search
    radius).
Closed regions are 8-connected, as Priority-Flood drains.

usage:
  scripts/realism/deep_basins.py --work /tmp/survey [--seed 3] [--only orom_alaska,orom_rockies]
Needs Debian's python3 with numpy, scipy and PIL (the realism instrument's dependencies).
"""
import argparse
import os
import sys

import numpy as np
from scipy import ndimage

import survey_outputs  # puts ../shared/realism on the path
import realism  # noqa: E402

RAISED_M = 0.01
DEEP_SHARE = 0.05


def basins(z):
    """(closed share, deep share) of a heightfield."""
    depth = realism.priority_flood_eps(z) - z
    closed = depth > RAISED_M
    labels, n = ndimage.label(closed, np.ones((3, 3)))
    if n == 0:
        return 0.0, 0.0
    index = np.arange(1, n + 1)
    deepest = ndimage.maximum(depth, labels, index)
    cells = ndimage.sum(closed, labels, index)
    relief = np.percentile(z, 99) - np.percentile(z, 1)
    return float(closed.mean()), float(cells[deepest > DEEP_SHARE * relief].sum() / z.size)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    survey_outputs.add_arguments(ap)
    a = ap.parse_args()
    print('%-24s %9s %9s %12s %9s' % ('exemplar', 'closed', 'deep', 'ex closed', 'ex deep'))
    for name in survey_outputs.exemplar_names(a):
        out = survey_outputs.synthesis_path(a, name)
        if not os.path.exists(out):
            print(f'{name}: no {out}; skipped', file=sys.stderr)
            continue
        s = basins(realism.load(out)[0].z)  # its sidecar gives the size and spacing
        e = basins(realism.load(survey_outputs.exemplar_path(a, name))[0].z)
        print('%-24s %8.2f%% %8.2f%% %11.2f%% %8.2f%%' % (name, 100 * s[0], 100 * s[1], 100 * e[0], 100 * e[1]))


if __name__ == '__main__':
    main()
