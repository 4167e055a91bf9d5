#!/usr/bin/env bash
# Game soak (issue 54): `terrasynth_game --autopilot S` in real time over new ground (the autopilot's
# course never turns back: 300 m/s, 540 km in 30 minutes), headless under xvfb-run, while this
# script samples the game's resident memory from /proc every 5 s. Writes
#   $OUT/soak.json   the series: RSS from /proc, and the game's own 10 s samples (--stats
#                    "series": frame time median and p95 per interval, RSS, resident tiles and
#                    their bytes, ground blocks) with the caches' caps, and the verdicts below
#   $OUT/soak.png    a plot of them (python3-matplotlib; skipped with a note when it is missing)
# and exits 1 unless: RSS at the end is within 10% of its value at 5 minutes of flight (at a fifth
# of the flight when it is shorter than 25 minutes, less what the tile cache grew meanwhile: a
# short flight ends before the cache is full); the tile cache and the ground cache never exceed their
# caps; and (SOAK_CHECK_FRAMES=1, the default) the frame-time p95 of the last minute is within 20%
# of that of the first minute after the reference point. ctest's short run (GameSoak, label
# `soak`) sets SOAK_CHECK_FRAMES=0: tests assert plateaus, not speed.
#
#   scripts/soak_game.sh [seconds=1800] [build dir=build]      OUT=dir (default <build>/soak_game)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-1800}
build=$(cd "${2:-build}" && pwd)
out=${OUT:-$build/soak_game}
mkdir -p "$out"
export POCL_CACHE_DIR="$build/pocl_cache"
mkdir -p "$POCL_CACHE_DIR"
game="$build/bin/terrasynth_game"
[ -x "$game" ] || { echo "soak_game.sh: $game is not built" >&2; exit 2; }
rm -f "$out/pid" "$out/stats.json" "$out/rss.tsv"

# The game's pid is written by the shell xvfb-run starts, so /proc is read for the game itself.
launch="'$game' --seed ${SOAK_SEED:-54} --autopilot $seconds --size 1280x720 --stats '$out/stats.json'"
if [ -n "${DISPLAY:-}" ]; then
  bash -c "$launch & echo \$! > '$out/pid'; wait \$!" > "$out/game.log" 2>&1 &
else
  xvfb-run -a -s "-screen 0 1280x720x24" bash -c "$launch & echo \$! > '$out/pid'; wait \$!" > "$out/game.log" 2>&1 &
fi
runner=$!
start=$SECONDS
while [ ! -s "$out/pid" ] && kill -0 "$runner" 2> /dev/null; do sleep 0.2; done
pid=$(cat "$out/pid" 2> /dev/null || echo 0)
while kill -0 "$pid" 2> /dev/null; do
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2> /dev/null || true)
  [ -n "$rss" ] && printf '%d\t%s\n' $((SECONDS - start)) "$rss" >> "$out/rss.tsv"
  sleep 5
done
status=0
wait "$runner" || status=$?
if [ "$status" -ne 0 ] || [ ! -s "$out/stats.json" ]; then
  echo "soak_game.sh: the game exited $status without stats (log: $out/game.log)" >&2
  tail -20 "$out/game.log" >&2
  exit 1
fi

/usr/bin/python3 - "$out" "$seconds" "${SOAK_CHECK_FRAMES:-1}" <<'EOF'
import json, sys
out, seconds, check_frames = sys.argv[1], float(sys.argv[2]), sys.argv[3] == "1"
stats = json.load(open(f"{out}/stats.json"))
rss = [(float(t), int(kb) / 1024.0) for t, kb in (line.split("\t") for line in open(f"{out}/rss.tsv"))]
cols = stats["series_columns"]
series = [dict(zip(cols, row)) for row in stats["series"]]
caps = stats["caps"]
if not rss or len(series) < 4:
    sys.exit(f"soak_game.sh: too few samples ({len(rss)} RSS, {len(series)} game)")
# The reference point: 5 minutes in, or a fifth of a shorter run, counted from the first flight
# frame (the game's first sample interval starts there; loading the terrain comes before).
# The autopilot's seconds are simulated ones, which a slow frame rate stretches: the fifth is of
# the flight's wall time.
flight_start = series[0]["t_s"] - 10.0
flight_wall = series[-1]["t_s"] - flight_start
ref_t = flight_start + (300.0 if seconds >= 1500 else flight_wall / 5.0)
def rss_at(t):
    return min(rss, key=lambda s: abs(s[0] - t))[1]
