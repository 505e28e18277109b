"""USD written by cuticle, read by Pixar's own library (usd-core): what Houdini, Blender and
Maya will see. Run by scripts/test with CUTICLE_BIN set to the release binary."""

import os
import subprocess

import numpy as np
import pytest

pxr = pytest.importorskip("pxr", reason="usd-core is in scripts/python-requirements.txt")
from pxr import Usd, UsdGeom  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURES = os.path.join(HERE, "..", "..", "crates", "groom", "tests", "data", "usd")


def cuticle(*args):
    binary = os.environ.get("CUTICLE_BIN")
    if not binary:
        pytest.skip("CUTICLE_BIN names the cuticle binary (scripts/test sets it)")
    out = subprocess.run([binary, *args], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout


def curves_of(path):
    stage = Usd.Stage.Open(path)
    assert stage is not None, path
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.z
    assert UsdGeom.GetStageMetersPerUnit(stage) == pytest.approx(0.01)
    prims = [p for p in stage.Traverse() if p.IsA(UsdGeom.BasisCurves)]
    assert len(prims) == 1
    # the stage must outlive its prims: keep it on the schema object's side.
    curves = UsdGeom.BasisCurves(prims[0])
    curves_of.stages.append(stage)
    return curves


curves_of.stages = []


@pytest.mark.parametrize("ext", ["usda"])
def test_groom_make_writes_basis_curves_usd_core_reads(tmp_path, ext):
    out = tmp_path / f"groom.{ext}"
    cuticle("groom", "make", "--preset", "curly", "--strands", "40", "--seed", "3", "--out", str(out))
    curves = curves_of(str(out))
    assert curves.GetTypeAttr().Get() == UsdGeom.Tokens.linear
    counts = list(curves.GetCurveVertexCountsAttr().Get())
    points = curves.GetPointsAttr().Get()
    widths = curves.GetWidthsAttr().Get()
    assert len(counts) == 40
    assert sum(counts) == len(points) == len(widths)
    assert curves.GetWidthsInterpolation() == UsdGeom.Tokens.vertex
    assert all(w > 0 for w in widths)
    # cuticle's own description of the same file agrees.
    info = cuticle("groom", "info", str(out))
    assert f"40 strands, {len(points)} points" in info
    # a procedural groom's strands carry their varied melanin.
    api = UsdGeom.PrimvarsAPI(curves.GetPrim())
    for name in ["sigma_a", "eumelanin", "pheomelanin", "melanin", "melanin_redness"]:
        pv = api.GetPrimvar(name)
        assert pv and pv.GetInterpolation() == UsdGeom.Tokens.uniform, name
        assert len(pv.Get()) == 40, name
    eu = api.GetPrimvar("eumelanin").Get()
    assert len(set(eu)) > 1, "per-strand values, not one"
    assert all(0.0 <= m <= 1.0 for m in api.GetPrimvar("melanin").Get())


def read_hair(path):
    """The counts, points and thickness of a cyHair .hair file (its 128-byte header, then the
    arrays its flags name), as numpy arrays."""
    data = open(path, "rb").read()
    assert data[:4] == b"HAIR"
    strands, points, flags, segments = np.frombuffer(data, "<u4", 4, 4)
    thickness_default = np.frombuffer(data, "<f4", 1, 20)[0]
    at = 128
    if flags & 1:
        counts = np.frombuffer(data, "<u2", strands, at).astype(int) + 1
        at += 2 * strands
    else:
        counts = np.full(strands, segments + 1)
    xyz = np.frombuffer(data, "<f4", 3 * points, at).reshape(points, 3)
    at += 12 * points
    if flags & 4:
        thickness = np.frombuffer(data, "<f4", points, at)
    else:
        thickness = np.full(points, thickness_default, dtype=np.float32)
    return counts, xyz, thickness


@pytest.mark.parametrize("ext", ["usda"])
def test_the_usd_groom_is_the_hair_groom_bit_for_bit(tmp_path, ext):
    args = ["groom", "make", "--preset", "wavy", "--strands", "25", "--seed", "7", "--out"]
    cuticle(*args, str(tmp_path / "hair"))
    cuticle(*args, str(tmp_path / f"groom.{ext}"))
    counts, xyz, thickness = read_hair(str(tmp_path / "hair" / "groom.hair"))
    curves = curves_of(str(tmp_path / f"groom.{ext}"))
    assert list(curves.GetCurveVertexCountsAttr().Get()) == list(counts)
    points = np.array(curves.GetPointsAttr().Get(), dtype=np.float32)
    widths = np.array(curves.GetWidthsAttr().Get(), dtype=np.float32)
    assert np.array_equal(points.view(np.uint32), xyz.view(np.uint32))
    assert np.array_equal(widths.view(np.uint32), thickness.view(np.uint32))
