#!/usr/bin/env python3
"""Spence's problem in plane strain by a boundary-element method on two elastic half-planes: a
cylinder pressed into a block with Coulomb friction, loaded monotonically; prints the half-width
of the central stick zone c against the contact half-width a.

An independent reference for slideline's plane frictional contact (Spence 1975, "The Hertz
contact problem with finite friction", J. Elasticity 5), the plane counterpart of
scripts/spence_bem.py. Nothing here shares code or discretisation with slideline: the
half-planes' surface relations (Johnson, Contact Mechanics, eq. 2.25) for the relative normal
and tangential displacements h and g of the two surfaces under the pressure p and the shear q,
    dh/dx = -(A / pi) PV int p(s) / (x - s) ds - beta A q(x),
    dg/dx = +(A / pi) PV int q(s) / (x - s) ds - beta A p(x),
A = 2 / E* and Dundurs' beta = (B1 - B2) / A, B_i = (1 - 2 nu_i)(1 + nu_i) / E_i (1 the
cylinder, q the shear on the block, g = u_x1 - u_x2; the operator from (p, q) to (h, -g) is
symmetric, as reciprocity wants); tractions constant on elements, displacements matched at their
centres; at each load step the contact and stick sets by an active-set iteration: in contact
h = delta - x^2 / (2R), p >= 0; sticking nodes keep g, sliding ones carry q = mu p sign(dg).

    python3 scripts/spence_bem_plane.py --beta -0.2851 --mu 0.2851 0.1996 0.4073

Units: A = 1, R = 1, the final load gives a = 1 (Hertz): c/a is free of all three. c/a is the
median over the last fifth of the steps (it is self-similar; a step's active set is now and then
one element off). About 10 s per mu at the defaults. tests/plane_sections.rs quotes its answers.
"""
import argparse

import numpy as np


def kernels(x, d):
    """Element-integrated kernels at the element centres x (width d): int ln|x_i - s| ds and
    int sign(x_i - s) ds over element j."""
    def big_g(u):
        safe = np.where(u == 0.0, 1.0, np.abs(u))
        return np.where(u == 0.0, 0.0, u * np.log(safe) - u)
    xi, sj = np.meshgrid(x, x, indexing="ij")
    logs = big_g(xi - (sj - d / 2)) - big_g(xi - (sj + d / 2))
    signs = np.sign(xi - sj) * d
    return logs, signs


def solve(beta, mu, elements=200, steps=60, extent=1.3):
    """Loads in `steps` equal steps to P = pi / 2 (a = 1 frictionless); returns per step
    (P, a, c) and the last step's x, p, q, contact and stick flags."""
    a_coef = 1.0
    d = 2.0 * extent / elements
    x = -extent + d * (np.arange(elements) + 0.5)
    logs, signs = kernels(x, d)
    kn, cn = -(a_coef / np.pi) * logs, -(beta * a_coef / 2.0) * signs  # h = kn p + cn q
    kt, ct = (a_coef / np.pi) * logs, -(beta * a_coef / 2.0) * signs  # g = kt q + ct p
    p, q, g = np.zeros(elements), np.zeros(elements), np.zeros(elements)
    contact = np.abs(x) < d
    stick = np.ones(elements, dtype=bool)
    direction = np.zeros(elements)
    history = []
    for step in range(1, steps + 1):
        load = (np.pi / 2.0) * step / steps
        g_before = g.copy()
        for _ in range(200):
            cs = np.where(contact)[0]
            st = np.where(contact & stick)[0]
            sl = np.where(contact & ~stick)[0]
            m, k = len(cs), len(st)
            # unknowns [p on cs, q on st, delta]; q on sl = mu p direction
            slip_q = np.zeros((elements, m))  # q on sliding elements from p
            col = {j: i for i, j in enumerate(cs)}
            for j in sl:
                slip_q[j, col[j]] = mu * direction[j]
            mat = np.zeros((m + k + 1, m + k + 1))
            rhs = np.zeros(m + k + 1)
            mat[:m, :m] = kn[np.ix_(cs, cs)] + cn[cs] @ slip_q
            mat[:m, m:m + k] = cn[np.ix_(cs, st)]
            mat[:m, -1] = -1.0
            rhs[:m] = -x[cs] ** 2 / 2.0
            mat[m:m + k, :m] = ct[np.ix_(st, cs)] + kt[st] @ slip_q
            mat[m:m + k, m:m + k] = kt[np.ix_(st, st)]
            rhs[m:m + k] = g_before[st]
            mat[-1, :m] = d
            rhs[-1] = load
            sol = np.linalg.solve(mat, rhs)
            p = np.zeros(elements)
            p[cs] = sol[:m]
            q = slip_q @ sol[:m]
            q[st] = sol[m:m + k]
            delta = sol[-1]
            h, g = kn @ p + cn @ q, kt @ q + ct @ p
            changed = False
            for i in range(elements):
                if contact[i] and p[i] < 0.0:
                    contact[i], stick[i], changed = False, True, True
                elif not contact[i] and h[i] < delta - x[i] ** 2 / 2.0 - 1e-12:
                    contact[i], stick[i], changed = True, True, True
            slip = g - g_before
            for i in np.where(contact)[0]:
                if stick[i] and abs(q[i]) > mu * p[i] * (1.0 + 1e-12):
                    stick[i], direction[i], changed = False, np.sign(q[i]), True
                elif not stick[i] and slip[i] * direction[i] < 0.0:
                    stick[i], changed = True, True
            if not changed:
                break
        a = np.abs(x[contact]).max() + d / 2.0
        held = contact & stick
        c = np.abs(x[held]).max() + d / 2.0 if held.any() else 0.0
        history.append((load, a, c))
    return history, (x, p, q, contact, stick)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--beta", type=float, required=True, help="Dundurs' beta")
    parser.add_argument("--mu", type=float, nargs="+", required=True)
    parser.add_argument("--elements", type=int, default=200)
    parser.add_argument("--steps", type=int, default=60)
    args = parser.parse_args()
    # frictionless first: Hertz's a = 1 and p0 = 1 check the normal part
    history, (_, p, _, _, _) = solve(args.beta, 0.0, args.elements, args.steps)
    print(f"frictionless: a {history[-1][1]:.4f} (Hertz 1), p0 {p.max():.4f} (Hertz 1)")
    for mu in args.mu:
        history, (_, p, _, _, _) = solve(args.beta, mu, args.elements, args.steps)
        ratios = [c / a for _, a, c in history[-max(1, args.steps // 5):]]
        print(f"beta {args.beta:+.4f}, mu {mu:.4f} (beta / mu {args.beta / mu:+.3f}): c/a {np.median(ratios):.4f} "
              f"(last steps {min(ratios):.3f} .. {max(ratios):.3f}), a {history[-1][1]:.4f}, p0 {p.max():.4f}")


if __name__ == "__main__":
    main()
