"""Fiber.latlong and cuticle.simulate against the command line: the same images as the EXRs
`cuticle lobes` and `cuticle sim` write (to the float32 they store) and the same energies as
their JSON records, read back through cuticle.read_exr."""

import json

import numpy as np
import pytest

import cuticle

IMAGES = ["R", "TT", "TRT", "TRRT", "rest", "total"]


def channel_mean(rgb):
    return (rgb[0] + rgb[1] + rgb[2]) / 3.0


@pytest.mark.parametrize(
    "model,flags",
    [
        ("deon2011", dict(beta=0.05, alpha_deg=-3.0, eta=1.6, mu_a=(0.1, 0.3, 0.8))),
        ("nonseparable-paper", dict(beta=0.1, alpha_deg=2.0, eumelanin=0.8)),
    ],
)
def test_latlong_is_cuticle_lobes(tmp_path, run_cli, model, flags):
    theta_i, width = 0.4, 40
    args = ["lobes", "--model", model, "--theta-i", theta_i, "--width", width, "--out", tmp_path]
    for key, value in flags.items():
        value = ",".join(map(str, value)) if isinstance(value, tuple) else value
        args += ["--" + key.replace("_", "-"), value]
    run_cli(*args)
    images = cuticle.Fiber(model, **flags).latlong(theta_i, width=width, height=width // 4)
    for name in IMAGES:
        exr = cuticle.read_exr(tmp_path / f"{name}.exr")
        assert images[name].shape == exr.shape == (width // 4, width, 3)
        np.testing.assert_array_equal(images[name].astype(np.float32), exr, err_msg=name)
    record = json.loads((tmp_path / "lobes.json").read_text())
    for name in ["R", "TT", "TRT", "TRRT", "rest", "total"]:
        assert channel_mean(images["energy"][name]) == pytest.approx(
            record["energy"][name], rel=1e-14, abs=1e-300
        )
    assert images["total"].sum() > 0


SIM = dict(theta_i=0.3, alpha_deg=-3.0, beta=0.05, eta=1.6, mu_a=(0.1, 0.2, 0.4), rays=300_000, seed=7)


def test_simulate_is_cuticle_sim(tmp_path, run_cli):
    args = ["sim", "--out", tmp_path]
    for key, value in SIM.items():
        value = ",".join(map(str, value)) if isinstance(value, tuple) else value
        args += ["--" + key.replace("_", "-"), value]
    run_cli(*args)
    result = cuticle.simulate(**SIM)
    for name in IMAGES:
        exr = cuticle.read_exr(tmp_path / f"{name}.exr")
        assert result[name].shape == exr.shape == (100, 400, 3)
        np.testing.assert_array_equal(result[name].astype(np.float32), exr, err_msg=name)
    record = json.loads((tmp_path / "sim.json").read_text())
    for name, rgb in record["energy_rgb"].items():
        np.testing.assert_array_equal(result["energy"][name], rgb, err_msg=name)
    for name in ["shadowing", "backfacing", "cutoff"]:
        assert channel_mean(result["lost"][name]) == pytest.approx(record["lost"][name], rel=1e-14, abs=1e-300)
    assert channel_mean(result["absorbed"]) == pytest.approx(record["absorbed"], rel=1e-14)
    assert result["rays"] == SIM["rays"]
    # The seed matters: another one gives other images.
    other = cuticle.simulate(**{**SIM, "seed": 8, "rays": 65_536})
    assert not np.array_equal(other["total"], result["total"])


def test_simulate_energy_is_conserved_without_absorption():
    r = cuticle.simulate(theta_i=0.2, beta=0.1, alpha_deg=0.0, mu_a=0.0, rays=100_000, seed=1)
    leaving = r["energy"]["total"] + sum(r["lost"].values()) + r["absorbed"]
    np.testing.assert_allclose(leaving, 1.0, atol=1e-9)
    assert 0.9 < channel_mean(r["energy"]["total"]) <= 1.0 + 1e-9


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(rays=0), "rays must be a whole number in 1..=1000000000, got 0"),
        (dict(rays=-5), "rays must be a whole number in 1..=1000000000, got -5"),
        (dict(rays=10**12), "rays must be a whole number in 1..=1000000000, got 1e12"),
        (dict(theta_i=float("nan")), "theta_i must be a finite number in (-1.5708, 1.5708) radians, got NaN"),
        (dict(beta=0.0), "beta must be a finite number in [0.0001, 1], got 0"),
        (dict(mu_a=(1.0, 2.0)), "mu_a takes one number or r, g, b, got 2 numbers"),
        (dict(mu_a=-1.0), "mu_a must be a finite number in [0, 1000], got -1"),
    ],
)
def test_simulate_refuses_bad_values_with_the_command_lines_message(kwargs, message):
    with pytest.raises(ValueError) as err:
        cuticle.simulate(**kwargs)
    assert message in str(err.value)


def test_read_exr_refuses_what_is_not_an_exr(tmp_path):
    path = tmp_path / "not.exr"
    path.write_bytes(b"v/1\x01" + b"\x00" * 64)
    with pytest.raises(ValueError, match="not.exr"):
        cuticle.read_exr(path)
    with pytest.raises(ValueError):
        cuticle.read_exr(tmp_path / "missing.exr")
