"""Independent quadrature of the element integrals, for the kernel tests."""

import math

from scipy import integrate


def square_integral_reference(x, y, k=0.0, b=0.5):
    """Integral of |r - r'|^-(1+k) over the square |x'|, |y'| <= b seen from (x, y), by quadrature."""
    if abs(x) < b and abs(y) < b:  # polar about the field point: int rho^-k drho = rho_max^(1-k)/(1-k)

        def f(t):
            c, s = math.cos(t), math.sin(t)
            rx = ((b - x) / c if c > 0 else (-b - x) / c) if abs(c) > 1e-300 else math.inf
            ry = ((b - y) / s if s > 0 else (-b - y) / s) if abs(s) > 1e-300 else math.inf
            return min(rx, ry) ** (1 - k) / (1 - k)

        pts = sorted(math.atan2(cy - y, cx - x) % (2 * math.pi) for cx in (-b, b) for cy in (-b, b))
        return integrate.quad(f, 0, 2 * math.pi, points=pts, limit=200, epsabs=1e-13)[0]
    return integrate.dblquad(
        lambda yy, xx: math.hypot(x - xx, y - yy) ** -(1 + k), -b, b, -b, b, epsabs=1e-12, epsrel=1e-10
    )[0]
