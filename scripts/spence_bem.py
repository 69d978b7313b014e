#!/usr/bin/env python3
"""Spence's problem by a boundary-element method on the elastic half-space: a rigid sphere
pressed into a linear elastic half-space with Coulomb friction, loaded monotonically; prints the
radius of the central stick zone c against the contact radius a.

An independent reference for slideline's frictional contact (Spence 1975, "The Hertz contact
problem with finite friction", J. Elasticity 5: c/a depends on mu and nu only). Nothing here
shares code or discretisation with slideline: the half-space's surface Green's functions
(Boussinesq and Cerruti) summed over rings in closed form with complete elliptic integrals,
tractions constant on annuli, displacements matched at the annuli's mid-radii, Spence's
incremental stick/slip conditions by an active-set iteration at each load step.

    python3 scripts/spence_bem.py [--mu 0.1 ...] [--nu 0.3] [--elements 400] [--steps 200]

Units: E = 1, sphere radius R = 1, final approach 1 (so a is about 1): c/a is free of all three.
Needs numpy; about 4 minutes per mu at the defaults (tests/hertz_sphere_on_flat.rs quotes them).
"""
import argparse

import numpy as np


def ellipke(m):
    """Complete elliptic integrals K(m), E(m) (parameter m = k^2) by the arithmetic-geometric mean."""
    m = np.asarray(m, dtype=float)
    a, b = np.ones_like(m), np.sqrt(1.0 - m)
    c2sum, pow2 = 0.5 * m, 0.5  # sum 2^(n-1) c_n^2, c_0^2 = m
    for _ in range(40):
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), np.sqrt(a * b)
        pow2 *= 2.0
        c2sum = c2sum + pow2 * c * c
    k = np.pi / (2.0 * a)
    return k, k * (1.0 - c2sum)


def ring_kernels(r, t, nu):
    """Surface displacements at radius r from unit line loads (force per unit length) on the
    ring of radius t, E = 1, times t: (u_z from a normal ring, u_r from an outward radial ring).
    Boussinesq: u_z = (1 - nu^2) / (pi E) P / rho; Cerruti's radial part integrates over the ring
    to (1 - nu^2) / (pi E) * int cos(phi) / rho dphi (its nu x^2 / rho^3 term sums to zero)."""
    m = 4.0 * r * t / (r + t) ** 2
    kk, ee = ellipke(np.minimum(m, 1.0 - 1e-16))
    c = (1.0 - nu * nu) / np.pi
    uz = c * t * 4.0 * kk / (r + t)
    ur = c * 2.0 * ((r * r + t * t) * kk / (r + t) - (r + t) * ee) / r
    return uz, ur


def check_cerruti_ring(nu=0.3):
    """The closed forms against a direct sum of the point-load solutions over the ring."""
    for r, t in [(1.0, 0.5), (0.7, 1.3), (1.0, 0.98)]:
        phi = np.linspace(0.0, 2.0 * np.pi, 400001)[:-1]
        dphi = phi[1] - phi[0]
        dx, dy = r - t * np.cos(phi), -t * np.sin(phi)
        rho = np.hypot(dx, dy)
        ex, ey = np.cos(phi), np.sin(phi)
        edotd = ex * dx + ey * dy
        # Cerruti, E = 1: u = (1 + nu) / pi [ (1 - nu) e / rho + nu (e . d) d / rho^3 ]
        ux = (1 + nu) / np.pi * ((1 - nu) * ex / rho + nu * edotd * dx / rho**3)
        uzb = (1 - nu * nu) / np.pi / rho
        uz, ur = ring_kernels(r, t, nu)
        assert abs(uzb.sum() * dphi * t - uz) < 1e-6 * abs(uz), (r, t)
        assert abs(ux.sum() * dphi * t - ur) < 1e-6 * abs(ur), (r, t, ux.sum() * dphi * t, ur)


GAUSS = np.polynomial.legendre.leggauss(24)


def integrate(f, lo, hi, near):
    """int_lo^hi f(t) dt for f log-singular at `near` (inside or outside): split there, and on
    the pieces next to it t = end + s^3 (the log becomes harmless to Gauss)."""
    x, w = GAUSS
    u, wu = 0.5 * (x + 1.0), 0.5 * w
    total = 0.0
    pieces = [(lo, near), (near, hi)] if lo < near < hi else [(lo, hi)]
    for a, b in pieces:
        if abs(a - near) <= abs(b - near):  # singular end a
            s = a + (b - a) * u**3
            total += np.sum(wu * 3.0 * u**2 * (b - a) * f(s))
        else:
            s = b - (b - a) * u**3
            total += np.sum(wu * 3.0 * u**2 * (b - a) * f(s))
    return total


