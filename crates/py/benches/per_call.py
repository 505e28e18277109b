"""Per-direction cost of cuticle.Fiber's eval, sample and pdf from Python, on the inputs of
BENCHMARKS.md's "Fiber models, per call" (issue 15: directions uniform on the sphere,
beta = 0.3, alpha = 2 degrees, mu_a from eumelanin 1.3), for comparison with the Rust
per-call figures there (issue 55: within 1.5x at N = 1,000,000, on all cores). A benchmark,
not a test: run it on an idle machine.

    python crates/py/benches/per_call.py [N] [repeats]
    RAYON_NUM_THREADS=1 python crates/py/benches/per_call.py    # one core, like for like
"""

import os
import sys
import time

import numpy as np

import cuticle

# Chiang 2016 is left out: BENCHMARKS.md times it at a known h (near field), the bindings'
# eval is its far field (averaged over h).
MODELS = ["deon2011", "nonseparable", "marschner"]


def uniform_sphere(rng, n):
    z = rng.uniform(-1, 1, n)
    phi = rng.uniform(-np.pi, np.pi, n)
    r = np.sqrt(1 - z * z)
    return np.stack([z, r * np.cos(phi), r * np.sin(phi)], axis=1)


def median_seconds(call, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def main(n, repeats):
    rng = np.random.default_rng(1)
    wi, wo, u = uniform_sphere(rng, n), uniform_sphere(rng, n), rng.random((n, 4))
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    print(f"N = {n}, median of {repeats}, threads {threads}: ns per direction (wall / N)")
    for name in MODELS:
        fiber = cuticle.Fiber(name, beta=0.3, alpha_deg=2.0, eumelanin=1.3)
        row = []
        for label, call in [
            ("eval", lambda: fiber.eval(wi, wo)),
            ("sample", lambda: fiber.sample(wi, u)),
            ("pdf", lambda: fiber.pdf(wi, wo)),
        ]:
            call()  # warm-up
            row.append(f"{label} {1e9 * median_seconds(call, repeats) / n:.0f}")
        print(f"{name:>14}: " + " / ".join(row))


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000, int(sys.argv[2]) if len(sys.argv) > 2 else 5)
