#!/usr/bin/env python3
"""The polynomial coefficients of crates/fiber/src/special.rs's sin_cos_quadrant, asin_fast,
atan2_fast and ln_fast: near-minimax Chebyshev fits (mpmath.chebyfit, 50 digits), lowest degree first, printed as
Rust literals. Run: python3 crates/fiber/tools/chebyfit.py (needs mpmath)."""
import mpmath as mp

mp.mp.dps = 50


def fit(name, f, a, b, n):
    poly, err = mp.chebyfit(f, [a, b], n, error=True)
    print(f"// {name}: degree {n - 1}, fit error {mp.nstr(err, 3)}")
    print(f"const {name}: [f64; {n}] = [")
    for c in poly[::-1]:
        print(f"    {float(c)!r},")
    print("];")


def sinc(t):
    return mp.sin(mp.sqrt(t)) / mp.sqrt(t) if t != 0 else mp.mpf(1)


def asin_rest(t):
    # (asin √t − √t) / (t √t), so that asin x = x + x t g(t) with t = x².
    if t == 0:
        return mp.mpf(1) / 6
    s = mp.sqrt(t)
    return (mp.asin(s) - s) / (t * s)


def atan_rest(t):
    # (atan √t − √t) / (t √t), so that atan x = x + x t g(t) with t = x².
    if t == 0:
        return mp.mpf(-1) / 3
    s = mp.sqrt(t)
    return (mp.atan(s) - s) / (t * s)


def atanh_rest(t):
    # (atanh √t − √t) / (t √t), so that ln m = 2 atanh f = 2f + 2f t g(t) with t = f².
    if t == 0:
        return mp.mpf(1) / 3
    s = mp.sqrt(t)
    return (mp.atanh(s) - s) / (t * s)


quarter_turn_sq = (mp.pi / 2) ** 2
fit("SIN_FIT", sinc, 0, quarter_turn_sq, 9)
fit("COS_FIT", lambda t: mp.cos(mp.sqrt(t)), 0, quarter_turn_sq, 9)
fit("ASIN_FIT", asin_rest, 0, mp.mpf(1) / 4, 12)
fit("ATAN_FIT", atan_rest, 0, mp.tan(mp.pi / 12) ** 2, 9)
fit("LN_FIT", atanh_rest, 0, ((mp.sqrt(2) - 1) / (mp.sqrt(2) + 1)) ** 2, 7)