def influence(edges, nu):
    """Influence matrices at the mid-radii for unit tractions on each annulus (E = 1):
    u_z = Czz p + Czr q, u_r = Crz p + Crr q; p pressure (into the solid), q outward shear."""
    n = len(edges) - 1
    mid = 0.5 * (edges[:-1] + edges[1:])
    czz, crr = np.zeros((n, n)), np.zeros((n, n))
    for i, r in enumerate(mid):
        for j in range(n):
            czz[i, j] = integrate(lambda t: ring_kernels(r, t, nu)[0], edges[j], edges[j + 1], r)
            crr[i, j] = integrate(lambda t: ring_kernels(r, t, nu)[1], edges[j], edges[j + 1], r)
    # Boussinesq's radial part: inward, the load inside r as if at the centre (u_r = -(1 - 2nu)
    # (1 + nu) / (E r) int_0^r p t dt); Cerruti's normal part by reciprocity.
    g = (1.0 - 2.0 * nu) * (1.0 + nu)
    lo, hi = edges[:-1][None, :], edges[1:][None, :]
    rr = mid[:, None]
    inside = np.clip(np.minimum(hi, rr), lo, None)
    crz = -g / rr * 0.5 * (inside**2 - lo**2)
    czr = -g * np.clip(hi - np.maximum(lo, rr), 0.0, None)
    return mid, czz, czr, crz, crr


OPEN, STICK, SLIP = 0, 1, 2


def solve(mu, nu, n, steps, reach=1.3, verbose=False):
    """Load the sphere (profile r^2 / 2) to approach 1 in `steps` equal steps of the approach
    (its square root, so that a grows evenly); returns [(approach, a, c)] per step."""
    edges = np.linspace(0.0, reach, n + 1)
    mid, czz, czr, crz, crr = influence(edges, nu)
    state = np.full(n, OPEN)
    sign = np.zeros(n)
    ur_prev = np.zeros(n)
    out = []
    for k in range(1, steps + 1):
        delta = (k / steps) ** 2
        target = delta - 0.5 * mid**2  # the sphere's surface, depth into the solid
        for _ in range(500):
            a = np.zeros((2 * n, 2 * n))
            rhs = np.zeros(2 * n)
            for i in range(n):
                if state[i] == OPEN:
                    a[i, i], a[n + i, n + i] = 1.0, 1.0
                    continue
                a[i, :n], a[i, n:], rhs[i] = czz[i], czr[i], target[i]
                if state[i] == STICK:
                    a[n + i, :n], a[n + i, n:], rhs[n + i] = crz[i], crr[i], ur_prev[i]
                else:
                    a[n + i, n + i], a[n + i, i] = 1.0, -sign[i] * mu
            x = np.linalg.solve(a, rhs)
            p, q = x[:n], x[n:]
            uz, ur = czz @ p + czr @ q, crz @ p + crr @ q
            # the worst violation of the current set, in lengths; one change at a time (changing
            # every violator at once cycles: the slip zone overshoots and springs back)
            worst, change = 0.0, None
            for i in range(n):
                if state[i] == OPEN:
                    # a point that touches has no pressure to stick with: it enters slipping
                    # (the direction check below makes it stick if it would not slip inward)
                    v, to = target[i] - uz[i], SLIP
                elif p[i] < 0.0:
                    v, to = -p[i] * czz[i, i], OPEN
                elif state[i] == STICK:
                    v, to = (abs(q[i]) - mu * p[i]) * crr[i, i], SLIP
                elif mu > 0.0:
                    v, to = sign[i] * (ur[i] - ur_prev[i]), STICK
                else:
                    continue
                if v > worst:
                    worst, change = v, (i, to)
            if change is None:
                break
            i, to = change
            if to == SLIP:
                sign[i] = np.sign(q[i]) if state[i] == STICK else 1.0
            state[i] = to
        else:
            raise RuntimeError(f"step {k}: the active set did not settle")
        ur_prev = ur.copy()
        contact = np.nonzero(state != OPEN)[0]
        a_k = edges[contact.max() + 1] if len(contact) else 0.0
        stick = np.nonzero(state == STICK)[0]
        c_k = edges[stick.max() + 1] if len(stick) else 0.0
        out.append((delta, a_k, c_k))
        if verbose:
            print(f"  step {k}: approach {delta:.4f} a {a_k:.4f} c {c_k:.4f} c/a {c_k / a_k if a_k else 0:.4f}")
    return out, mid, p, q


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mu", type=float, nargs="+", default=[0.1])
    ap.add_argument("--nu", type=float, default=0.3)
    ap.add_argument("--elements", type=int, default=400)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args()
    check_cerruti_ring(args.nu)
    beta = (1 - 2 * args.nu) / (2 * (1 - args.nu))
    print(f"nu {args.nu} (Dundurs' beta {beta:.4f}), {args.elements} annuli, {args.steps} steps")
    for mu in args.mu:
        hist, mid, p, q = solve(mu, args.nu, args.elements, args.steps, verbose=args.verbose)
        ratios = [c / a for _, a, c in hist[len(hist) // 2 :] if a > 0]
        delta, a, c = hist[-1]
        print(f"mu {mu}: a {a:.4f} (Hertz {delta ** 0.5:.4f}), c/a {c / a:.4f} at the end, "
              f"{min(ratios):.4f} .. {max(ratios):.4f} over the second half of the loading")


if __name__ == "__main__":
    main()
