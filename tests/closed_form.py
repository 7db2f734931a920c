"""Closed forms of two 1D wave problems at the foundation, for the tests
impact_bar.py and shear_wave.py and for benchmarks/closed-form
(doc/theory.md, section 10). Python 3 standard library only.

- ImpactBar: a bar of length L (P-wave modulus Ep = lambda + 2 mu, density
  rho) moving at -V onto the Kelvin-Voigt foundation p = c_nu s_+,
  q = d_nu (ds/dt)_+ (s the penetration of its end): d'Alembert's solution
  reduces the contact to the delay equation
      Z ds/dt + c_nu s_+ + d_nu (ds/dt)_+ = R(t),  Z = rho c,
      R(t) = Z V for t < T2 = 2L/c,  R(t) = -Z V + 2 Z ds/dt(t - T2) - ...
  (exactly: R = -2 Z f(t), f the downward wave at the end, f(t) = -V/2 for
  t < T2 and f(t) = g(t - T2) after, g = -f - ds/dt the upward wave it
  sends), solved step by step (Heun's rule on a grid that T2 divides; every
  jump of R falls on the grid).
- ShearBase: a plane shear wave of incident traction tau_inc(t) at a base
  pressed with p: the base's slip rate v >= 0 solves
      2 tau_inc - rho c_s v = mu(v) p  (slip)  or  v = 0, 2 tau_inc <= mu(0) p
  (stick); with a nonmonotone mu this has up to three solutions, and the
  one continued in time (the branch the program's loop follows from the
  last step's velocity) is returned.
"""

import math


class ImpactBar:
    def __init__(self, rho, ep, length, v0, c_nu, d_nu, t_end, n_per_t2=100000):
        self.rho, self.ep, self.length, self.v0 = rho, ep, length, v0
        self.c_nu, self.d_nu = c_nu, d_nu
        self.c = math.sqrt(ep / rho)
        self.z = rho * self.c
        self.t2 = 2 * length / self.c
        m = n_per_t2
        self.dt = self.t2 / m
        n = int(math.ceil(t_end / self.dt)) + 1
        z, c, d = self.z, c_nu, d_nu

        def rate(s, r):
            r = r - c * max(s, 0.)
            return r / (z + d) if r > 0 else r / z

        # Per interval j = [t_j, t_j+1]: the upward wave g just after t_j and
        # just before t_j+1 (jumps fall on grid points).
        g_start, g_end = [], []
        s = [0.]
        force_start, force_end = [], []
        for j in range(n):
            if j < m:
                f0 = f1 = -v0 / 2
            else:
                f0, f1 = g_start[j - m], g_end[j - m]
            r0, r1 = -2 * z * f0, -2 * z * f1
            k1 = rate(s[j], r0)
            k2 = rate(s[j] + self.dt * k1, r1)
            s1 = s[j] + self.dt * (k1 + k2) / 2
            rate0, rate1 = k1, rate(s1, r1)
            g_start.append(-f0 - rate0)
            g_end.append(-f1 - rate1)
            force_start.append(c * max(s[j], 0.) + d * max(rate0, 0.))
            force_end.append(c * max(s1, 0.) + d * max(rate1, 0.))
            s.append(s1)
        self.s = s
        self.force_start, self.force_end = force_start, force_end
        # The centre of mass's velocity: -V + (impulse)/(rho L).
        v = [-v0]
        for j in range(n):
            v.append(v[-1] + self.dt * (force_start[j] + force_end[j]) / 2 /
                     (rho * length))
        self.v_cm = v

    def _interp(self, values, t):
        x = t / self.dt
        j = min(int(x), len(values) - 2)
        a = x - j
        return (1 - a) * values[j] + a * values[j + 1]

    def penetration(self, t):
        return self._interp(self.s, t)

    def centre_velocity(self, t):
        return self._interp(self.v_cm, t)

    def peak_force(self):
        return max(max(self.force_start), max(self.force_end))

    def penetration_max(self):
        return max(self.s)

    def contact_end(self):
        """The first time after 0 at which the end leaves the foundation
        (s falls to 0), linearly interpolated on the grid."""
        for j in range(1, len(self.s) - 1):
            if self.s[j] > 0 and self.s[j + 1] <= 0:
                return (j + self.s[j] / (self.s[j] - self.s[j + 1])) * self.dt
        return float("nan")

    def recontact(self, t_from):
        """Whether the end touches the foundation again after t_from."""
        j0 = int(t_from / self.dt) + 2
        return any(x > 0 for x in self.s[j0:])


def crossing(times, values):
    """The first time where values falls from > 0 to <= 0 after having been
    > 0, linearly interpolated; nan if never."""
    for i in range(1, len(values)):
        if values[i - 1] > 0 and values[i] <= 0:
            return times[i - 1] + (times[i] - times[i - 1]) * \
                values[i - 1] / (values[i - 1] - values[i])
    return float("nan")


class ShearBase:
    """The slip rate of a base under a plane shear wave; mu(v) =
    (a - b) exp(-alpha v) + b, impedance z = rho c_s, pressure p."""

    def __init__(self, z, p, a, b, alpha):
        self.z, self.p, self.a, self.b, self.alpha = z, p, a, b, alpha

    def mu(self, v):
        return (self.a - self.b) * math.exp(-self.alpha * v) + self.b

    def residual(self, tau, v):
        return 2 * tau - self.z * v - self.mu(v) * self.p

    def several_roots(self):
        """Whether 2 tau - z v = mu(v) p can have several roots: mu falls
        faster than the impedance line at v = 0."""
        return (self.a - self.b) * self.alpha * self.p > self.z

    def fold(self):
        """(v_f, tau_f): where the upper slip branch ends (residual and its
        derivative vanish); None without several roots."""
        if not self.several_roots():
            return None
        v = math.log((self.a - self.b) * self.alpha * self.p / self.z) / \
            self.alpha
        return v, (self.z * v + self.mu(v) * self.p) / 2

    def upper_root(self, tau):
        """The largest root v > 0 of the residual, or None."""
        # The residual is concave in v: it rises to its maximum at v_m (0
        # without several roots), then falls; the largest root lies beyond.
        fold = self.fold()
        v_m = fold[0] if fold else 0.
        if self.residual(tau, v_m) < 0:
            return None
        lo, hi = v_m, v_m + 1.
        while self.residual(tau, hi) > 0:
            hi *= 2
        for _ in range(200):
            mid = (lo + hi) / 2
            if not lo < mid < hi:
                break  # lo and hi are neighbouring doubles: converged
            if self.residual(tau, mid) > 0:
                lo = mid
            else:
                hi = mid
        root = (lo + hi) / 2
        return root if root > 0 else None

    def history(self, taus):
        """The slip rates along a history of tau_inc >= 0 from rest, on the
        branch continued in time: stick while 2 tau <= mu(0) p, else the
        upper root, kept (after slipping) while it exists."""
        out, slipping = [], False
        for tau in taus:
            if not slipping and 2 * tau > self.a * self.p:
                slipping = True
            v = self.upper_root(tau) if slipping else None
            if v is None:
                slipping = False
                v = 0.
            out.append(v)
        return out
