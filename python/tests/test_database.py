"""terrasynth.build_database: the bytes `terrasynth db build` writes, and synthesis from it."""
import pytest

import terrasynth
from conftest import DATA_DIR, read_f32, run_cli, same_bits

EXEMPLAR = DATA_DIR / "exemplars" / "orom_rockies.png"  # a shipped DEM, 648 x 648


def test_build_database_is_the_cli_db_build_and_synthesizes_like_synth_db(tmp_path):
    stages = []
    built = terrasynth.build_database([str(EXEMPLAR)], str(tmp_path / "py.tsdb"), levels=3,
                                      progress=lambda stage, done: stages.append((stage, done)))
    run_cli("db", "build", EXEMPLAR, "--levels", "3", "-o", tmp_path / "cli.tsdb")
    assert (tmp_path / "py.tsdb").read_bytes() == (tmp_path / "cli.tsdb").read_bytes()
    assert built["exemplars"] == ["orom_rockies"] and built["levels"] == 4 and built["meters_per_pixel"] > 90
    assert stages and all(0.0 <= done <= 1.0 for _, done in stages)

    run_cli("synth", "--db", tmp_path / "cli.tsdb", "--size", "32x24", "--seed", "5", "-o", tmp_path / "cli.f32")
    project = terrasynth.from_database(str(tmp_path / "py.tsdb"), (32, 24), seed=5)
    assert same_bits(project.heights(), read_f32(tmp_path / "cli.f32"))


def test_build_errors_raise(tmp_path):
    with pytest.raises(terrasynth.Error, match="nothing.png"):
        terrasynth.build_database([str(tmp_path / "nothing.png")], str(tmp_path / "x.tsdb"))
    with pytest.raises(ValueError, match="levels"):
        terrasynth.build_database([str(EXEMPLAR)], str(tmp_path / "x.tsdb"), levels=0)
    with pytest.raises(ValueError, match="meters_per_pixel"):
        terrasynth.build_database([str(EXEMPLAR)], str(tmp_path / "x.tsdb"), meters_per_pixel=float("inf"))

    def fails(stage, done):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        terrasynth.build_database([str(EXEMPLAR)], str(tmp_path / "x.tsdb"), levels=2, progress=fails)
