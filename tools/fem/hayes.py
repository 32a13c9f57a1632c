#!/usr/bin/python3
"""Layer correction factor kappa(a/h, nu) for a flat punch on a bonded layer.

Hayes, Keer, Herrmann and Mockros (J. Biomech. 5 (1972) 541-551) write the
force of a rigid frictionless flat-ended punch of radius a, pressed a depth
d into an elastic layer of thickness h bonded to a rigid base, as

    F = 2 a E d kappa(a/h, nu) / (1 - nu^2)

i.e. Sneddon's half-space result times kappa >= 1. They obtain kappa from a
Fredholm integral equation of the second kind; this module solves that same
equation numerically instead of reading their table:

    psi(x) - (2 lam / pi) int_0^1 k(x, y) psi(y) dy = 1,   kappa = int_0^1 psi,
    k(x, y) = int_0^inf M(u) cos(lam u x) cos(lam u y) du,   lam = a / h,
    M(u) = 1 - (2 c sinh 2u - 4u) / (2 c cosh 2u + 1 + c^2 + 4 u^2),  c = 3 - 4 nu.

(1 - M) is the surface-compliance factor of the bonded layer relative to the
half-space in Hankel-transform space; psi is the normalised Copson density
of the contact pressure. Limits used as checks: kappa -> 1 as a/h -> 0, and
for a thin compressible layer F -> pi a^2 d M_oed / h (uniaxial strain,
oedometric modulus M_oed = E (1 - nu) / ((1 + nu)(1 - 2 nu))).

Gauss-Legendre Nystrom in x, y and a trapezoidal rule in u on [0, 40]
(M(u) decays like u^2 exp(-2u)); the result changes by less than 1e-6 when
the quadrature is refined.
numpy only.
"""

import argparse
import sys

import numpy as np


def layer_kernel_weight(u, nu):
    """M(u) = 1 - L(u): the extra surface stiffness of the bonded layer."""
    c = 3.0 - 4.0 * nu
    u = np.asarray(u, dtype=float)
    # written with exp(-2u) factored out to avoid overflow at large u
    e = np.exp(-2.0 * u)
    e4 = e * e
    sinh_part = c * (1.0 - e4)          # 2 c sinh(2u) * e
    cosh_part = c * (1.0 + e4)          # 2 c cosh(2u) * e
    num = sinh_part - 4.0 * u * e
    den = cosh_part + (1.0 + c * c + 4.0 * u * u) * e
    return 1.0 - num / den


def kappa(a_over_h, nu, n=48, u_max=None, n_u=20000):
    """Hayes et al. layer factor for a flat punch (bonded base, frictionless)."""
    lam = float(a_over_h)
    if lam <= 0.0:
        return 1.0
    if not 0.0 <= nu < 0.5:
        raise ValueError("nu must be in [0, 0.5)")
    x, wx = np.polynomial.legendre.leggauss(n)
    x, wx = 0.5 * (x + 1.0), 0.5 * wx
    u_max = u_max or 40.0
    u = np.linspace(0.0, u_max, n_u + 1)
    wu = np.full(u.shape, u[1] - u[0])
    wu[0] = wu[-1] = 0.5 * (u[1] - u[0])
    m = layer_kernel_weight(u, nu) * wu
    C = np.cos(lam * np.outer(x, u))               # (n, n_u)
    K = (C * m) @ C.T                               # k(x_i, x_j)
    A = np.eye(n) - (2.0 * lam / np.pi) * K * wx[None, :]
    psi = np.linalg.solve(A, np.ones(n))
    return float(wx @ psi)


def thin_layer_kappa(a_over_h, nu):
    """Uniaxial-strain (very thin compressible layer) limit of kappa."""
    oed = (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))    # M_oed / E
    return np.pi * a_over_h * (1.0 - nu * nu) * oed / 2.0


def main(argv=None):
    p = argparse.ArgumentParser(description="Hayes et al. (1972) layer factor kappa(a/h, nu)")
    p.add_argument("a_over_h", type=float, nargs="+", help="punch radius / layer thickness")
    p.add_argument("--poisson", type=float, default=0.49)
    o = p.parse_args(argv)
    if not 0.0 <= o.poisson < 0.5:
        p.error("--poisson must be in [0, 0.5)")
    for r in o.a_over_h:
        if r < 0:
            p.error("a/h must be >= 0")
        print(f"a/h={r:g} nu={o.poisson:g} kappa={kappa(r, o.poisson):.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
