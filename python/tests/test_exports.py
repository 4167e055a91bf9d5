"""Exports (GeoTIFF and other heightmaps, glTF, engine presets) byte for byte as `terrasynth export`
and `terrasynth synth` write them."""
import pathlib

import numpy as np
import pytest

import terrasynth
from conftest import read_f32, run_cli, same_bits


def files_under(folder: pathlib.Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture
def project(project_path):
    return terrasynth.open(str(project_path))


def test_heightmaps_are_the_cli_export_files(tmp_path, project_path, project):
    for name in ["region.tif", "region.f32", "region.png"]:
        cli_dir, py_dir = tmp_path / "cli" / name, tmp_path / "py" / name
        cli_dir.mkdir(parents=True), py_dir.mkdir(parents=True)
        run_cli("export", project_path, "--region", "30,-20,40,24", "-o", cli_dir / name)
        project.export_heightmap(str(py_dir / name), region=(30, -20, 40, 24))
        assert files_under(py_dir) == files_under(cli_dir), name


def test_a_geotiff_of_the_extent_is_synths_and_write_heightmap_places_arrays_alike(tmp_path, database):
    from conftest import write_project
    path = write_project(tmp_path, size=(36, 28), origin=(-12, 40))
    run_cli("synth", path, "-o", tmp_path / "cli.tif")
    project = terrasynth.open(str(path))
    project.export_heightmap(str(tmp_path / "py.tif"))
    assert (tmp_path / "py.tif").read_bytes() == (tmp_path / "cli.tif").read_bytes()
    # numpy in: the same heights written from an array at the same origin are the same file.
    terrasynth.write_heightmap(str(tmp_path / "array.tif"), project.heights(), project.spacing, origin=(-12, 40))
    assert (tmp_path / "array.tif").read_bytes() == (tmp_path / "cli.tif").read_bytes()
    terrasynth.write_heightmap(str(tmp_path / "array.f32"), project.heights().astype(np.float64), project.spacing)
    assert same_bits(read_f32(tmp_path / "array.f32"), project.heights())


def test_gltf_is_the_cli_export(tmp_path, project_path, project):
    (tmp_path / "cli").mkdir(), (tmp_path / "py").mkdir()
    run_cli("export", project_path, "--region", "0,0,65,49", "--tile", "32", "--lods", "2", "--colors",
            "-o", tmp_path / "cli" / "terrain.glb")
    stats = project.export_gltf(str(tmp_path / "py" / "terrain.glb"), region=(0, 0, 65, 49), tile=32, lods=2,
                                colors=True)
    assert files_under(tmp_path / "py") == files_under(tmp_path / "cli")
    assert stats["tiles"] == (2, 2) and len(stats["lods"]) == 2 and len(stats["files"]) == 2
    assert stats["file_bytes"] == sum(len(b) for b in files_under(tmp_path / "py").values())


def test_engine_preset_is_the_cli_export(tmp_path, project_path, project):
    (tmp_path / "cli").mkdir(), (tmp_path / "py").mkdir()
    run_cli("export", project_path, "--preset", "unity", "--region", "0,0,20,20", "-o", tmp_path / "cli" / "t.raw")
    written = project.export_engine("unity", str(tmp_path / "py" / "t.raw"), region=(0, 0, 20, 20))
    assert files_under(tmp_path / "py") == files_under(tmp_path / "cli")
    assert written["height_max_m"] > written["height_min_m"] and written["summary"].startswith("Unity Terrain")
    assert len(written["files"]) == len(files_under(tmp_path / "py"))


def test_export_errors_name_the_problem(tmp_path, project):
    with pytest.raises(terrasynth.Error, match="unknown heightmap extension|\\.bmp"):
        project.export_heightmap(str(tmp_path / "out.bmp"))
    with pytest.raises(terrasynth.Error, match="preset"):
        project.export_engine("cryengine", str(tmp_path / "t.png"))
    with pytest.raises(ValueError, match="tile"):
        project.export_gltf(str(tmp_path / "t.glb"), tile=0)
    with pytest.raises(ValueError, match="lod_method"):
        project.export_gltf(str(tmp_path / "t.glb"), lod_method="nanite")
    with pytest.raises(ValueError, match="width"):
        project.export_heightmap(str(tmp_path / "t.tif"), region=(0, 0, 1, 5))
    with pytest.raises(ValueError, match="2-D"):
        terrasynth.write_heightmap(str(tmp_path / "a.tif"), np.zeros(5), 10.0)
    with pytest.raises(ValueError, match="spacing"):
        terrasynth.write_heightmap(str(tmp_path / "a.tif"), np.zeros((2, 2)), float("nan"))
