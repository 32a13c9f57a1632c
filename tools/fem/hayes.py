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


def _layer_state(s, tau, g, nu):
    """Rows u_r, u_z, sigma_z, tau_rz per unit of the coefficients A, B, C, D of Love's strain
    function f = (A + B s) exp(s - tau) + (C + D s) exp(-s) at local depth s = xi z of a
    layer tau = xi t thick, shear modulus g, wavenumber xi = 1."""
    p, e = np.exp(s - tau), np.exp(-s)
    f = np.array([[p, s * p, e, s * e], [p, (1 + s) * p, -e, (1 - s) * e],
                  [p, (2 + s) * p, e, (s - 2) * e], [p, (3 + s) * p, -e, (3 - s) * e]])
    return np.array([f[1] / (2 * g), ((1 - 2 * nu) * f[2] - 2 * (1 - nu) * f[0]) / (2 * g),
                     (1 - nu) * f[3] - (2 - nu) * f[1], nu * f[2] + (1 - nu) * f[0]])


def column_kernel_weight(u, layers, nu):
    """M(u) of a layered column [(thickness m, modulus Pa)] from the skin down, bonded to each
    other and to a rigid base, frictionless skin: 1 - its surface compliance at u = xi h over
    that of a half-space of the top layer's modulus (core/src/mat/layer_stiffness.cpp)."""
    h, n = sum(t for t, _ in layers), len(layers)
    tau = [u * t / h for t, _ in layers]
    g = [E / (2 * (1 + nu)) for _, E in layers]
    a, b = np.zeros((4 * n, 4 * n)), np.zeros(4 * n)
    skin = _layer_state(0.0, tau[0], g[0], nu)
    a[0:2, 0:4], b[0] = skin[2:4], 1.0
    for i in range(n - 1):
        a[2 + 4 * i:6 + 4 * i, 4 * i:4 * i + 4] = _layer_state(tau[i], tau[i], g[i], nu)
        a[2 + 4 * i:6 + 4 * i, 4 * i + 4:4 * i + 8] = -_layer_state(0.0, tau[i + 1], g[i + 1], nu)
    a[4 * n - 2:, 4 * n - 4:] = _layer_state(tau[-1], tau[-1], g[-1], nu)[0:2]
    w = skin[1] @ np.linalg.solve(a, b)[0:4]
    return 1.0 - abs(w) * layers[0][1] / (2 * (1 - nu * nu))


def _panels(lo, hi, count):
    x, w = np.polynomial.legendre.leggauss(8)
    width = (hi - lo) / count
    starts = lo + width * np.arange(count)
    return ((starts[:, None] + 0.5 * width * (x + 1)).ravel(), np.tile(0.5 * width * w, count))


def column_modulus(a, layers, nu):
    """The equivalent modulus (Pa) of a layered column under a flat punch of radius a: the
    column's kappa over the homogeneous kappa, times the top layer's modulus (the same
    quadrature as core/src/mat/layer_stiffness.cpp; 2 or more layers, a/h <= 10)."""
    h = sum(t for t, _ in layers)
    lam = a / h
    tail = 20.0 * min(h / layers[0][0], 200.0)
    count = lambda lo, hi: max(40, int(np.ceil(lam * (hi - lo) / 3.0)) * 2)
    u, wu = _panels(0.0, 20.0, count(0.0, 20.0))
    if tail > 20.0:
        u2, w2 = _panels(20.0, tail, count(20.0, tail))
        u, wu = np.concatenate([u, u2]), np.concatenate([wu, w2])
    x, wx = _panels(0.0, 1.0, 4)

    def factor(m):
        C = np.cos(lam * np.outer(x, u))
        A = np.eye(len(x)) - (2.0 * lam / np.pi) * ((C * (m * wu)) @ C.T) * wx[None, :]
        return float(wx @ np.linalg.solve(A, np.ones(len(x))))
    column = factor(np.array([column_kernel_weight(v, layers, nu) for v in u]))
    return layers[0][1] * column / factor(layer_kernel_weight(u, nu))


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
