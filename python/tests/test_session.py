"""terrasynth.edit: edits, exact undo, and a save that the CLI, open() and edit() read back bit for bit."""
import json

import numpy as np
import pytest

import terrasynth
from conftest import read_f32, run_cli, same_bits, write_project


@pytest.fixture
def small_project(tmp_path, database):
    return write_project(tmp_path, size=(96, 80), seed=3)


def test_edits_undo_exactly_and_the_save_reads_back_bit_for_bit(tmp_path, small_project):
    session = terrasynth.edit(str(small_project))
    assert session.extent == (0, 0, 96, 80) and not session.is_dirty and not session.can_undo
    before = session.heights()
    assert before.shape == (80, 96) and same_bits(before, terrasynth.open(str(small_project)).heights())

    point = session.add_point(48, 40, float(before[40, 48]) + 250.0, radius_px=24)
    with_point = session.heights()
    assert session.point_ids == [point] and session.is_dirty
    assert with_point[40, 48] > before[40, 48] + 100.0
    assert session.undo() is not None and same_bits(session.heights(), before)
    assert session.redo() is not None and same_bits(session.heights(), with_point)

    low, high = float(before.min()), float(before.max())
    curve = session.add_curve(np.array([[8.0, 70.0], [88.0, 60.0]]),
                              [{"t": 0.0, "height_m": low}, {"t": 1.0, "height_m": (low + high) / 2}])
    assert session.curve_ids == [curve]
    assert session.paint_types([(10, 10), (40, 12)], 6, session.type_names[1]) is not None
    changed = session.add_layer({"type": "peak", "center": [30, 30], "height_m": 400, "spread_px": 8})
    assert changed is not None and session.layers[-1]["type"] == "peak"
    edited = session.heights()
    assert session.heights(20, 20, 8, 8).shape == (8, 8) and same_bits(session.heights(20, 20, 8, 8), edited[20:28, 20:28])

    saved = tmp_path / "edited.tsyn"
    session.save(str(saved))
    assert not session.is_dirty and session.path == str(saved)
    doc = json.loads(saved.read_text())
    assert len(doc["constraints"]["points"]) == 1 and len(doc["constraints"]["curves"]) == 1
    assert doc["layers"][-1]["type"] == "peak" and doc["edited_heights"]

    reopened = terrasynth.open(str(saved))
    assert reopened.uses_edited_heights and same_bits(reopened.heights(), edited)
    run_cli("synth", saved, "-o", tmp_path / "cli.f32")
    assert same_bits(read_f32(tmp_path / "cli.f32"), edited)
    again = terrasynth.edit(str(saved))
    assert same_bits(again.heights(), edited)
    assert len(again.point_ids) == 1 and len(again.curve_ids) == 1 and again.layers[-1]["type"] == "peak"

    # The session exports what the reopened project exports.
    (tmp_path / "a").mkdir(), (tmp_path / "b").mkdir()
    session.export_gltf(str(tmp_path / "a" / "t.glb"), tile=32)
    reopened.export_gltf(str(tmp_path / "b" / "t.glb"), tile=32)
    assert (tmp_path / "a" / "t.glb").read_bytes() == (tmp_path / "b" / "t.glb").read_bytes()


def test_refused_edits_raise_and_change_nothing(tmp_path, small_project):
    session = terrasynth.edit(str(small_project))
    before = session.heights()
    with pytest.raises(terrasynth.Error, match="point.height_m"):
        session.add_point(10, 10, float("nan"))
    with pytest.raises(terrasynth.Error, match="no-such-type|type"):
        session.paint_types([(10, 10)], 4, "no-such-type")
    with pytest.raises(terrasynth.Error, match="spread_px"):
        session.add_layer({"type": "peak", "center": [3, 3], "height_m": 10, "spread_px": -1})
    with pytest.raises(terrasynth.Error, match="layers"):
        session.add_layer("{not json")
    with pytest.raises(ValueError, match="edit layer"):
        session.add_layer({"type": "base", "source": "blank", "height_m": 5})
    with pytest.raises(ValueError, match="unknown key 'hieght_m'"):
        session.add_curve([(0, 0), (10, 10)], [{"t": 0, "hieght_m": 5}])
    with pytest.raises(ValueError, match="course"):
        session.add_curve([0, 1, 2], [{"t": 0, "height_m": 5}])
    with pytest.raises(terrasynth.Error):
        session.remove_point(123456)
    with pytest.raises(terrasynth.Error, match="tsyn"):
        session.save(str(tmp_path / "edited.png"))
    with pytest.raises(ValueError, match="seed"):
        session.reseed(2**33)
    assert session.undo() is None and not session.can_undo and not session.is_dirty
    assert same_bits(session.heights(), before)
    with pytest.raises(terrasynth.Error, match="missing.tsyn"):
        terrasynth.edit(str(tmp_path / "missing.tsyn"))
