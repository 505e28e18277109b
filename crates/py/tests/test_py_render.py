"""cuticle.render, load_groom and fit_env against the command line: the same pixels as the
image.exr `cuticle render --device cpu` writes (read back with cuticle.read_exr), and
hostile arguments refused with the scene's messages. Tiny sizes: the point is equality."""

import numpy as np
import pytest

import cuticle

SCENE = dict(groom="straight", strands=150, width=40, height=24, supersampling=1, lights=6)


def flags(kwargs):
    args = []
    for key, value in kwargs.items():
        args += ["--" + key.replace("_", "-"), value]
    return args


@pytest.mark.parametrize(
    "extra",
    [
        dict(method="srbf", mu_a=0.4),
        dict(method="brute", brute_grid=3, eta=1.6),
        dict(method="path", spp=2, seed=3, max_depth=4, mu_a=0.3),
    ],
)
def test_render_gives_the_pixels_of_cuticle_render(tmp_path, run_cli, extra):
    scene = {**SCENE, **extra}
    if extra["method"] == "path":
        del scene["lights"]  # the path tracer samples the map itself
    run_cli("render", "--device", "cpu", "--out", tmp_path, *flags(scene))
    expected = cuticle.read_exr(tmp_path / "image.exr")
    image = cuticle.render(**scene)
    assert image.dtype == np.float32 and image.shape == (24, 40, 3)
    np.testing.assert_array_equal(image, expected)
    assert image.max() > 0


def test_render_options_change_the_image():
    base = cuticle.render(**SCENE)
    single = cuticle.render(**SCENE, multiple=False)
    assert single.sum() < base.sum()


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(width=0), "width must be a whole number"),
        (dict(width=10**9), "width must be a whole number"),
        (dict(width=-3), "width must be a whole number"),
        (dict(supersampling=10**6), "supersampling must be a whole number"),
        (dict(method="fast"), 'method must be srbf, brute or path, got "fast"'),
        (dict(spp=4), "spp, seed and max_depth are for method path"),
        (dict(method="path", spp=0), "spp must be a whole number in 1..=1048576, got 0"),
        (dict(method="path", max_depth=10**9), "max_depth must be a whole number in 1..=100000"),
        (dict(method="path", multiple=False), "multiple = False is for methods srbf and brute"),
        (dict(eta=float("nan")), "eta must be a finite number"),
        (dict(mu_a=(1.0, 2.0)), "mu_a takes one number or r, g, b, got 2 numbers"),
        (dict(groom="/nonexistent/groom.hair"), "/nonexistent/groom.hair"),
        (dict(env="/nonexistent/sky.exr"), "/nonexistent/sky.exr"),
        (dict(strands=10**12), "strands must be a whole number"),
    ],
)
def test_render_refuses_bad_scenes_with_one_message(kwargs, message):
    with pytest.raises(ValueError) as err:
        cuticle.render(**{**SCENE, **kwargs})
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_load_groom_gives_the_strands_the_renderer_loads():
    groom = cuticle.load_groom("wavy", strands=20)
    assert groom["strands"] == 20
    offsets, points = groom["offsets"], groom["points"]
    assert offsets.shape == (21,) and offsets[0] == 0 and offsets[-1] == len(points)
    assert np.all(np.diff(offsets) >= 2) and points.shape[1] == 3
    assert np.all(np.isfinite(points)) and groom["thickness"].shape == (len(points),)
    with pytest.raises(ValueError, match="strands must be a whole number"):
        cuticle.load_groom("wavy", strands=0)
    with pytest.raises(ValueError, match="missing.hair"):
        cuticle.load_groom("missing.hair")


def test_fit_env_gives_unit_directions_and_refuses_bad_counts():
    fit = cuticle.fit_env("default", lights=4)
    assert fit["directions"].shape == (4, 3) and fit["coefficients"].shape == (4, 3)
    np.testing.assert_allclose(np.linalg.norm(fit["directions"], axis=1), 1, atol=1e-5)
    assert np.all(fit["bandwidths"] > 0) and 0 <= fit["relative_l2"] < 1
    with pytest.raises(ValueError, match="lights"):
        cuticle.fit_env("default", lights=0)
