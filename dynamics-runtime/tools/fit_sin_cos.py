#!/usr/bin/env python3
"""Fit the polynomial coefficients of `dynamics_runtime::fast_trig` (sin and cos on [-pi/4, pi/4]).

    python3 dynamics-runtime/tools/fit_sin_cos.py            # needs mpmath (pip install mpmath)

What it fits, with z = r^2 and |r| <= pi/4 (plus a small margin, see MARGIN):

    sin r = r + r z P(z),          P(z) = S1 + S2 z + ... + S6 z^5      (degree 13 in r)
    cos r = 1 - z/2 + z^2 Q(z),    Q(z) = C1 + C2 z + ... + C6 z^5      (degree 14 in r)

Each of P and Q is the weighted minimax polynomial (Remez exchange, written out below) for the
*relative* error of sin and cos: the error of P is weighted by r^3 / sin r, that of Q by
z^2 / cos r. The targets are evaluated from their Taylor series in 60-digit arithmetic, so
there is no cancellation near z = 0. The coefficients are then rounded to f64 one at a time,
constant term first, refitting the remaining ones to what is left after each rounding
(`remez_rounded`), and the relative error of the rounded polynomial (in exact arithmetic) is
measured on a dense grid and printed, beside that of rounding all at once: this is the
approximation part of the error budget stated in fast_trig.rs (the rest is the f64
evaluation). It also prints the same figures for one coefficient less, to show why degrees
13 and 14 are needed for f64.

The three-part split of pi/2 (C1 + C2 + C3: two 33-bit heads and a 53-bit tail) is printed
at the end, as exact decimal strings, so the constants can be checked too.

Output: Rust `const` lines to paste into fast_trig.rs. Deterministic (no randomness); takes
about five minutes (60-digit arithmetic, pure Python).
"""
import mpmath as mp

mp.mp.dps = 60
MARGIN = mp.mpf("1.0001")  # fit a little beyond pi/4: the reduced argument can exceed it by ~1 ulp
R_MAX = mp.pi / 4 * MARGIN
Z_MAX = R_MAX**2


def p_target(z):
    """(sin r - r) / r^3 as a series in z = r^2: sum_{k>=1} (-1)^k z^(k-1) / (2k+1)!."""
    return mp.fsum((-1) ** k * z ** (k - 1) / mp.factorial(2 * k + 1) for k in range(1, 40))


def q_target(z):
    """(cos r - 1 + z/2) / z^2 = sum_{k>=2} (-1)^k z^(k-2) / (2k)!."""
    return mp.fsum((-1) ** k * z ** (k - 2) / mp.factorial(2 * k) for k in range(2, 40))


def p_weight(z):
    r = mp.sqrt(z)
    return r**3 / mp.sin(r)


def q_weight(z):
    r = mp.sqrt(z)
    return z**2 / mp.cos(r)


def horner(c, z):
    acc = mp.mpf(0)
    for ck in reversed(c):
        acc = acc * z + ck
    return acc


def remez(f, w, n, a, b, iterations=30):
    """Weighted minimax polynomial of n coefficients for f on [a, b]; returns (coeffs, E)."""
    # Start from n + 1 points clustered towards both ends but away from z = 0, where the
    # weights vanish (a reference point there would make the system meaningless).
    pts = [a + (b - a) * mp.sin(mp.pi * (i + 1) / (2 * (n + 1))) ** 2 for i in range(n + 1)]
    grid = [(a + b) / 2 - (b - a) / 2 * mp.cos(mp.pi * i / 4000) for i in range(4001)]
    coeffs, level = None, None
    for _ in range(iterations):
        # p(z_i) + (-1)^i E / w(z_i) = f(z_i); the weight at z = 0 is 0 for P, so guard it.
        rows, rhs = [], []
        for i, z in enumerate(pts):
            wz = w(z)
            rows.append([z**k for k in range(n)] + [(-1) ** i / wz])
            rhs.append(f(z))
        sol = mp.lu_solve(mp.matrix(rows), mp.matrix(rhs))
        coeffs = [sol[k] for k in range(n)]
        level = abs(sol[n])
        err = [w(z) * (horner(coeffs, z) - f(z)) for z in grid]
        # Local extrema of the error, alternating in sign, n + 1 of them.
        ext = []
        for i in range(len(grid)):
            left = err[i - 1] if i > 0 else None
            right = err[i + 1] if i + 1 < len(grid) else None
            e = err[i]
            if (left is None or abs(e) >= abs(left)) and (right is None or abs(e) >= abs(right)):
                if ext and mp.sign(err[ext[-1]]) == mp.sign(e):
                    if abs(e) > abs(err[ext[-1]]):
                        ext[-1] = i
                else:
                    ext.append(i)
        while len(ext) > n + 1:  # drop the smaller end
            if abs(err[ext[0]]) < abs(err[ext[-1]]):
                ext.pop(0)
            else:
                ext.pop()
        if len(ext) < n + 1:
            break
        new = [grid[i] for i in ext]
        top = max(abs(err[i]) for i in ext)
        pts = new
        if top - level < level * mp.mpf("1e-6"):
            break
    return coeffs, level


