"""`cuticle export --format mitsuba` against the real Mitsuba 3 (PyPI `mitsuba`, scalar_rgb).

1. The environment: a map with one bright texel, exported with a rotation, lights the same
   world direction in Mitsuba (its emitter evaluated over a grid of directions) as in cuticle
   (docs/conventions.md §4 and `light_to_world` of crate cuticle-render).
2. The picture: a small groom of thick, wavy strands under a lat-long map with a bright patch
   and ambient light whose colour turns with azimuth (rotated 30°), Chiang et al. 2016 hair
   with beta_m != beta_n, rendered by `cuticle render --method path --model chiang2016` and by
   Mitsuba from the export. The hair's share of the image (coverage) agrees within 3 %, the
   background (the map seen directly) within 2 %, and the per-channel mean over the hair within 5 %, at
   sample counts where the noise of each mean is below 1 % (measured: cuticle's standard error,
   Mitsuba's two seeds).

The binary is $CUTICLE_BIN (scripts/test sets it), else target/release/cuticle.
"""

import math
import os
import re
import struct
import subprocess
from pathlib import Path

import mitsuba as mi  # pinned in scripts/python-requirements.txt
import numpy as np

# The JIT variants (llvm_ad_rgb) need a working libLLVM; the scalar one runs anywhere.
mi.set_variant("scalar_rgb")

ROOT = Path(__file__).resolve().parents[2]
BIN = os.environ.get("CUTICLE_BIN", str(ROOT / "target" / "release" / "cuticle"))

SPP = 256
HAIR = [
    "--model", "chiang2016", "--beta-m", "0.25", "--beta-n", "0.5",
    "--alpha-deg", "-3", "--eta", "1.55", "--mu-a", "0.4,0.8,1.6", "--max-depth", "16",
]


def cuticle(*args):
    done = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done


def write_hair(path):
    """A cyHair file: 12 wavy strands in two rows, 0.2 units thick (header defaults), a fifth
    of their spacing or less: cuticle's path tracer scatters from a fiber's axis (the far-field
    BCSDF), Mitsuba from its surface, and with fibers half their spacing wide the two pictures
    differed by 2-3 % (R and G) for that reason alone."""
    strands = []
    for i in range(6):
        for j in range(2):
            x0, y0 = -2.5 + i + 0.3 * j, 0.6 * j
            strands.append([
                (x0 + 0.6 * math.sin(2.5 * k / 8 + i), y0 + 0.3 * k / 8, 4.0 - k)
                for k in range(9)
            ])
    points = sum(len(s) for s in strands)
    header = (b"HAIR" + struct.pack("<IIIIff3f", len(strands), points, 1 | 2, 0, 0.2, 0.0,
                                    1.0, 1.0, 1.0) + b"\0" * 88)
    segments = b"".join(struct.pack("<H", len(s) - 1) for s in strands)
    xyz = b"".join(struct.pack("<3f", *p) for s in strands for p in s)
    path.write_bytes(header + segments + xyz)


def write_map(path, pixels):
    mi.Bitmap(np.ascontiguousarray(pixels, dtype=np.float32)).write(str(path))


def cuticle_direction(column, row, width, height, rotate_deg):
    """World direction of a texel centre of cuticle's lat-long map (+y up in the map, the
    world +z up: (x, y, z) -> (x, -z, y))."""
    phi = -math.pi + 2 * math.pi * (column + 0.5) / width + math.radians(rotate_deg)
    theta = math.pi / 2 - math.pi * (row + 0.5) / height
    x, y, z = (math.cos(theta) * math.cos(phi), math.sin(theta),
               math.cos(theta) * math.sin(phi))
    return np.array([x, -z, y])


def emitter_radiance(emitter, direction):
    """Mitsuba's envmap radiance arriving from world `direction`."""
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*(-np.asarray(direction)))
    return np.array(emitter.eval(si))


def test_bright_texel_lights_the_same_direction(tmp_path):
    width, height, rotate = 32, 16, 30.0
    for column, row in [(5, 4), (0, 8), (20, 12)]:
        pixels = np.zeros((height, width, 3))
        pixels[row, column] = [1000.0, 500.0, 250.0]
        write_map(tmp_path / "one.exr", pixels)
        (tmp_path / "s.toml").write_text(
            f'env = "{tmp_path / "one.exr"}"\nenv_rotate_deg = {rotate}\n')
        out = tmp_path / f"e{column}_{row}"
        cuticle("export", "--format", "mitsuba", "--scene", tmp_path / "s.toml", "--strands",
                4, "--width", 8, "--height", 8, *HAIR, "--out", out)
        emitter = mi.load_file(str(out / "scene.xml")).emitters()[0]
        best, best_dir = -1.0, None
        for k in range(90):
            for j in range(180):
                theta, phi = math.pi * (k + 0.5) / 90, 2 * math.pi * (j + 0.5) / 180
                d = np.array([math.sin(theta) * math.cos(phi),
                              math.sin(theta) * math.sin(phi), math.cos(theta)])
                value = emitter_radiance(emitter, d)[0]
                if value > best:
                    best, best_dir = value, d
        want = cuticle_direction(column, row, width, height, rotate)
        angle = math.degrees(math.acos(min(1.0, float(best_dir @ want))))
        # A texel of the 32 x 16 map spans 11.25 degrees.
        assert angle < 6.0, f"texel ({column}, {row}): brightest {angle:.1f} deg away"
        assert emitter_radiance(emitter, want)[0] > 100.0
        assert emitter_radiance(emitter, -want)[0] < 1e-6


