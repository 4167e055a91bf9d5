#!/usr/bin/python3
"""Kill -9 at random moments of one long editor session, and recover each time (issue 54 item 2).

One project is edited by a scripted designer who places point constraints one after another without
pausing (so the autosave is never written in a pause, only when an edit has waited its longest:
EditorOptions::autosave_max_delay_s). At a random moment the editor is killed with SIGKILL; the next
round starts it again with --recover and goes on editing from what it recovered. After every kill:

- the autosave holds a prefix of the edits made (point 1..P, nothing out of order or half-written),
  and `--recover` opens it (the round after it reaches its first edit; the last kill is followed by
  a run that only reads the heights back and quits with status 0);
- every edit older than the longest autosave delay plus SLACK_S at the moment of the kill is in it:
  what a crash loses is at most the edits of the last autosave interval.

Writes OUT/kills.json (per kill: how long the round ran, edits made, points recovered, edits lost and
the age of the oldest lost one) and exits 1 on any failed check.

    scripts/soak_editor_kill.py [--kills 20] [--seed 54] [--build build] [--out build/soak_editor_kill]
"""
import argparse
import json
import os
import random
import re
import signal
import subprocess
import sys
import threading
import time

MAX_DELAY_S = 10.0  # EditorOptions::autosave_max_delay_s, the editor's default
# The autosave is written after an edit has waited MAX_DELAY_S and the current gesture ended, and
# writing it (~30 MB at 1024^2) takes a moment more, longer on a loaded machine.
SLACK_S = 10.0
AERIAL_START = "settle\nview aerial 512 512 60000\nsettle\n"  # as tests/editor_gui_test.cpp


def grid_positions():
    """Screen positions on the terrain (1280x720, the middle 30 km of a 60 km aerial view), 24 px
    apart so that a click never lands on an earlier point's handle (kHandlePx, 12 px): 529, enough
    for 20 kills of a quiet machine's two edits a second (324 at 30 px ran out after 16)."""
    return [(x, y) for y in range(100, 640, 24) for x in range(380, 920, 24)]


def project_points(path):
    try:
        with open(path) as f:
            return json.load(f).get("constraints", {}).get("points", [])
    except FileNotFoundError:
        return []


class Editor:
    """One editor process whose output lines are timestamped as they arrive."""

    def __init__(self, args, env, log_path):
        self.lines = []  # (monotonic seconds, line)
        self.changed = threading.Condition()
        self.log = open(log_path, "w")
        self.proc = subprocess.Popen(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, bufsize=1)
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.proc.stdout:
            with self.changed:
                self.lines.append((time.monotonic(), line.rstrip("\n")))
                self.changed.notify_all()
            self.log.write(line)
            self.log.flush()
        with self.changed:
            self.changed.notify_all()

    def wait_for(self, pattern, timeout_s=900.0):
        """The time the first line matching `pattern` arrived; None when the editor ended first."""
        deadline = time.monotonic() + timeout_s
        with self.changed:
            while True:
                for t, line in self.lines:
                    if re.search(pattern, line):
                        return t
                if self.proc.poll() is not None and not self.reader.is_alive():
                    return None
                if time.monotonic() > deadline:
                    return None
                self.changed.wait(1.0)

    def kill(self):
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait()
        self.reader.join()
        self.log.close()

    def finish(self, timeout_s=900.0):
        self.proc.wait(timeout=timeout_s)
        self.reader.join()
        self.log.close()
        return self.proc.returncode


