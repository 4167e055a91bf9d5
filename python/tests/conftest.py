"""Shared fixtures of the Python module's tests (run by ctest, label python; see python/CMakeLists.txt).

They use the default test database the C++ tests share (<build>/test_tmp/default.tsdb, built by the
ctest fixture test_database_default from the shipped data/exemplars) and the built `terrasynth` CLI,
which the module's results are compared with bit for bit.
"""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import terrasynth

BIN_DIR = pathlib.Path(os.environ["TERRASYNTH_TEST_BIN_DIR"])
TMP_DIR = pathlib.Path(os.environ["TERRASYNTH_TEST_TMP"])
DATA_DIR = pathlib.Path(os.environ["TERRASYNTH_TEST_DATA_DIR"])
DATABASE = TMP_DIR / "default.tsdb"


@pytest.fixture(scope="session")
def database() -> pathlib.Path:
    assert DATABASE.is_file(), f"{DATABASE} is missing: run the tests through ctest (fixture test_database_default)"
    return DATABASE


def write_project(folder: pathlib.Path, size=(1024, 1024), origin=(0, 0), seed=1, name="world.tsyn") -> pathlib.Path:
    """A project over the default test database, as tests/test_support.cpp writes them."""
    path = folder / name
    path.write_text(json.dumps({"format": "terrasynth-project", "version": 1, "database": str(DATABASE),
                                "size": list(size), "origin": list(origin), "synthesis": {"seed": seed}}))
    return path


@pytest.fixture
def project_path(tmp_path, database) -> pathlib.Path:
    return write_project(tmp_path)


def run_cli(*args) -> str:
    """Runs the built terrasynth CLI; fails the test with its output when it fails."""
    done = subprocess.run([str(BIN_DIR / "terrasynth"), *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, f"terrasynth {' '.join(map(str, args))}:\n{done.stdout}{done.stderr}"
    return done.stdout


def read_f32(path: pathlib.Path) -> np.ndarray:
    """A .f32 heightmap and its sidecar, as the CLI writes them."""
    side = json.loads(path.with_suffix(".json").read_text())
    return np.fromfile(path, dtype="<f4").reshape(side["height"], side["width"])


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()