rss_ref, rss_end = rss_at(ref_t), rss[-1][1]
after = [s for s in series if s["t_s"] > ref_t]
# A short flight ends before the tile cache reaches its cap (the game's 384 MB take some 300 km of
# new ground), so its tiles still grow, as they should: there the check is of the memory besides
# them. A full run's cache is at its cap by 5 minutes in and the check is of RSS itself.
tiles_growth = after[-1]["tiles_resident_mb"] - after[0]["tiles_resident_mb"] if seconds < 1500 else 0.0
minute = max(1, int(60 / 10))
p95_start = sorted(s["frame_ms_p95"] for s in after[:minute])[len(after[:minute]) // 2]
p95_end = sorted(s["frame_ms_p95"] for s in after[-minute:])[len(after[-minute:]) // 2]
tiles_max = max(s["tiles_resident_mb"] for s in series)
ground_max = max(s["ground_blocks"] for s in series)
checks = {
    "rss_end_within_10pct_of_reference": abs(rss_end - tiles_growth - rss_ref) <= 0.10 * rss_ref,
    "tiles_within_cap": tiles_max <= caps["tiles_mb"],
    "ground_within_cap": ground_max <= caps["ground_blocks"],
}
if check_frames:
    checks["frame_p95_end_within_20pct_of_start"] = p95_end <= 1.20 * p95_start
result = {
    "seconds": seconds, "seed": stats["seed"], "frames": stats["frames"], "synthesizer": stats["synthesizer"],
    "distance_km": stats["flight"]["distance_km"],
    "reference_s": ref_t, "rss_reference_mb": rss_ref, "rss_end_mb": rss_end, "rss_max_mb": max(r for _, r in rss),
    "tiles_growth_after_reference_mb": tiles_growth,
    "frame_p95_start_ms": p95_start, "frame_p95_end_ms": p95_end,
    "tiles_max_resident_mb": tiles_max, "ground_max_blocks": ground_max, "caps": caps,
    "tiles": stats["tiles"], "checks": checks,
    "rss_series_columns": ["t_s", "rss_mb"], "rss_series": rss,
    "game_series_columns": cols, "game_series": stats["series"],
}
json.dump(result, open(f"{out}/soak.json", "w"), indent=1)
print(f"soak {seconds:.0f} s: RSS {rss_ref:.0f} MB at {ref_t:.0f} s, {rss_end:.0f} MB at the end "
      f"({tiles_growth:.0f} MB of it new tiles below the cap) "
      f"(max {result['rss_max_mb']:.0f}); tiles max {tiles_max:.0f} of {caps['tiles_mb']:.0f} MB; ground blocks max "
      f"{ground_max} of {caps['ground_blocks']}; frame p95 {p95_start:.1f} ms after the reference, {p95_end:.1f} ms at the end")
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    a.plot([t for t, _ in rss], [r for _, r in rss], label="RSS (/proc), MB")
    a.plot([s["t_s"] for s in series], [s["tiles_resident_mb"] for s in series], label="resident tiles, MB")
    a.axhline(caps["tiles_mb"], ls=":", c="grey", label="tile cache cap")
    a.axvline(ref_t, ls="--", c="k", lw=0.8)
    a.set_ylabel("MB"); a.legend(loc="lower right")
    b.plot([s["t_s"] for s in series], [s["frame_ms_p95"] for s in series], label="frame p95 (10 s)")
    b.plot([s["t_s"] for s in series], [s["frame_ms_median"] for s in series], label="frame median (10 s)")
    b.set_ylabel("ms"); b.set_xlabel("s since start"); b.legend(loc="upper right")
    fig.suptitle(f"terrasynth_game --autopilot {seconds:.0f} (seed {stats['seed']})")
    fig.tight_layout(); fig.savefig(f"{out}/soak.png", dpi=90)
    print(f"plot: {out}/soak.png")
except ImportError:
    print("no plot: python3-matplotlib is not installed")
failed = [k for k, ok in checks.items() if not ok]
for k in failed:
    print(f"FAILED: {k}")
sys.exit(1 if failed else 0)
EOF
