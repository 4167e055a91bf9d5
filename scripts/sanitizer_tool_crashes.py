#!/usr/bin/python3
"""Tells a sanitizer's own crash from a finding, after a failed ctest run in BUILD_DIR.

LeakSanitizer checks for leaks at exit by stopping every thread from a tracer (ptrace). That tracer
sometimes dies of a segfault of its own ("Tracer caught signal 11", "LeakSanitizer has encountered a
fatal error") while threads are still running, here PoCL's device workers; it happens at random,
after the test has passed, and is a known defect of the tool (google/sanitizers#1353). CI hit it once
in Coherence.ResynthesisWithUnchangedInputsIsIdentical (2026-12-02) and failed a clean run.

Reads Testing/Temporary/LastTestsFailed.log and LastTest.log and prints the failed tests one per
line. Exit 0: every failed test is such a crash (its GoogleTest run ended "[  PASSED  ]" and it has
no sanitizer report: no "ERROR: AddressSanitizer", no "detected memory leaks", no "runtime error"),
so scripts/sanitize.sh reruns those once. Exit 1: at least one failure is real, or the logs are
missing; nothing is rerun.
"""
import pathlib
import re
import sys

TOOL_CRASH = "LeakSanitizer has encountered a fatal error"
FINDINGS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer: detected memory leaks", "runtime error:",
            "ThreadSanitizer", "[  FAILED  ]")


def outputs_by_test(log_text):
    """Maps each test name in ctest's LastTest.log to the text ctest recorded for it (from its
    "n/N Test: name" line to the next test's)."""
    starts = list(re.finditer(r"^\d+/\d+ Test: (.+)$", log_text, flags=re.M))
    ends = [m.start() for m in starts[1:]] + [len(log_text)]
    return {m.group(1).strip(): log_text[m.start():end] for m, end in zip(starts, ends)}


def main():
    if len(sys.argv) != 2:
        print("usage: sanitizer_tool_crashes.py BUILD_DIR", file=sys.stderr)
        return 2
    temporary = pathlib.Path(sys.argv[1]) / "Testing" / "Temporary"
    try:
        failed_lines = (temporary / "LastTestsFailed.log").read_text().split()
        log_text = (temporary / "LastTest.log").read_text(errors="replace")
    except OSError as error:
        print(f"sanitizer_tool_crashes: {error}", file=sys.stderr)
        return 1
    # LastTestsFailed.log holds "<number>:<name>" per failed test.
    failed = [line.split(":", 1)[1] for line in failed_lines if ":" in line]
    outputs = outputs_by_test(log_text)
    all_tool_crashes = bool(failed)
    for name in failed:
        output = outputs.get(name, "")
        crash = TOOL_CRASH in output and "[  PASSED  ]" in output and not any(f in output for f in FINDINGS)
        print(f"{name}: {'sanitizer tool crash after a passing run' if crash else 'real failure'}")
        all_tool_crashes = all_tool_crashes and crash
    return 0 if all_tool_crashes else 1


if __name__ == "__main__":
    sys.exit(main())
