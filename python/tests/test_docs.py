"""docs/python.md's examples run as printed, from a copy of the repository's data/, and write what the
CLI writes."""
import pathlib
import re
import shutil
import subprocess
import sys

from conftest import BIN_DIR, DATA_DIR, DATABASE, run_cli

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"


def examples():
    return re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)


def test_the_examples_run_and_write_what_the_cli_writes(tmp_path, database):
    blocks = examples()
    assert len(blocks) == 2
    shutil.copytree(DATA_DIR, tmp_path / "data", ignore=shutil.ignore_patterns("*.tsdb"))
    # The test database is the shipped default's (same exemplars and options): a valid cache there.
    shutil.copyfile(DATABASE, tmp_path / "data" / "default.tsdb")
    for block in blocks:
        done = subprocess.run([sys.executable, "-c", block], cwd=tmp_path, capture_output=True, text=True)
        assert done.returncode == 0, block + done.stdout + done.stderr
    run_cli("synth", tmp_path / "data" / "default.tsyn", "-o", tmp_path / "out" / "cli.tif")
    assert (tmp_path / "out" / "default.tif").read_bytes() == (tmp_path / "out" / "cli.tif").read_bytes()
    assert (tmp_path / "out" / "peak.heights").is_file()
    for lod in ["peak.glb", "peak_lod1.glb", "peak_lod2.glb"]:
        assert (tmp_path / "out" / lod).stat().st_size > 0, lod
