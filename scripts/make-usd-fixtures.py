#!/usr/bin/env python3
"""Writes the USD groom fixtures of crates/groom/tests/data/usd with Pixar's own library
(usd-core, pinned in scripts/python-requirements.txt):

    $(scripts/python-env) scripts/make-usd-fixtures.py

The files are small and committed; the Rust tests read them (crates/groom/tests/usd_read.rs)
and know every number written here, so a change here needs the same change there.

- bases.usda      Z-up, centimetres: one BasisCurves prim per basis and wrap (linear,
                  bspline, catmullRom, bezier; nonperiodic and pinned), each with another
                  widths interpolation (vertex, varying, uniform, constant).
- primvars.usda   per-strand appearance: melanin + melanin_redness (Blender's names),
                  eumelanin + pheomelanin, displayColor, color; uniform, constant and vertex.
- transforms.usdc binary, Y-up, metres: two prims under different transforms.
- upright_y_cm.usda / upright_z_m.usdc / upright_z_m.usdz
                  the same two strands growing "up" from a scalp, Y-up in centimetres and
                  Z-up in metres (also packaged as .usdz): all must arrive identical, +z up,
                  in centimetres.
"""

import os
import sys

from pxr import Gf, Sdf, Usd, UsdGeom, UsdUtils, Vt

OUT = os.path.join(os.path.dirname(__file__), "..", "crates", "groom", "tests", "data", "usd")


def stage(name, up, meters):
    path = os.path.join(OUT, name)
    if os.path.exists(path):
        os.remove(path)
    s = Usd.Stage.CreateNew(path)
    UsdGeom.SetStageUpAxis(s, up)
    UsdGeom.SetStageMetersPerUnit(s, meters)
    root = UsdGeom.Xform.Define(s, "/Groom")
    s.SetDefaultPrim(root.GetPrim())
    return s


def curves(s, path, kind, basis, wrap, counts, points, widths=None, interp=None):
    c = UsdGeom.BasisCurves.Define(s, path)
    c.CreateTypeAttr(kind)
    if basis is not None:
        c.CreateBasisAttr(basis)
    c.CreateWrapAttr(wrap)
    c.CreateCurveVertexCountsAttr(Vt.IntArray(counts))
    c.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in points]))
    if widths is not None:
        w = c.CreateWidthsAttr(Vt.FloatArray(widths))
        c.SetWidthsInterpolation(interp)
    return c


def primvar(c, name, type_name, values, interp):
    api = UsdGeom.PrimvarsAPI(c.GetPrim())
    pv = api.CreatePrimvar(name, type_name, interp)
    pv.Set(values)
    return pv


# Control points every test knows: a wiggle in x over a rise in z.
WIGGLE = [(0, 0, 0), (1, 0, 1), (0, 1, 2), (2, 0, 3), (1, 1, 4), (0, 0, 5), (1, 0, 6)]


def bases():
    s = stage("bases.usda", UsdGeom.Tokens.z, 0.01)
    shifted = [(x + 10, y, z) for (x, y, z) in WIGGLE]
    # linear: 2 curves (3 and 4 points), vertex widths.
    curves(s, "/Groom/Linear", "linear", None, "nonperiodic", [3, 4], WIGGLE,
           [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7], UsdGeom.Tokens.vertex)
    # bspline: 7 points, 4 segments; varying widths (segments + 1 = 5).
    curves(s, "/Groom/Bspline", "cubic", "bspline", "nonperiodic", [7], WIGGLE,
           [0.1, 0.2, 0.3, 0.4, 0.5], UsdGeom.Tokens.varying)
    # catmullRom: 2 curves of 7, uniform widths.
    curves(s, "/Groom/CatmullRom", "cubic", "catmullRom", "nonperiodic", [7, 7],
           WIGGLE + shifted, [0.25, 0.5], UsdGeom.Tokens.uniform)
    # bezier: 7 points = 2 segments; constant width.
    curves(s, "/Groom/Bezier", "cubic", "bezier", "nonperiodic", [7], WIGGLE,
           [0.3], UsdGeom.Tokens.constant)
    # pinned bspline and catmullRom: pass through the end points.
    curves(s, "/Groom/BsplinePinned", "cubic", "bspline", "pinned", [7], WIGGLE,
           [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7], UsdGeom.Tokens.vertex)
    curves(s, "/Groom/CatmullRomPinned", "cubic", "catmullRom", "pinned", [7], WIGGLE)
    s.GetRootLayer().Save()


