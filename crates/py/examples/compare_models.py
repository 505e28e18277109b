"""The non-separable model beside the Monte Carlo simulator for one fiber, as a notebook
would draw it: both as lat-long images of S, and their azimuthal profiles (S integrated
over theta_o) per lobe. Writes compare_models.png (or the path given).

    pip install ./crates/py matplotlib
    python crates/py/examples/compare_models.py [out.png]
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import cuticle  # noqa: E402

# One configuration: light at 0.4 rad, a rough fiber with tilted scales, light brown.
THETA_I, BETA, ALPHA_DEG, ETA, MU_A = 0.4, 0.1, -3.0, 1.55, (0.12, 0.25, 0.5)
LOBES = ["R", "TT", "TRT", "TRRT", "rest"]


def azimuthal(image):
    """S integrated over theta_o per column (channel mean), sr^-1 per radian of phi."""
    height = image.shape[0]
    edges = np.linspace(np.pi / 2, -np.pi / 2, height + 1)
    row_weight = np.sin(edges[:-1]) - np.sin(edges[1:])  # ∫ cos θ dθ over each row
    return np.einsum("hwc,h->w", image, row_weight) / 3.0


def main(out):
    model = cuticle.Fiber("nonseparable", beta=BETA, alpha_deg=ALPHA_DEG, eta=ETA, mu_a=MU_A)
    drawn = model.latlong(THETA_I, width=400)
    simulated = cuticle.simulate(
        theta_i=THETA_I, alpha_deg=ALPHA_DEG, beta=BETA, eta=ETA, mu_a=MU_A, rays=4_000_000, seed=1
    )
    white = np.percentile(drawn["total"], 99.5)
    fig = plt.figure(figsize=(12, 8), layout="constrained")
    grid = fig.add_gridspec(3, 2, height_ratios=[1, 1, 1.4])
    extent = [-180, 180, -90, 90]
    for column, (title, images) in enumerate([("nonseparable model", drawn), ("simulator", simulated)]):
        ax = fig.add_subplot(grid[0, column])
        ax.imshow(np.clip(images["total"] / white, 0, 1) ** (1 / 2.2), extent=extent, aspect="auto")
        ax.set_title(f"{title}: S, all lobes (θ_i = {THETA_I} rad)")
        ax.set_xlabel("φ_o (degrees)")
        ax.set_ylabel("θ_o (degrees)")
        ax = fig.add_subplot(grid[1, column])
        ax.imshow(
            np.clip(np.abs(drawn["total"] - simulated["total"]) / white, 0, 1) ** (1 / 2.2)
            if column
            else np.clip(drawn["TT"] / white, 0, 1) ** (1 / 2.2),
            extent=extent,
            aspect="auto",
        )
        ax.set_title("|model − simulator|" if column else "model: TT lobe alone")
        ax.set_xlabel("φ_o (degrees)")
    ax = fig.add_subplot(grid[2, :])
    phi = np.linspace(-180, 180, 400, endpoint=False) + 180 / 400
    for k, lobe in enumerate(LOBES):
        color = f"C{k}"
        ax.plot(phi, azimuthal(drawn[lobe]), color=color, label=f"{lobe} model")
        ax.plot(phi, azimuthal(simulated[lobe]), color=color, ls="--", label=f"{lobe} simulator")
    ax.set_yscale("log")
    ax.set_ylim(1e-4, None)
    ax.set_xlabel("φ_o (degrees)")
    ax.set_ylabel("∫ S cos θ dθ (per radian), channel mean")
    ax.legend(ncol=5, fontsize="small")
    energies = ", ".join(
        f"{lobe} {drawn['energy'][lobe].mean():.3f}/{simulated['energy'][lobe].mean():.3f}" for lobe in LOBES
    )
    ax.set_title(f"azimuthal profiles; energy model/simulator: {energies}")
    fig.suptitle(f"β = {BETA}, α = {ALPHA_DEG}°, η = {ETA}, μ_a = {MU_A}")
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "compare_models.png")