def masked_mean(image, mask):
    return image[mask][:, :3].mean(axis=0)


def mitsuba_coverage(scene_xml, spp):
    """Per pixel, the fraction of Mitsuba's camera rays that meet hair: the exported scene
    with paths of one segment (only what the camera sees directly) under a unit constant
    environment shows 1 - coverage. (A black diffuse BSDF instead crashed Mitsuba 3.9.1 on
    curves as thick as 0.6 of their segments.)"""
    text = scene_xml.read_text()
    text = re.sub(r'<integer name="max_depth" value="\d+"/>',
                  '<integer name="max_depth" value="1"/>', text)
    text = re.sub(r'<emitter type="envmap">.*?</emitter>',
                  '<emitter type="constant"><rgb name="radiance" value="1"/></emitter>',
                  text, flags=re.S)
    path = scene_xml.with_name("coverage.xml")
    path.write_text(text)
    return 1.0 - np.array(mi.render(mi.load_file(str(path)), spp=spp))[..., 0]


def test_mitsuba_renders_the_exported_scene_as_cuticle_does(tmp_path):
    write_hair(tmp_path / "groom.hair")
    # Ambient light that changes colour with azimuth (the background shows the map's
    # orientation directly), a warm bright patch and a dim blue one.
    phi = 2 * np.pi * (np.arange(64) + 0.5) / 64
    tint = np.stack([1 + 0.6 * np.sin(phi), 1 + 0.6 * np.cos(phi), 1 - 0.6 * np.sin(phi)], -1)
    env = np.broadcast_to(0.3 * tint, (32, 64, 3)).copy()
    env[8:11, 20:23] = [40.0, 30.0, 20.0]
    env[20:23, 50:53] = [2.0, 4.0, 8.0]
    write_map(tmp_path / "env.exr", env)
    (tmp_path / "scene.toml").write_text(f"""
groom = "{tmp_path / 'groom.hair'}"
env = "{tmp_path / 'env.exr'}"
env_rotate_deg = 30
width = 96
height = 96
[camera]
eye = [2.0, -14.0, 3.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
fov_deg = 40.0
""")
    flags = ["--scene", tmp_path / "scene.toml", *HAIR, "--spp", SPP]
    cuticle("render", "--method", "path", *flags, "--out", tmp_path / "ref")
    cuticle("export", "--format", "mitsuba", *flags, "--out", tmp_path / "mts")

    ref = np.array(mi.Bitmap(str(tmp_path / "ref" / "image.exr")))
    error = np.array(mi.Bitmap(str(tmp_path / "ref" / "standard_error.exr")))
    coverage = np.array(mi.Bitmap(str(tmp_path / "ref" / "coverage.exr")))[..., 0]
    scene = mi.load_file(str(tmp_path / "mts" / "scene.xml"))
    seeds = [np.array(mi.render(scene, seed=seed)) for seed in (0, 1)]
    theirs = mitsuba_coverage(tmp_path / "mts" / "scene.xml", SPP)

    share = (coverage.mean(), theirs.mean())
    background = coverage == 0
    back = (masked_mean(ref, background), masked_mean(seeds[0], background))
    # Pixels all hair in both: no background mixed into either mean.
    mask = (coverage >= 1.0) & (theirs >= 0.999)
    ours = masked_mean(ref, mask)
    mitsuba = (masked_mean(seeds[0], mask) + masked_mean(seeds[1], mask)) / 2
    ours_noise = np.sqrt((error[mask][:, :3] ** 2).sum(axis=0)) / mask.sum() / ours
    mitsuba_noise = np.abs(masked_mean(seeds[0], mask) - masked_mean(seeds[1], mask)) / 2 / mitsuba
    ratio = mitsuba / ours
    report = (f"coverage cuticle {share[0]:.4f}, mitsuba {share[1]:.4f}; background cuticle "
              f"{back[0]}, mitsuba {back[1]}; hair mean ({mask.sum()} pixels) cuticle {ours}, "
              f"mitsuba {mitsuba}, ratio {ratio}; relative noise cuticle {ours_noise}, "
              f"mitsuba {mitsuba_noise}")
    print(report)
    assert abs(share[1] / share[0] - 1) < 0.03, report
    assert (np.abs(back[1] / back[0] - 1) < 0.02).all(), report
    assert mask.sum() > 200, report
    assert (ours_noise < 0.01).all() and (mitsuba_noise < 0.01).all(), report
    assert (np.abs(ratio - 1) < 0.05).all(), report