def remez_rounded(f, w, n, a, b):
    """Minimax coefficients rounded one at a time: fit all n, round the constant term to f64,
    then refit the others to what is left, (f - c0) / z with weight w z, and so on. The
    later coefficients absorb the rounding of the earlier (larger) ones."""
    fixed = []
    for k in range(n):
        coeffs, _ = remez(lambda z, k=k: (f(z) - horner(fixed, z)) / z**k,
                          lambda z, k=k: w(z) * z**k, n - k, a, b)
        fixed.append(mp.mpf(f64(coeffs[0])))
    return [f64(c) for c in fixed]


def max_rel_error(coeffs_f64, kind):
    worst = mp.mpf(0)
    for i in range(1, 20001):
        r = R_MAX * i / 20000
        z = r * r
        if kind == "sin":
            approx = r + r * z * horner(coeffs_f64, z)
            exact = mp.sin(r)
        else:
            approx = 1 - z / 2 + z * z * horner(coeffs_f64, z)
            exact = mp.cos(r)
        worst = max(worst, abs(approx / exact - 1))
    return worst


def f64(x):
    return float(x)  # round to nearest


def main():
    for name, f, w, n in (("S", p_target, p_weight, 6), ("C", q_target, q_weight, 6)):
        kind = "sin" if name == "S" else "cos"
        for degree_terms in (n - 1, n):
            # The weights vanish at z = 0 (there P and Q contribute nothing), so the interval
            # starts just above it.
            coeffs, level = remez(f, w, degree_terms, Z_MAX * mp.mpf("1e-9"), Z_MAX)
            rounded = remez_rounded(f, w, degree_terms, Z_MAX * mp.mpf("1e-9"), Z_MAX)
            exact_err = max_rel_error(coeffs, kind)
            err = max_rel_error([mp.mpf(c) for c in rounded], kind)
            naive = max_rel_error([mp.mpf(f64(c)) for c in coeffs], kind)
            print(f"// {kind}: {degree_terms} coefficients, relative error {mp.nstr(exact_err, 5)} "
                  f"(minimax level {mp.nstr(level, 5)}), rounded to f64 one at a time {mp.nstr(err, 5)} "
                  f"(2^{mp.nstr(mp.log(err, 2), 4)}; all at once {mp.nstr(naive, 5)})")
        for k, c in enumerate(rounded):
            print(f"const {name}{k + 1}: f64 = {c!r};")
    # The split of pi/2.
    half_pi = mp.pi / 2
    c1 = mp.floor(half_pi * 2**32) / 2**32          # 33 significant bits (1 before the point)
    c2 = mp.floor((half_pi - c1) * 2**65) / 2**65   # the next 33 bits
    c3 = f64(half_pi - c1 - c2)                     # the rest, rounded to 53 bits
    print(f"const PIO2_1: f64 = {f64(c1)!r}; // {mp.nstr(c1, 30)} = {int(c1 * 2**32)} * 2^-32")
    print(f"const PIO2_2: f64 = {f64(c2)!r}; // {int(c2 * 2**65)} * 2^-65")
    print(f"const PIO2_3: f64 = {c3!r};")
    rest = half_pi - c1 - c2 - mp.mpf(c3)
    print(f"// pi/2 - (PIO2_1 + PIO2_2 + PIO2_3) = {mp.nstr(rest, 5)} (2^{mp.nstr(mp.log(abs(rest), 2), 4)})")
    assert f64(c1) == c1 and f64(c2) == c2
    assert int(c1 * 2**32).bit_length() <= 33 and int(c2 * 2**65).bit_length() <= 33


if __name__ == "__main__":
    main()
