#!/usr/bin/python3
"""synth_rounds.py -- two builds' `terrasynth synth` times in interleaved rounds.

The 2-core machines drift by 20% and more within minutes (docs/benchmarks.md, "Machines"), so a
build is compared with another only in rounds that run both, alternating which goes first, in
the same minutes: each round runs every configuration once on the same seed (a new seed per round,
so no round repeats another's windows), and the figure is the median of the per-round ratios.
The time is what the CLI prints ("synthesis N ms": the synthesis alone, database and device ready
before it), the first synthesis of a fresh process as a user meets it.

usage:
  scripts/synth_rounds.py --db db.tsdb --size 1024x1024 --rounds 9 \\
      base=/path/old/terrasynth new=build/bin/terrasynth [name=BINARY[:ENV=VALUE;...] ...]
The first configuration is the one the others are divided by. Prints one line per round, then per
configuration the median time and the median and range of its per-round ratio, and the load
average before and after (the machine's load beside the figures).
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile


def parse_config(text):
    name, _, rest = text.partition('=')
    binary, _, env_text = rest.partition(':')
    env = dict(item.split('=', 1) for item in env_text.split(';') if item)
    if not name or not binary:
        raise SystemExit(f'synth_rounds: configuration "{text}" is not NAME=BINARY[:ENV=VALUE;...]')
    return name, binary, env


def run_once(binary, env, db, size, seed, out):
    full_env = dict(os.environ, **env)
    done = subprocess.run([binary, 'synth', '--db', db, '--size', size, '--seed', str(seed), '-o', out],
                          capture_output=True, text=True, env=full_env)
    match = re.search(r'synthesis ([0-9.]+) ms', done.stdout + done.stderr)
    if done.returncode != 0 or not match:
        raise SystemExit(f'synth_rounds: {binary} failed ({done.returncode}):\n{done.stdout}{done.stderr}')
    return float(match.group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--db', required=True)
    ap.add_argument('--size', default='1024x1024')
    ap.add_argument('--rounds', type=int, default=9)
    ap.add_argument('--first-seed', type=int, default=1)
    ap.add_argument('--same-bits', action='store_true', help='also check every configuration writes the same bytes')
    ap.add_argument('configs', nargs='+')
    args = ap.parse_args()
    configs = [parse_config(c) for c in args.configs]
    os.environ.setdefault('POCL_CACHE_DIR', os.path.join(tempfile.gettempdir(), 'synth_rounds_pocl'))
    load_before = os.getloadavg()
    times = {name: [] for name, _, _ in configs}
    with tempfile.TemporaryDirectory() as work:
        for name, binary, env in configs:  # warm: kernels compiled into the PoCL cache, database in the page cache
            run_once(binary, env, args.db, args.size, 0, os.path.join(work, 'warm.f32'))
        for r in range(args.rounds):
            seed = args.first_seed + r
            order = configs if r % 2 == 0 else configs[::-1]
            outputs = {}
            for name, binary, env in order:
                out = os.path.join(work, f'{name}.f32')
                times[name].append(run_once(binary, env, args.db, args.size, seed, out))
                outputs[name] = open(out, 'rb').read() if args.same_bits else None
            if args.same_bits and len({outputs[n] for n in outputs}) != 1:
                raise SystemExit(f'synth_rounds: seed {seed}: the configurations wrote different bytes')
            print(f'round {r + 1} seed {seed}: ' + ', '.join(f'{n} {times[n][-1]:.1f} ms' for n, _, _ in configs),
                  flush=True)
    base = configs[0][0]
    print(f'load average before {load_before[0]:.2f}, after {os.getloadavg()[0]:.2f}; {args.size}, {args.db}')
    for name, _, _ in configs:
        ratios = [t / b for t, b in zip(times[name], times[base])]
        print(f'{name}: median {statistics.median(times[name]):.1f} ms (range {min(times[name]):.1f}-'
              f'{max(times[name]):.1f}); over {base} per round: median {statistics.median(ratios):.3f} '
              f'(range {min(ratios):.3f}-{max(ratios):.3f})')
    if args.same_bits:
        print('same bytes from every configuration in every round')


if __name__ == '__main__':
    sys.exit(main())