def primvars():
    s = stage("primvars.usda", UsdGeom.Tokens.z, 0.01)
    two = WIGGLE[:3] + [(x + 5, y, z) for (x, y, z) in WIGGLE[:3]]
    f = Sdf.ValueTypeNames
    c = curves(s, "/Groom/Blender", "linear", None, "nonperiodic", [3, 3], two, [0.01], "constant")
    primvar(c, "melanin", f.FloatArray, Vt.FloatArray([0.5, 0.9]), UsdGeom.Tokens.uniform)
    primvar(c, "melanin_redness", f.FloatArray, Vt.FloatArray([0.0, 0.25]), UsdGeom.Tokens.uniform)
    c = curves(s, "/Groom/Pigments", "linear", None, "nonperiodic", [3, 3], two, [0.01], "constant")
    primvar(c, "eumelanin", f.FloatArray, Vt.FloatArray([1.5, 0.25]), UsdGeom.Tokens.uniform)
    primvar(c, "pheomelanin", f.FloatArray, Vt.FloatArray([0.0, 2.0]), UsdGeom.Tokens.uniform)
    c = curves(s, "/Groom/DisplayColor", "linear", None, "nonperiodic", [3, 3], two, [0.01], "constant")
    c.CreateDisplayColorPrimvar(UsdGeom.Tokens.uniform).Set(
        Vt.Vec3fArray([Gf.Vec3f(0.8, 0.5, 0.2), Gf.Vec3f(0.2, 0.1, 0.05)]))
    c = curves(s, "/Groom/Color", "linear", None, "nonperiodic", [3, 3], two, [0.01], "constant")
    # a per-point colour: each strand takes its points' mean.
    primvar(c, "color", f.Color3fArray,
            Vt.Vec3fArray([Gf.Vec3f(0.5, 0.5, 0.5)] * 3 + [Gf.Vec3f(0.1, 0.2, 0.3)] * 2
                          + [Gf.Vec3f(0.4, 0.5, 0.6)]), UsdGeom.Tokens.vertex)
    c = curves(s, "/Groom/Constant", "linear", None, "nonperiodic", [3, 3], two, [0.01], "constant")
    primvar(c, "eumelanin", f.Float, 3.0, UsdGeom.Tokens.constant)
    primvar(c, "pheomelanin", f.Float, 0.5, UsdGeom.Tokens.constant)
    s.GetRootLayer().Save()


def transforms():
    s = stage("transforms.usdc", UsdGeom.Tokens.y, 1.0)
    a = UsdGeom.Xform.Define(s, "/Groom/Left")
    a.AddTranslateOp().Set(Gf.Vec3d(-0.1, 0.0, 0.0))
    b = UsdGeom.Xform.Define(s, "/Groom/Right")
    b.AddTranslateOp().Set(Gf.Vec3d(0.2, 0.05, 0.0))
    b.AddRotateZOp().Set(90.0)
    b.AddScaleOp().Set(Gf.Vec3f(2.0, 2.0, 2.0))
    strand = [(0, 0, 0), (0, 0.1, 0)]
    curves(s, "/Groom/Left/Hair", "linear", None, "nonperiodic", [2], strand, [0.0001], "constant")
    curves(s, "/Groom/Right/Hair", "linear", None, "nonperiodic", [2], strand, [0.0001], "constant")
    s.GetRootLayer().Save()


def upright():
    # Scalp points and strands growing up and slightly forward (+y forward in Z-up cm).
    zup_cm = [(0, 0, 10), (0, 1, 20), (3, 0, 10), (3, 1, 20)]
    s = stage("upright_y_cm.usda", UsdGeom.Tokens.y, 0.01)
    # Z-up (x, y, z) is Y-up (x, z, -y).
    yup = [(x, z, -y) for (x, y, z) in zup_cm]
    curves(s, "/Groom/Hair", "linear", None, "nonperiodic", [2, 2], yup, [0.007], "constant")
    s.GetRootLayer().Save()
    s = stage("upright_z_m.usdc", UsdGeom.Tokens.z, 1.0)
    metres = [(x / 100, y / 100, z / 100) for (x, y, z) in zup_cm]
    curves(s, "/Groom/Hair", "linear", None, "nonperiodic", [2, 2], metres, [0.00007], "constant")
    s.GetRootLayer().Save()
    # the same as a .usdz package.
    usdz = os.path.join(OUT, "upright_z_m.usdz")
    if os.path.exists(usdz):
        os.remove(usdz)
    assert UsdUtils.CreateNewUsdzPackage(os.path.join(OUT, "upright_z_m.usdc"), usdz)


def main():
    os.makedirs(OUT, exist_ok=True)
    bases()
    primvars()
    transforms()
    upright()
    print("wrote", ", ".join(sorted(os.listdir(OUT))), "in", os.path.normpath(OUT), file=sys.stderr)


if __name__ == "__main__":
    main()