def start_display():
    """An Xvfb of our own, on a display it picks (-displayfd), unless one is given."""
    if os.environ.get("DISPLAY"):
        return None, os.environ["DISPLAY"]
    r, w = os.pipe()
    xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", "1280x720x24", "-nolisten", "tcp"],
                            pass_fds=(w,), stderr=subprocess.DEVNULL)
    os.close(w)
    number = b""
    while not number.endswith(b"\n"):
        chunk = os.read(r, 16)
        if not chunk:
            raise SystemExit("soak_editor_kill: Xvfb did not start")
        number += chunk
    os.close(r)
    return xvfb, ":" + number.decode().strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--kills", type=int, default=20)
    ap.add_argument("--seed", type=int, default=54)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default=None)
    ap.add_argument("--longest-round-s", type=float, default=30.0,
                    help="each round is killed at a uniform random moment up to this long after its first edit")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    out = os.path.abspath(a.out or os.path.join(build, "soak_editor_kill"))
    os.makedirs(out, exist_ok=True)
    editor = os.path.join(build, "bin", "terrasynth_editor")
    database = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "default.tsdb")
    if not os.access(editor, os.X_OK):
        raise SystemExit(f"soak_editor_kill: {editor} is not built")
    rng = random.Random(a.seed)
    project = os.path.join(out, "p.tsyn")
    autosave = os.path.join(out, "p.autosave.tsyn")
    for name in os.listdir(out):
        if name.startswith("p.") or name.endswith((".script", ".log", ".f32", ".json")):
            os.remove(os.path.join(out, name))
    with open(project, "w") as f:
        json.dump({"format": "terrasynth-project", "version": 1, "database": os.path.abspath(database),
                   "size": [1024, 1024], "constraints": {}}, f)
    env = dict(os.environ)
    env.setdefault("POCL_CACHE_DIR", os.path.join(build, "pocl_cache"))
    xvfb, env["DISPLAY"] = start_display()
    positions = grid_positions()
    failures, kills, previous_points = [], [], []
    try:
        for round_index in range(a.kills + 1):
            held = len(project_points(autosave))
            # The last round reads back and quits; so does a session that has used every position.
            last = round_index == a.kills or held >= len(positions)
            if held >= len(positions):
                print(f"soak_editor_kill: every position holds a point after {len(kills)} kills", flush=True)
            script = os.path.join(out, f"round{round_index}.script")
            with open(script, "w") as f:
                f.write(AERIAL_START)
                if last:  # after the last kill: read back and quit
                    f.write(f"heights {out}/recovered.f32\nquit\n")
                else:
                    f.write("tool point\n")
                    for i in range(held, len(positions)):
                        x, y = positions[i]
                        f.write(f"move {x} {y}\nclick\nsettle\necho EDIT {i + 1}\n")
                    f.write("echo OUT-OF-POSITIONS\nsleep 600000\n")
            e = Editor([editor, project, "--recover", "--script", script], env,
                       os.path.join(out, f"round{round_index}.log"))
            if last:
                code = e.finish()
                recovered = any("recovering" in line for _, line in e.lines) or held == 0
                if code != 0 or not recovered:
                    failures.append(f"the last --recover run exited {code} (recovering: {recovered}); "
                                    f"see round{round_index}.log")
                break
            first_edit = e.wait_for(rf"^EDIT {held + 1}$")
            if first_edit is None:
                e.kill()
                failures.append(f"round {round_index}: --recover did not reach its first edit "
                                f"(held {held}); see round{round_index}.log")
                break
            if round_index > 0 and held > 0 and not any("recovering" in line for _, line in e.lines):
                failures.append(f"round {round_index}: the autosave was not recovered")
            time.sleep(rng.uniform(0.0, a.longest_round_s))
            t_kill = time.monotonic()
            ended_by_itself = e.proc.poll()  # a crash before the kill (an abort, a signal)
            e.kill()
            if ended_by_itself is not None:
                failures.append(f"round {round_index}: the editor ended by itself (status {ended_by_itself}) "
                                f"before the kill; see round{round_index}.log")
            done = {int(m.group(1)): t for t, line in e.lines if (m := re.match(r"^EDIT (\d+)$", line))}
            made = max(done) if done else held
            points = project_points(autosave)
            saved = len(points)
            oldest_lost_s = max((t_kill - done[i] for i in range(saved + 1, made + 1) if i in done), default=0.0)
            kill = {"round": round_index, "ran_s": round(t_kill - first_edit, 2), "held_at_start": held,
                    "edits_made": made, "points_recovered": saved, "edits_lost": max(0, made - saved),
                    "oldest_lost_edit_age_s": round(oldest_lost_s, 2),
                    "autosaves": sum("autosaved" in line for _, line in e.lines),
                    # How long the editor had printed nothing when it was killed (an edit, a settle
                    # or an autosave that did not end).
                    "silent_s": round(t_kill - max(t for t, _ in e.lines), 2)}
            kills.append(kill)
            print(json.dumps(kill), flush=True)
            # The edit in flight at the kill may have reached the autosave before its echo did.
            if saved < held or saved > made + 1:
                failures.append(f"round {round_index}: {saved} points recovered, {held} held before, {made} made")
            # What an earlier autosave held is still there, unchanged and first.
            if points[:held] != previous_points:
                failures.append(f"round {round_index}: the {held} points recovered before are not the first "
                                f"of the {saved} recovered now")
            previous_points = points
            if oldest_lost_s > MAX_DELAY_S + SLACK_S:
                failures.append(f"round {round_index}: lost an edit made {oldest_lost_s:.1f} s before the kill "
                                f"(longest autosave delay {MAX_DELAY_S} s + {SLACK_S} s)")
    finally:
        if xvfb:
            xvfb.terminate()
            xvfb.wait()
    summary = {"kills": kills, "max_delay_s": MAX_DELAY_S, "slack_s": SLACK_S, "failures": failures,
               "edits_made": sum(k["edits_made"] - k["held_at_start"] for k in kills),
               "edits_lost": sum(k["edits_lost"] for k in kills),
               "oldest_lost_edit_age_s": max((k["oldest_lost_edit_age_s"] for k in kills), default=0.0)}
    with open(os.path.join(out, "kills.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(f"soak_editor_kill: {len(kills)} kills, {summary['edits_made']} edits, {summary['edits_lost']} lost, "
          f"oldest lost {summary['oldest_lost_edit_age_s']} s; {len(failures)} failures")
    for msg in failures:
        print("FAIL:", msg)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
