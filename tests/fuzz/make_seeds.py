#!/usr/bin/python3
"""Regenerates the seed inputs of the fuzz corpora (tests/fuzz/corpus/<target>/seed_*) from the
shipped exemplars in data/ and the JSON examples in docs/. Inputs found by fuzzing are kept beside
them (crash_*, slow_* or libFuzzer's hash names); this script only rewrites seed_* files.

  /usr/bin/python3 tests/fuzz/make_seeds.py build/bin/terrasynth [exemplar|database|project|cli_flags|edit_sidecar ...]

Needs numpy and PIL (Debian python3-numpy, python3-pil) and a built terrasynth for the database seeds.
"""
import io, json, os, re, struct, subprocess, sys, tempfile

import numpy as np
from PIL import Image

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CORPUS = os.path.join(ROOT, "tests", "fuzz", "corpus")
CLI = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "bin", "terrasynth")


def write(target, name, data):
    os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    with open(os.path.join(CORPUS, target, "seed_" + name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def split_input(first, rest):
    first = first if isinstance(first, bytes) else first.encode()
    return struct.pack("<H", len(first)) + first + rest


def png_bytes(array, mode, **save):
    out = io.BytesIO()
    Image.fromarray(array, mode=mode).save(out, format="PNG", **save)
    return out.getvalue()


def crop(stem, x, y, w, h):
    """A crop of a shipped exemplar: 16-bit samples and the sidecar rewritten for it."""
    image = np.array(Image.open(os.path.join(ROOT, "data", "exemplars", stem + ".png")))
    side = json.load(open(os.path.join(ROOT, "data", "exemplars", stem + ".json")))
    side.update(width=w, height=h, file=stem + "_crop.png")
    return image[y:y + h, x:x + w].astype(np.uint16), side


def exemplar_seeds():
    for i, (stem, w, h) in enumerate([("orom_alaska", 16, 16), ("orom_rockies", 24, 12), ("orom_appalachians", 9, 31)]):
        samples, side = crop(stem, 100 + 7 * i, 200, w, h)
        png16 = png_bytes(samples, "I;16")
        write("exemplar_png", f"{stem}_{w}x{h}", split_input(json.dumps(side, indent=1), png16))
        if i == 0:
            write("exemplar_png", "plain_no_sidecar", split_input(b"", png16))
            masked = dict(side, type_mask="mask.png", type_names=["rock", "ice"])
            write("exemplar_png", "with_type_mask", split_input(json.dumps(masked), png16))
            write("exemplar_png", "spacing_number", split_input(json.dumps(dict(side, meters_per_pixel=30)), png16))
            gray8 = png_bytes((samples >> 8).astype(np.uint8), "L")
            write("exemplar_png", "gray8_is_refused", split_input(json.dumps(side), gray8))
            rgb = np.stack([(samples >> 8).astype(np.uint8)] * 3, axis=-1)
            write("exemplar_png", "rgb8_is_refused", split_input(json.dumps(side), png_bytes(rgb, "RGB")))
            pal = Image.fromarray((samples >> 12).astype(np.uint8), mode="L").convert("P")
            out = io.BytesIO(); pal.save(out, format="PNG")
            write("exemplar_png", "palette_mask", split_input(json.dumps(masked), out.getvalue()))
            write("exemplar_png", "interlaced", split_input(json.dumps(side), png_bytes(samples, "I;16", optimize=False)))
            # The lying header of issue 20: a small file claiming 65536 x 65536.
            lie = bytearray(png16)
            lie[16:24] = struct.pack(">II", 65536, 65536)
            write("exemplar_png", "lying_header", split_input(json.dumps(side), bytes(lie)))
            write("exemplar_png", "width_wraps_int", split_input(json.dumps(dict(side, width=2**32 + 16)), png16))
        heights = (samples.astype(np.float32) / 65535.0 * (side["height_max_m"] - side["height_min_m"]) + side["height_min_m"])
        f32_side = {"file": stem + ".f32", "width": w, "height": h, "format": "float32 little-endian, metres, row-major, row 0 north",
                    "meters_per_pixel": side["meters_per_pixel"], "source": "terrasynth"}
        write("exemplar_f32", f"{stem}_{w}x{h}", split_input(json.dumps(f32_side, indent=1), heights.astype("<f4").tobytes()))
    write("exemplar_f32", "truncated", split_input(json.dumps({"width": 4, "height": 4, "meters_per_pixel": 10}), b"\0" * 60))
    write("exemplar_f32", "nan_heights", split_input(json.dumps({"width": 2, "height": 1, "meters_per_pixel": [10, 10]}),
                                                   struct.pack("<2f", float("nan"), 1.0)))


def database_seeds():
    with tempfile.TemporaryDirectory() as tmp:
        for stem in ("orom_alaska", "orom_rockies"):
            samples, side = crop(stem, 50, 60, 14, 12)
            side["file"] = stem + ".png"
            Image.fromarray(samples, mode="I;16").save(os.path.join(tmp, stem + ".png"))
            json.dump(side, open(os.path.join(tmp, stem + ".json"), "w"))
        db = os.path.join(tmp, "tiny.tsdb")
        subprocess.run([CLI, "db", "build", tmp, "-o", db, "--levels", "1", "-q"], check=True, stdout=subprocess.DEVNULL)
        data = open(db, "rb").read()
    write("database", "tiny_whole_file", b"\0" + data)
    write("database", "tiny_payload", b"\1" + data[32:])


def json_blocks(path):
    text = open(os.path.join(ROOT, path)).read()
    return re.findall(r"```json\n(.*?)```", text, re.S)


def project_seeds():
    write("project", "default", open(os.path.join(ROOT, "data", "default.tsyn")).read())
    base = json.load(open(os.path.join(ROOT, "data", "default.tsyn")))
    for i, block in enumerate(json_blocks("docs/project-format.md")):
        write("project", f"project_format_{i}", block)
    for i, block in enumerate(json_blocks("docs/layers.md")):
        try:
            value = json.loads(block)
        except ValueError:
            continue
        layers = value if isinstance(value, list) else [value]
        write("project", f"layers_{i}", json.dumps(dict(base, layers=layers)))
    write("project", "constraints_all", json.dumps(dict(base, size=[64, 48], constraints={
        "points": [{"x": 10, "y": 12, "height_m": 900, "slope_direction_deg": 45, "slope_angle_deg": 10, "radius_px": 16}],
        "curves": [{"course": [[2, 2], [30, 10], [10, 30], [2, 2]], "spline": True,
                    "widgets": [{"t": 0, "height_m": 800, "left_gradient": -0.5, "right_reach_px": 8}, {"t": 1, "height_m": 1200}]},
                   {"course": [[0, 20], [60, 20]], "spline": False, "widgets": [{"t": 0.5, "height_m": 1000}]}],
        "types": {"strokes": [{"type": "alpine ranges", "radius_px": 6, "points": [[5, 5], [40, 30]]}]},
        "freeze": {"strokes": [{"radius_px": 3, "points": [[20, 20]]}]},
        "pastes": [{"source": [[1, 1], [10, 1], [10, 10]], "target": [30, 30], "height_offset_m": 5},
                   {"exemplar": "hills", "source": [[5, 5], [15, 5], [15, 15]], "target": [3, 3]}]})))
    write("project", "group_layers", json.dumps(dict(base, layers=[{"type": "group", "layers": [
        {"type": "peak", "center": [10, 10], "height_m": 300, "spread_px": 6},
        {"type": "group", "layers": [{"type": "ridge", "points": [[0, 0], [20, 15]], "profile_m": [100, 200], "width_px": 3}]}]}])))
    write("project", "origin_int64_min", json.dumps(dict(base, origin=[-9223372036854775808, 0])))


def cli_seeds():
    commands = [
        "synth\nproject.tsyn\n-o\nout.png\n--size\n256x256\n--origin\n-512,64\n--seed\n3\n--preview\nhs.png",
        "synth\n--db\ndb.tsdb\n-o\nout.f32\n--level\n2\n--sources\nsrc.png\n--backend\nreference",
        "synth\nnew.tsyn\n--coherent-with\nold.tsyn\n-o\nout.png",
        "db\nbuild\ndata/exemplars\n-o\ndb.tsdb\n--levels\n6\n--meters-per-pixel\n90\n--threads\n2\n-q",
        "layers\nproject.tsyn\n--json",
        "layers\nproject.tsyn\n--size\n512,512\n--mpp\n30\n-o\nout.png\n--hillshade\nhs.png",
        "export\nproject.tsyn\n-o\nout.glb\n--region\n0,0,512,512\n--tile\n254\n--lods\n2\n--lod-method\nsimplify\n--quantize",
        "export\n--heightmap\nin.png\n-o\nout.tif\n--masks\nmask_\n--mask-blur\n3\n--texture\n256\n--colors",
        "stats\na.png\n--vs\nb.png\n--json",
        "frobnicate\n--help",
        "--help",
    ]
    for i, c in enumerate(commands):
        write("cli_flags", f"command_{i}", c)


def sidecar_file(extent, heights, frozen, history=(), lifts=(), tilts=(), curve_lifts=(), digest="0123456789abcdef",
                 header_extra=None, checksum=True):
    """An edited-heights sidecar as project/edit_sidecar.cpp writes it: magic, version, header JSON,
    blobs, FNV-1a of everything before (left off when checksum is False: the target appends it)."""
    blobs, body = [], b""
    def blob(name, data):
        nonlocal body
        blobs.append({"name": name, "bytes": len(data)})
        body += data
    blob("heights", struct.pack(f"<{len(heights)}f", *heights))
    blob("frozen", bytes(frozen))
    levels = []
    for (x, y, w, h, passes) in history:
        levels.append([x, y, w, h, len(passes)])
        for index, v in passes:
            blob("history.index", struct.pack(f"<{len(index)}I", *index))
            blob("history.v", struct.pack(f"<{len(v)}f", *v))
    header = {"format": "terrasynth-edited-heights", "digest": digest, "extent": list(extent), "lifts": list(lifts),
              "tilts": [list(t) for t in tilts], "curve_lifts": [list(c) for c in curve_lifts], "history": levels,
              "reference": {"constraints": {}, "masks": [], "lifts": [], "tilts": [], "curve_lifts": []}, "blobs": blobs}
    if isinstance(header_extra, bytes):
        text = header_extra
    else:
        header.update(header_extra or {})
        text = json.dumps(header, separators=(",", ":")).encode()
    out = b"TSYNEDIT" + struct.pack("<IQ", 1, len(text)) + text + body
    if checksum:
        h = 1469598103934665603
        for c in out:
            h = ((h ^ c) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
        out += struct.pack("<Q", h)
    return out


def sidecar_seeds():
    # Mode 2 with no edits: the target's own real sidecar of a small session (it restores).
    write("edit_sidecar", "real_session", b"\2")
    write("edit_sidecar", "real_session_edited", b"\2" + bytes([40, 0, 0x7b, 200, 1, 0xff, 0, 2, 0x30]))
    extent, n = (-8, 4, 4, 3), 12
    heights = [800.0 + 5 * i for i in range(n)]
    plain = dict(extent=extent, heights=heights, frozen=[0] * n, checksum=False)
    write("edit_sidecar", "small", b"\1" + sidecar_file(**plain, lifts=[1.5], tilts=[(0.1, -0.2)], curve_lifts=[[0, 2, 1]]))
    write("edit_sidecar", "small_whole", b"\0" + sidecar_file(**dict(plain, checksum=True)))
    write("edit_sidecar", "history_level", b"\1" + sidecar_file(**plain, history=[(-4, 2, 2, 2, [([0, 1, 2, 3], [0.0] * 4)])]))
    # The hostile cases of issue 37: each must be refused, never crash.
    write("edit_sidecar", "deep_header", b"\1" + sidecar_file(**dict(plain, header_extra=b"[" * 1000 + b"]" * 1000)))
    write("edit_sidecar", "deep_lifts", b"\1" + sidecar_file(**plain, header_extra={"lifts": json.loads("[" * 60 + "]" * 60)}))
    write("edit_sidecar", "digest_not_hex", b"\1" + sidecar_file(**plain, digest="zz23456789abcdef"))
    write("edit_sidecar", "nan_heights", b"\1" + sidecar_file(**dict(plain, heights=[float("nan")] + heights[1:])))
    write("edit_sidecar", "frozen_not_binary", b"\1" + sidecar_file(**dict(plain, frozen=[7] + [0] * (n - 1))))
    write("edit_sidecar", "atlas_index_past_atlas",
          b"\1" + sidecar_file(**plain, history=[(-4, 2, 2, 2, [([0xfffffff0] * 4, [0.0] * 4)])]))
    write("edit_sidecar", "truncated", b"\0" + sidecar_file(**dict(plain, checksum=True))[:-30])


# `make_seeds.py CLI [target ...]`: only the named targets' seeds (default: every target).
seeders = {"exemplar": exemplar_seeds, "database": database_seeds, "project": project_seeds, "cli_flags": cli_seeds,
           "edit_sidecar": sidecar_seeds}
for name in sys.argv[2:] or list(seeders):
    seeders[name]()
