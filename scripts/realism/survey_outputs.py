"""survey_outputs.py -- what the scripts reading a realism survey's kept syntheses share.

scripts/realism/realism_survey.py --keep leaves, per shared exemplar and seed, WORK/<exemplar>_s<seed>.f32
(with its JSON sidecar) and WORK/<exemplar>_s<seed>_src.png (the sources map). The scripts that
measure those (flat_sources.py, deep_basins.py) take the same arguments and walk the same names;
importing this module also puts the realism instrument (../shared/realism) on the import path.
It is also where every script in scripts/realism/ finds the repository and the shared data.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))  # scripts/realism
ROOT = os.path.dirname(os.path.dirname(HERE))  # the repository (worktree) root
SHARED = os.path.normpath(os.path.join(ROOT, '..', 'shared'))  # the shared data beside it
if not os.path.isdir(SHARED):
    SHARED = '/work/shared'
REALISM = os.path.join(SHARED, 'realism')  # the instrument: realism.py, realism_gate.py, discriminator.py
if REALISM not in sys.path:
    sys.path.insert(0, REALISM)


def add_arguments(ap):
    """--work (required), --exemplars, --seed, --only on an argparse parser."""
    ap.add_argument('--work', required=True)
    ap.add_argument('--exemplars', default=os.path.join(SHARED, 'exemplars'))
    ap.add_argument('--seed', type=int, default=3)
    ap.add_argument('--only', default='')


def exemplar_names(args):
    """The exemplars (PNG stems) under --exemplars, sorted, narrowed to --only when given."""
    names = sorted(n[:-4] for n in os.listdir(args.exemplars) if n.endswith('.png'))
    return [n for n in names if n in args.only.split(',')] if args.only else names


def synthesis_path(args, name, suffix='.f32'):
    """WORK/<name>_s<seed><suffix>: the kept synthesis ('.f32') or its sources map ('_src.png')."""
    return os.path.join(args.work, f'{name}_s{args.seed}{suffix}')


def exemplar_path(args, name):
    return os.path.join(args.exemplars, name + '.png')
