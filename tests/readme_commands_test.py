#!/usr/bin/env python3
"""Runs every command of README.md's sh (and python) blocks exactly as printed there (issue: a README command that
fails for a new user), in a scratch folder laid out like the repository after `bash scripts/demo.sh`:
build/ and scripts/ are the real ones (links), data/ holds the shipped project, exemplars and database
cache (links and copies), and my_dem.tif, the README's "your own DEM", is a real shipped exemplar as a
GeoTIFF. Each block runs as one bash script (an `export` holds for the lines below it), on an Xvfb of its own, with
OSG_RUN_FRAME_COUNT set so osgviewer, the editor and the game quit after a few frames, and
OSG_WINDOW so osgviewer opens a window rather than a full screen (see run_all).

Lines that are not commands are told apart by rule: usage synopses (`terrasynth <...>` without
build/bin, placeholders in <>, continuation lines). The two first commands are the ones this test runs
inside of (test.sh is CI; demo.sh's every step is a line of this test's blocks or run by CI's build), so
they are left out by name. A server that runs until stopped (scripts/view_world.sh) is stopped once it
says it serves.

usage: readme_commands_test.py REPO_ROOT BUILD_DIR SCRATCH_DIR
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys

NOT_RUN_HERE = {
    "bash scripts/demo.sh": "the newcomer's first command: installs and builds, then runs the lines of this test",
    "bash scripts/test.sh": "CI's command, which runs this test",
}
# Commands that serve until stopped: the line is run until its output says this.
SERVES = {"scripts/view_world.sh": re.compile(r"serving .* at http://127\.0\.0\.1")}


def code_blocks(readme, language):
    blocks, block = [], None
    for line in open(readme, encoding="utf-8"):
        line = line.rstrip("\n")
        if block is None and line.strip() == "```" + language:
            block = []
        elif block is not None and line.strip() == "```":
            blocks.append(block)
            block = None
        elif block is not None:
            block.append(line)
    return blocks


def is_command(line):
    text = line.split("#", 1)[0].strip()
    if not text or line.startswith((" ", "\t")):
        return False  # blank, comment, or a synopsis' continuation
    if re.search(r"<[^>]+>", text) or text.startswith("terrasynth "):
        return False  # usage synopsis
    return True


def make_scratch(repo, build, scratch):
    if os.path.exists(scratch):
        shutil.rmtree(scratch)
    os.makedirs(os.path.join(scratch, "data"))
    os.symlink(os.path.abspath(build), os.path.join(scratch, "build"))
    os.symlink(os.path.join(repo, "scripts"), os.path.join(scratch, "scripts"))
    data = os.path.join(repo, "data")
    os.symlink(os.path.join(data, "exemplars"), os.path.join(scratch, "data", "exemplars"))
    for name in ("default.tsyn", "README.md"):
        shutil.copy(os.path.join(data, name), os.path.join(scratch, "data", name))
    # The project's database cache as the demo leaves it; on a fresh clone, the tests' default
    # database (the same exemplars and options), else the first command builds it.
    for cache in (os.path.join(data, "default.tsdb"), os.path.join(build, "test_tmp", "default.tsdb")):
        if os.path.exists(cache):
            shutil.copy(cache, os.path.join(scratch, "data", "default.tsdb"))
            break
    # "my_dem.tif": a shipped real DEM (16-bit PNG + sidecar) as a georeferenced GeoTIFF in metres.
    png = os.path.join(data, "exemplars", "orom_alaska.png")
    side = json.load(open(png[:-4] + ".json"))
    spacing = float(side["meters_per_pixel"][0])
    size = min(side["width"], side["height"])
    lo, hi = side["height_min_m"], side["height_max_m"]
    subprocess.run(["gdal_translate", "-q", "-ot", "Float32", "-scale", "0", "65535", str(lo), str(hi),
                    "-a_srs", "EPSG:32606", "-a_ullr", "500000", "7000000", str(500000 + size * spacing),
                    str(7000000 - size * spacing), "-srcwin", "0", "0", str(size), str(size), png,
                    os.path.join(scratch, "my_dem.tif")], check=True)


def run_block(lines, scratch, env):
    script = "set -euo pipefail\n" + "\n".join(lines) + "\n"
    server = next((pattern for name, pattern in SERVES.items() if name in script), None)
    proc = subprocess.Popen(["bash", "-c", script], cwd=scratch, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)
    output = []
    for line in proc.stdout:
        output.append(line)
        if server and server.search(line):
            os.killpg(proc.pid, signal.SIGTERM)
            proc.wait()
            return 0, "".join(output)
    rc = proc.wait()
    if server and rc == 0:
        output.append("(the server ended without saying it serves)\n")
        rc = 1
    return rc, "".join(output)


def start_xvfb():
    """An Xvfb of our own on a display it picks itself (-displayfd: no race with other tests' servers,
    which xvfb-run -a has: two of them can take the same number)."""
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", "1280x720x24", "-nolisten", "tcp"],
                              pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as pipe:
        number = pipe.readline().strip()
    if not number:
        raise SystemExit("Xvfb did not start (is the xvfb package installed?)")
    return server, ":" + number


def main():
    repo, build, scratch = (os.path.abspath(a) for a in sys.argv[1:4])
    make_scratch(repo, build, scratch)
    xvfb, display = start_xvfb()
    try:
        return run_all(repo, build, scratch, display)
    finally:
        xvfb.terminate()
        xvfb.wait()


def run_all(repo, build, scratch, display):
    # OSG_WINDOW: stock osgviewer opens a window, as on a desktop: its default full screen on Xvfb
    # with bookworm's Mesa software GL aborts at exit about 1 run in 3, whatever it shows (the
    # measurements are in docs/plugin.md, "Without a display").
    env = dict(os.environ, DISPLAY=display, OSG_RUN_FRAME_COUNT="20", OSG_NOTIFY_LEVEL="WARN",
               OSG_WINDOW="0 0 1280 720")
    env.setdefault("POCL_CACHE_DIR", os.path.join(build, "pocl_cache"))
    failures, ran = [], 0
    for block in code_blocks(os.path.join(repo, "README.md"), "sh"):
        commands = [line for line in block if is_command(line) and line.split("#", 1)[0].strip() not in NOT_RUN_HERE]
        if not commands:
            continue
        ran += len(commands)
        print("$ " + "\n$ ".join(commands), flush=True)
        rc, output = run_block(commands, scratch, env)
        print(output[-4000:], flush=True)
        if rc != 0:
            failures.append(f"exit {rc}: " + " ; ".join(commands))
    # Python snippets, with the module where the README says it is (PYTHONPATH=build/python).
    python_env = dict(env, PYTHONPATH=os.path.join(scratch, "build", "python"))
    for block in code_blocks(os.path.join(repo, "README.md"), "python"):
        ran += 1
        print(">>> " + "\n... ".join(block), flush=True)
        done = subprocess.run(["/usr/bin/python3", "-c", "\n".join(block)], cwd=scratch, env=python_env)
        if done.returncode != 0:
            failures.append(f"exit {done.returncode}: python: " + " ; ".join(block))
    # What the README says the commands write.
    for written in ("my.tsdb", "out/mine.tif", "out/mine.png", "out/unreal/terrain.png", "out/world/tileset.json",
                    "out/terrain.osgb", "out/default.tif"):
        if not os.path.exists(os.path.join(scratch, written)):
            failures.append(f"{written}: not written")
    if ran < 8:
        failures.append(f"only {ran} README commands found: is README.md's layout what this test reads?")
    for f in failures:
        print("FAILED: " + f, file=sys.stderr)
    print(f"{ran} README commands run, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
