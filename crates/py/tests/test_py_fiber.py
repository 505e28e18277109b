"""cuticle.Fiber against the Rust figures and against itself: S, pdf and samples at the inputs
the fiber crate pins (crates/fiber/tests/figures.json), sampling by a chi-square test against
the pdf, the white furnace by quadrature over eval, and hostile arguments."""

import json
import math
import pathlib

import numpy as np
import pytest

import cuticle

ROOT = pathlib.Path(__file__).resolve().parents[3]

FIGURES = json.loads((ROOT / "crates/fiber/tests/figures.json").read_text())


@pytest.fixture(scope="module")
def models():
    return {name: cuticle.Fiber(name) for name in cuticle.MODELS}


def test_every_model_of_the_registry_is_offered():
    assert sorted(cuticle.MODELS) == sorted(FIGURES["models"])


@pytest.mark.parametrize("name", sorted(FIGURES["models"]))
def test_eval_pdf_and_sample_give_the_rust_figures(models, name):
    fiber, pinned = models[name], FIGURES["models"][name]
    wi, wo, u = (np.array(FIGURES[k])[None, :] for k in ("wi", "wo", "u"))
    assert fiber.model == name
    np.testing.assert_allclose(fiber.eval(wi, wo)[0], pinned["eval"], rtol=1e-10)
    np.testing.assert_allclose(fiber.pdf(wi, wo)[0], pinned["pdf"], rtol=1e-10)
    s_wo, weight, pdf = fiber.sample(wi, u)
    np.testing.assert_allclose(s_wo[0], pinned["sample_wo"], rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(weight[0], pinned["sample_weight"], rtol=1e-10)
    np.testing.assert_allclose(pdf[0], pinned["sample_pdf"], rtol=1e-10)


def unit_rows(rng, n):
    d = rng.normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def test_lobes_sum_to_eval_and_rows_are_independent(models):
    fiber = models["nonseparable"]
    rng = np.random.default_rng(7)
    wi, wo = unit_rows(rng, 500), unit_rows(rng, 500)
    lobes = fiber.lobes(wi, wo)
    assert list(lobes) == ["R", "TT", "TRT", "TRRT", "rest"]
    total = fiber.eval(wi, wo)
    assert total.shape == (500, 3) and total.dtype == np.float64
    np.testing.assert_allclose(sum(lobes.values()), total, rtol=1e-12, atol=1e-300)
    # Row k depends on row k alone: one row evaluated by itself gives the same bits.
    np.testing.assert_array_equal(fiber.eval(wi[123], wo[123:124]), total[123:124])
    # A single wi (shape (3,)) is broadcast against every wo.
    np.testing.assert_array_equal(
        fiber.eval(wi[0], wo), fiber.eval(np.repeat(wi[:1], 500, axis=0), wo)
    )


def test_samples_report_the_pdf_and_the_weight_s_over_pdf(models):
    rng = np.random.default_rng(3)
    for name in ("nonseparable", "deon2011", "chiang2016"):
        fiber = models[name]
        wi = np.array([math.sin(0.3), math.cos(0.3), 0.0])
        wo, weight, pdf = fiber.sample(wi, rng.random((2000, 4)))
        ok = pdf > 0
        assert ok.mean() > 0.9, name
        assert np.all(weight[~ok] == 0) and np.all(wo[~ok] == 0)
        np.testing.assert_allclose(np.linalg.norm(wo[ok], axis=1), 1, atol=1e-12)
        np.testing.assert_allclose(fiber.pdf(wi, wo[ok]), pdf[ok], rtol=1e-6, err_msg=name)
        np.testing.assert_allclose(
            fiber.eval(wi, wo[ok]) / pdf[ok][:, None], weight[ok], rtol=1e-6, err_msg=name
        )


def chi2_survival(chi2, dof):
    """P(X > chi2) for X ~ chi-square(dof), by Wilson and Hilferty's cube-root normal
    approximation (within 1e-3 of the exact value for the dozens of cells used here)."""
    k = 2.0 / (9.0 * dof)
    z = ((chi2 / dof) ** (1 / 3) - (1 - k)) / math.sqrt(k)
    return 0.5 * math.erfc(z / math.sqrt(2))


def bin_integrals(pdf, theta_bins, phi_bins, panels=8, nodes=6):
    """The pdf integrated over each (theta, phi) bin of the sphere, cos(theta) included, theta
    split into `panels` Gauss-Legendre panels per bin (the fiber crate's chi2 test's rule)."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    t_edges = np.linspace(-np.pi / 2, np.pi / 2, theta_bins * panels + 1)
    p_edges = np.linspace(-np.pi, np.pi, phi_bins + 1)
    half_t, half_p = np.diff(t_edges)[0] / 2, np.diff(p_edges)[0] / 2
    theta = (t_edges[:-1, None] + half_t * (x + 1)).ravel()
    phi = (p_edges[:-1, None] + half_p * (x + 1)).ravel()
    wt = np.tile(w * half_t, theta_bins * panels) * np.cos(theta)
    wp = np.tile(w * half_p, phi_bins)
    T, P = np.meshgrid(theta, phi, indexing="ij")
    wo = np.stack([np.sin(T), np.cos(T) * np.cos(P), np.cos(T) * np.sin(P)], -1).reshape(-1, 3)
    values = pdf(wo).reshape(theta.size, phi.size) * wt[:, None] * wp[None, :]
    return values.reshape(theta_bins, panels * nodes, phi_bins, nodes).sum(axis=(1, 3))


@pytest.mark.parametrize("name", ["nonseparable", "deon2011"])
def test_sampling_passes_the_chi_square_test_against_pdf(models, name):
    fiber, n, bins = models[name], 200_000, (16, 24)
    wi = np.array([math.sin(0.4), math.cos(0.4), 0.0])
    wo, _, pdf = fiber.sample(wi, np.random.default_rng(11).random((n, 4)))
    wo = wo[pdf > 0]
    theta, phi = np.arcsin(np.clip(wo[:, 0], -1, 1)), np.arctan2(wo[:, 2], wo[:, 1])
    observed, _, _ = np.histogram2d(
        theta, phi, bins=bins, range=[[-np.pi / 2, np.pi / 2], [-np.pi, np.pi]]
    )
    expected = n * bin_integrals(lambda d: fiber.pdf(wi, d), *bins)
    assert observed.sum() == pytest.approx(expected.sum(), rel=0.01)
    # Bins expecting fewer than 5 samples pooled into one cell (the fiber crate's rule).
    small = expected < 5
    o = np.append(observed[~small], observed[small].sum())
    e = np.append(expected[~small], expected[small].sum())
    chi2 = np.sum((o - e) ** 2 / np.maximum(e, 1e-300))
    p = chi2_survival(chi2, len(o) - 1)
    assert p > 0.01, f"{name}: chi2 {chi2:.1f} with {len(o) - 1} dof, p = {p:.2e}"


def test_a_wrong_pdf_fails_the_chi_square_test(models):
    """The test above has power: deon2011's samples judged against the pdf of a fiber 1.5x
    rougher fail it."""
    wi = np.array([math.sin(0.4), math.cos(0.4), 0.0])
    wo, _, pdf = models["deon2011"].sample(wi, np.random.default_rng(11).random((200_000, 4)))
    wo = wo[pdf > 0]
    theta, phi = np.arcsin(np.clip(wo[:, 0], -1, 1)), np.arctan2(wo[:, 2], wo[:, 1])
    observed, _, _ = np.histogram2d(theta, phi, bins=(16, 24), range=[[-1.5708, 1.5708], [-np.pi, np.pi]])
    rougher = cuticle.Fiber("deon2011", beta=0.06)
    expected = len(wo) * bin_integrals(lambda d: rougher.pdf(wi, d), 16, 24)
    small = expected < 5
    o = np.append(observed[~small], observed[small].sum())
    e = np.append(expected[~small], expected[small].sum())
    assert chi2_survival(np.sum((o - e) ** 2 / e), len(o) - 1) < 1e-6


def furnace(fiber, theta_i, theta_panels=360, phi_panels=90, nodes=8):
    """The albedo ∫ S cos θ dθ dφ by a product Gauss-Legendre rule over eval (RGB)."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    t_edges = np.linspace(-np.pi / 2, np.pi / 2, theta_panels + 1)
    p_edges = np.linspace(-np.pi, np.pi, phi_panels + 1)
    ht, hp = (t_edges[1] - t_edges[0]) / 2, (p_edges[1] - p_edges[0]) / 2
    theta = (t_edges[:-1, None] + ht * (x + 1)).ravel()
    phi = (p_edges[:-1, None] + hp * (x + 1)).ravel()
    wt = np.tile(w * ht, theta_panels) * np.cos(theta)
    wp = np.tile(w * hp, phi_panels)
    T, P = np.meshgrid(theta, phi, indexing="ij")
    wo = np.stack([np.sin(T), np.cos(T) * np.cos(P), np.cos(T) * np.sin(P)], -1).reshape(-1, 3)
    wi = np.array([math.sin(theta_i), math.cos(theta_i), 0.0])
    s = fiber.eval(wi, wo).reshape(theta.size, phi.size, 3)
    return np.einsum("tpc,t,p->c", s, wt, wp)


@pytest.mark.parametrize("theta_i", [0.0, 0.6, -1.1])
def test_deon2011_white_furnace_is_one(theta_i):
    fiber = cuticle.Fiber("deon2011", beta=0.1, mu_a=0.0, alpha_deg=0.0)
    albedo = furnace(fiber, theta_i)
    np.testing.assert_allclose(albedo, 1.0, rtol=5e-3)
    # And it is the albedo latlong reports (the Rust furnace's quadrature).
    energy = fiber.latlong(theta_i, width=40)["energy"]["total"]
    np.testing.assert_allclose(albedo, energy, rtol=1e-3)


def test_absorption_lowers_the_furnace():
    albedo = furnace(cuticle.Fiber("deon2011", beta=0.1, mu_a=(0.1, 0.5, 2.0)), 0.3)
    assert 0.05 < albedo[2] < albedo[1] < albedo[0] < 1.0


def test_parameters_and_melanin_are_the_command_lines():
    fiber = cuticle.Fiber("deon2011")
    assert (fiber.beta, fiber.alpha_deg, fiber.eta) == (0.04, -2.0, 1.55)
    assert fiber.mu_a == (0.12, 0.25, 0.5)
    assert cuticle.Fiber("deon2011", mu_a=0.3).mu_a == (0.3, 0.3, 0.3)
    dark = cuticle.Fiber("deon2011", eumelanin=2.0).mu_a
    assert dark[0] < dark[1] < dark[2] and dark[0] > 0
    # The docstring states each default the fiber crate gives and each range as it prints it.
    for name in ("beta", "alpha_deg", "eta"):
        assert f"{name}={getattr(fiber, name)}" in cuticle.Fiber.__doc__, name
    for name in ("eta", "beta", "alpha_deg", "mu_a", "iterations"):
        text = cuticle.RANGES[name].replace(" degrees", "")
        assert text in cuticle.Fiber.__doc__, (name, text)


BAD_FIBERS = [
    (dict(beta=float("nan")), "beta must be a finite number in [0.0001, 1], got NaN"),
    (dict(eta=1.0), "eta must be a finite number in (1, 10], got 1"),
    (dict(alpha_deg=45.0), "alpha_deg must be a finite number in [-20, 20] degrees, got 45"),
    (dict(mu_a=(0.1, -1.0, 0.2)), "mu_a must be a finite number in [0, 1000], got -1"),
    (dict(mu_a=(0.1, 0.2)), "mu_a takes one number or r, g, b, got 2 numbers"),
    (dict(mu_a=0.5, eumelanin=1.0), "both set the absorption; give one"),
    (dict(eumelanin=1e9), "eumelanin must be a finite number in [0, 50], got 1e9"),
    (dict(iterations=0), "iterations must be a whole number in 1..=1000, got 0"),
    (dict(iterations=-1), "iterations must be a whole number in 1..=1000, got -1"),
    (dict(model="marschner2004"), 'unknown model "marschner2004" (models: nonseparable,'),
]


@pytest.mark.parametrize("kwargs,message", BAD_FIBERS)
def test_bad_parameters_raise_value_error_with_the_command_lines_message(kwargs, message):
    with pytest.raises(ValueError) as err:
        cuticle.Fiber(**kwargs)
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_bad_types_raise_type_error():
    with pytest.raises(TypeError):
        cuticle.Fiber("deon2011", beta="rough")
    with pytest.raises(TypeError, match="mu_a must be a number or"):
        cuticle.Fiber("deon2011", mu_a="red")


def test_hostile_arrays_raise_one_clear_message(models):
    fiber = models["deon2011"]
    wi = np.array([[0.0, 1.0, 0.0]] * 4)
    cases = [
        (lambda: fiber.eval(wi, np.ones((4, 2))), "wo must have shape (N, 3) or (3,), got (4, 2)"),
        (lambda: fiber.eval(wi, np.ones((2, 2, 3))), "wo must have shape (N, 3) or (3,), got (2, 2, 3)"),
        (lambda: fiber.eval(wi, 2 * wi), "wo[0] = (0, 2, 0) is not a finite unit vector (length 2)"),
        (lambda: fiber.pdf(wi * np.nan, wi), "wi[0] = (NaN, NaN, NaN) is not a finite unit vector"),
        (lambda: fiber.eval(wi, wi[:3]), "wi has 4 rows and wo has 3"),
        (lambda: fiber.sample(wi, np.full((4, 4), 1.0)), "u must lie in [0, 1), got u[0, 0] = 1"),
        (lambda: fiber.sample(wi, np.full((4, 4), np.nan)), "u must lie in [0, 1), got u[0, 0] = NaN"),
        (lambda: fiber.sample(wi, np.zeros((4, 3))), "u must have shape (N, 4), got (4, 3)"),
        (lambda: fiber.latlong(2.0), "theta_i must be a finite number in (-1.5708, 1.5708) radians, got 2"),
        (lambda: fiber.latlong(0.5, width=10), "width must be a multiple of 4, got 10"),
        (lambda: fiber.latlong(0.5, width=40, height=20), "height must be width / 4 = 10 (the grid of `cuticle lobes`), got 20"),
        (lambda: fiber.latlong(0.5, width=10**6), "width must be a whole number in 8..=4000, got 1000000"),
    ]
    for call, message in cases:
        with pytest.raises(ValueError) as err:
            call()
        assert message in str(err.value), (message, str(err.value))
    with pytest.raises((TypeError, ValueError)):
        fiber.eval(wi, "north")


def test_empty_and_float32_inputs():
    fiber = cuticle.Fiber("deon2011")
    assert fiber.eval(np.zeros((0, 3)), np.zeros((0, 3))).shape == (0, 3)
    d = np.array([[0.6, 0.8, 0.0]], dtype=np.float32)
    np.testing.assert_allclose(fiber.eval(d, d), fiber.eval(d.astype(np.float64), d.astype(np.float64)))
    # A list of lists is an array too.
    assert fiber.pdf([0.0, 1.0, 0.0], [[0.0, 0.0, 1.0]]).shape == (1,)


def test_the_gil_is_released_while_a_call_works(models):
    """Another Python thread runs while eval works (the call releases the GIL)."""
    import threading
    import time

    fiber, rng = models["nonseparable"], np.random.default_rng(5)
    wi, wo = unit_rows(rng, 600_000), unit_rows(rng, 600_000)
    span = {}

    def work():
        span["start"] = time.perf_counter()
        fiber.eval(wi, wo)
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    start, end = span["start"], span["end"]
    assert end - start > 0.05, "the call is too short to tell"
    inside = [t for t in ticks if start + 0.01 < t < end - 0.01]
    assert len(inside) > 5, f"{len(inside)} ticks of the main thread in {end - start:.3f} s"
