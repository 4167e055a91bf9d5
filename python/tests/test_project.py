"""terrasynth.open / from_database: heights, sources and types, bit for bit what the CLI writes."""
import json

import numpy as np
import pytest

import terrasynth
from conftest import read_f32, run_cli, same_bits, write_project


@pytest.mark.parametrize("backend", ["opencl", "reference"])
def test_heights_are_the_cli_synth_output_bit_for_bit(tmp_path, project_path, backend):
    # `synth --size --origin` makes the extent the window; Python asks the whole project for it.
    run_cli("synth", project_path, "--size", "48x40", "--origin", "100,-30", "--backend", backend,
            "-o", tmp_path / "cli.f32")
    project = terrasynth.open(str(project_path), backend=backend)
    heights = project.heights(100, -30, 48, 40)
    assert heights.dtype == np.float32 and heights.shape == (40, 48)
    assert same_bits(heights, read_f32(tmp_path / "cli.f32"))
    # A coarser level: the CLI's --level 1 writes the extent at that level.
    run_cli("synth", project_path, "--size", "64x48", "--origin", "100,-32", "--level", "1", "--backend", backend,
            "-o", tmp_path / "cli_level1.f32")
    assert same_bits(project.heights(50, -16, 32, 24, level=1), read_f32(tmp_path / "cli_level1.f32"))


def test_overrides_and_the_default_window_are_the_extent(project_path):
    whole = terrasynth.open(str(project_path))
    assert whole.extent == (0, 0, 1024, 1024) and whole.seed == 1 and whole.path == str(project_path)
    assert whole.spacing > 0 and len(whole.type_names) == 4 and len(whole.exemplar_names) == 4
    small = terrasynth.open(str(project_path), size=(40, 32), origin=(8, -8))
    assert small.extent == (8, -8, 40, 32)
    assert same_bits(small.heights(), whole.heights(8, -8, 40, 32))
    other_seed = terrasynth.open(str(project_path), size=(40, 32), origin=(8, -8), seed=2)
    assert other_seed.seed == 2
    assert not np.array_equal(other_seed.heights(), small.heights())


def test_sources_and_types_follow_the_windowing_contract(project_path):
    project = terrasynth.open(str(project_path))
    sx, sy, exemplar = project.sources(200, 300, 64, 48)
    assert sx.shape == sy.shape == exemplar.shape == (48, 64)
    assert sx.dtype == np.float32 and exemplar.dtype == np.uint8
    assert exemplar.max() < len(project.exemplar_names) and sx.min() >= 0 and sy.min() >= 0
    # A window inside the first gives the same coordinates.
    inner = project.sources(216, 310, 20, 16)
    assert same_bits(inner[0], sx[10:26, 16:36]) and same_bits(inner[2], exemplar[10:26, 16:36])
    types = project.types(200, 300, 64, 48)
    assert types.shape == (48, 64) and types.max() < len(project.type_names)
    # Each exemplar has one type (the shipped exemplars' terrain_class), so type is a function of exemplar.
    for e in np.unique(exemplar):
        assert len(np.unique(types[exemplar == e])) == 1


def test_heights_at_world_points_are_the_grid_samples(project_path):
    project = terrasynth.open(str(project_path))
    grid = project.heights(10, 20, 4, 3)
    s = project.spacing
    points = np.array([[(10 + i) * s, -(20 + j) * s] for j in range(3) for i in range(4)])
    at = project.heights_at(points)
    assert at.dtype == np.float64 and at.shape == (12,)
    assert np.array_equal(at.astype(np.float32).reshape(3, 4), grid)


def test_from_database_is_synth_with_db_size_and_seed(tmp_path, database):
    run_cli("synth", "--db", database, "--size", "40x24", "--seed", "9", "-o", tmp_path / "cli.f32")
    project = terrasynth.from_database(str(database), (40, 24), seed=9)
    assert project.extent == (0, 0, 40, 24) and project.path == ""
    assert same_bits(project.heights(), read_f32(tmp_path / "cli.f32"))


def test_bad_paths_raise_the_runtimes_message(tmp_path):
    with pytest.raises(terrasynth.Error, match="no/such.tsyn"):
        terrasynth.open("no/such.tsyn")
    broken = tmp_path / "broken.tsyn"
    broken.write_text('{"format": "terrasynth-project", "version": 1, "size": [0, 5]')
    with pytest.raises(terrasynth.Error, match="broken.tsyn"):
        terrasynth.open(str(broken))
    with pytest.raises(terrasynth.Error, match="missing.tsdb"):
        terrasynth.from_database(str(tmp_path / "missing.tsdb"), (8, 8))
    assert issubclass(terrasynth.Error, RuntimeError)


def test_bad_windows_and_arguments_raise_instead_of_crashing(project_path):
    project = terrasynth.open(str(project_path), size=(16, 16))
    for window, name in [((0, 0, 0, 5), "width"), ((0, 0, 5, 20000), "height"), ((2**40, 0, 5, 5), "x"),
                         ((0, -2**40, 5, 5), "y")]:
        with pytest.raises(ValueError, match=name):
            project.heights(*window)
    with pytest.raises(ValueError, match="level: expected a finite number in \\[0, 12\\]"):
        project.heights(0, 0, 4, 4, level=13)
    with pytest.raises(terrasynth.Error, match="output level"):  # the database has levels 0..6
        project.heights(0, 0, 4, 4, level=9)
    with pytest.raises(ValueError, match="all of x, y, width, height"):
        project.heights(0, 0)
    with pytest.raises(TypeError):
        project.heights(0, 0, 2**70, 4)
    with pytest.raises(ValueError, match="seed"):
        terrasynth.open(str(project_path), seed=-1)
    with pytest.raises(ValueError, match="backend"):
        terrasynth.open(str(project_path), backend="cuda")
    with pytest.raises(ValueError, match="drainage"):
        terrasynth.open(str(project_path), drainage="sometimes")
    with pytest.raises(ValueError, match="size"):
        terrasynth.open(str(project_path), size=(0, 4))
    with pytest.raises(terrasynth.Error, match="origin"):
        terrasynth.open(str(project_path), origin=(2**40, 0))
    with pytest.raises(ValueError, match="heights_at|points"):
        project.heights_at(np.zeros((3, 3)))
    # The project still answers after all that.
    assert project.heights(0, 0, 2, 2).shape == (2, 2)


def test_stale_sidecar_is_a_warning(tmp_path, database):
    path = write_project(tmp_path, size=(32, 32))
    doc = json.loads(path.read_text())
    doc["edited_heights"] = "world.heights"  # names a sidecar that is not there
    path.write_text(json.dumps(doc))
    with pytest.warns(UserWarning, match="edited heights"):
        project = terrasynth.open(str(path))
    assert not project.uses_edited_heights and project.warnings
