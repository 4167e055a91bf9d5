"""The GIL is released while the runtime works, and Ctrl-C stops a synthesis between two levels."""
import signal
import subprocess
import sys
import textwrap
import threading

import numpy as np

import terrasynth
from conftest import same_bits, write_project

NOTE = "terrasynth: the synthesis stopped between two pyramid levels"


def test_other_python_threads_run_during_a_synthesis(tmp_path, database):
    project = terrasynth.open(str(write_project(tmp_path)))
    project.heights(0, 0, 8, 8)  # device ready, so the call below is all synthesis
    main = threading.main_thread().ident
    done = threading.Event()
    seen_in_call = []

    def watch():
        # Python code of this thread can only run while the main thread is in the call if the call
        # released the GIL; each pass that finds it there counts.
        while not done.is_set():
            frame = sys._current_frames().get(main)
            if frame is not None and frame.f_code.co_name == "synthesize_while_watched":
                seen_in_call.append(frame.f_lineno)
            done.wait(0.001)

    def synthesize_while_watched():
        return project.heights(0, 0, 512, 512)

    watcher = threading.Thread(target=watch)
    watcher.start()
    try:
        heights = synthesize_while_watched()
    finally:
        done.set()
        watcher.join()
    assert heights.shape == (512, 512)
    # With the GIL held the watcher would get in at most at the call's two ends.
    assert len(seen_in_call) >= 10, f"the watcher ran {len(seen_in_call)} times during the call"


CHILD = textwrap.dedent('''
    import signal, sys
    import terrasynth

    NOTE = "terrasynth: the synthesis stopped between two pyramid levels"
    armed = False

    def on_sigint(signum, frame):
        # What Ctrl-C does (KeyboardInterrupt), once per arming: the handler disarms itself before it
        # raises, so a second SIGINT of the parent's stream cannot land in the except clause below
        # (or anywhere else outside a try) while the first is being handled.
        global armed
        if armed:
            armed = False
            raise KeyboardInterrupt

    signal.signal(signal.SIGINT, on_sigint)
    project = terrasynth.open(sys.argv[1])
    session = terrasynth.edit(sys.argv[1])
    small = project.heights(0, 0, 16, 16)
    extent = session.heights()
    print("ready", flush=True)

    def stop_one(call, restore=lambda: None):
        # The parent sends SIGINT every few milliseconds. Most land inside the call; one that lands
        # outside it (no note) or a call that finished first leaves the state to restore (disarmed),
        # and the call is tried again.
        global armed
        for attempt in range(200):
            armed = True
            try:
                call()
                armed = False
            except KeyboardInterrupt as e:
                if NOTE in getattr(e, "__notes__", []):
                    return attempt
            restore()
        raise SystemExit("never stopped inside the call")

    stop_one(lambda: project.heights(0, 0, 1024, 1024))
    print("project stopped", flush=True)
    stop_one(lambda: session.reseed(77), restore=lambda: session.can_undo and session.undo())
    # The parent's stream of SIGINTs stops once it reads the line below; one still in flight must not
    # reach the default handler that Python puts back at exit (it would kill this process).
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    print("session stopped", flush=True)
    same = project.heights(0, 0, 16, 16).tobytes() == small.tobytes()
    unchanged = session.heights().tobytes() == extent.tobytes() and not session.can_undo
    print("after", same, unchanged, flush=True)
''')


def test_ctrl_c_stops_a_synthesis_and_leaves_project_and_session_as_they_were(tmp_path, database):
    path = write_project(tmp_path, size=(384, 384))
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(path)], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "ready"
        stopper = threading.Event()

        def interrupt():
            while not stopper.wait(0.005):
                child.send_signal(signal.SIGINT)

        sender = threading.Thread(target=interrupt)
        sender.start()
        try:
            lines = [child.stdout.readline().strip() for _ in range(2)]
        finally:
            stopper.set()
            sender.join()
        assert lines == ["project stopped", "session stopped"]
        assert child.stdout.readline().split() == ["after", "True", "True"]
        assert child.wait() == 0
    finally:
        if child.poll() is None:
            child.kill()
