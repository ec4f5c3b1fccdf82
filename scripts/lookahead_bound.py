#!/usr/bin/env python3
"""Premise check of look-ahead growth bounds (docs/fast-step.md section 5).

On the approach the adhesive step's result is the least fixed point of
X -> peel(X u ring(X)), peel(Y) the largest stable subset of Y (docs/fast-step.md section 1).
peel is monotone, so with U = peel(X u N(X) u ... u N^k(X)) (k layers of trial neighbours at
once) every ring j whose set X_j u R_j lies inside that k-layer domain satisfies
peel(X_j u R_j) = peel((X_j u R_j) n U): the rings could be peeled inside the bound U, the
members outside U dropped without a solve. This counts the solves (all-violator peels,
CG converged to 1e-11) of the trial-ring rule against that look-ahead policy on the Fig. 1
wavy sphere, and checks every ring's result against the rule's.

    python3 scripts/lookahead_bound.py 64 75 2,4,8      # N, approach steps, layers k; ~1 min
    python3 scripts/lookahead_bound.py 128 75 4,8,16    # ~20 min

Needs numpy. A simplified replica of the rule (bans lifted on growth, restore after a ring
that fails completely, penetration attached with the ring), for counting, not for results.
"""
import sys

import numpy as np
from numpy.fft import irfft2, rfft2


def love(x, y, a, b):
    """u_z at (x, y) of a unit pressure on [-a, a] x [-b, b], times pi E* (Love 1929)."""

    def corner(X, Y):
        r = np.sqrt(X * X + Y * Y)
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = np.where(np.abs(X) > 0, X * np.log(np.where(Y + r > 0, Y + r, 1e-300)), 0.0)
            t2 = np.where(np.abs(Y) > 0, Y * np.log(np.where(X + r > 0, X + r, 1e-300)), 0.0)
        return t1 + t2

    return corner(x + a, y + b) - corner(x + a, y - b) - corner(x - a, y + b) + corner(x - a, y - b)


class HalfSpace:
    """The free half-space (E* = 1) by zero-padded FFT convolution."""

    def __init__(self, n, dx):
        self.n = n
        idx = np.arange(2 * n)
        idx = np.where(idx < n, idx, idx - 2 * n)
        i, j = np.meshgrid(idx, idx, indexing="ij")
        kernel = love(i * dx, j * dx, dx / 2, dx / 2) / np.pi
        kernel[np.abs(i) == n] = 0.0
        kernel[np.abs(j) == n] = 0.0
        self.spectrum = rfft2(kernel)

    def apply(self, p):
        n = self.n
        padded = np.zeros((2 * n, 2 * n))
        padded[:n, :n] = p
        return irfft2(rfft2(padded) * self.spectrum, s=(2 * n, 2 * n))[:n, :n]


def solve(space, target, contact, p0, tol=1e-11, maxit=2000):
    """K_CC p = target_C with p = 0 off C (CG); returns p and u = K p."""
    p = np.where(contact, p0, 0.0)
    u = space.apply(p)
    r = np.where(contact, target - u, 0.0)
    norm = np.sqrt(np.vdot(np.where(contact, target, 0), np.where(contact, target, 0))) + 1e-300
    d = r.copy()
    rr = np.vdot(r, r)
    for _ in range(maxit):
        if np.sqrt(rr) <= tol * norm:
            break
        z = space.apply(d)
        zc = np.where(contact, z, 0.0)
        step = rr / np.vdot(d, zc)
        p += step * d
        u += step * z
        r -= step * zc
        rr_new = np.vdot(r, r)
        d = r + (rr_new / rr) * d
        rr = rr_new
    return p, u


def neighbours(contact):
    out = np.zeros_like(contact)
    out[1:, :] |= contact[:-1, :]
    out[:-1, :] |= contact[1:, :]
    out[:, 1:] |= contact[:, :-1]
    out[:, :-1] |= contact[:, 1:]
    return out & ~contact


class Fig1:
    """The Fig. 1 wavy sphere on an n x n grid: R = E* = 1, L = 0.8, lambda = 0.05,
    h = 0.0025, gamma0 = 6.1685e-4, and its all-violator peel."""

    def __init__(self, n):
        size, gamma, wavelength, amplitude = 0.8, 6.16850275068085e-4, 0.05, 0.0025
        dx = size / n
        x = (np.arange(n) - n / 2 + 0.5) * dx
        xx, yy = np.meshgrid(x, x, indexing="ij")
        waves = amplitude * np.sin(2 * np.pi * xx / wavelength) * np.sin(2 * np.pi * yy / wavelength)
        self.z = (xx**2 + yy**2) / 2 + waves
        self.z -= self.z.min()
        self.critical = np.sqrt(gamma / (0.473201004409338 * dx))  # Pohrt & Popov's detachment stress
        self.d_jkr = (3 * np.pi**2 * gamma**2 / 64) ** (1 / 3)
        self.space = HalfSpace(n, dx)

    def peel(self, contact, depth, p):
        """The largest stable subset of `contact` (all violators per round): set, p, u, solves."""
        contact = contact.copy()
        solves = 0
        while True:
            p, u = solve(self.space, depth - self.z, contact, p)
            solves += 1
            violators = contact & (p < -self.critical)
            if not violators.any():
                return contact, p, u, solves
            contact &= ~violators
            p = np.where(violators, 0.0, p)


def main():
    n, approach_steps = int(sys.argv[1]), int(sys.argv[2])
    layers = [int(a) for a in sys.argv[3].split(",")]
    problem = Fig1(n)
    z, d_jkr, peel = problem.z, problem.d_jkr, problem.peel

    def reach(contact, k, banned):
        domain = contact.copy()
        for _ in range(k):
            domain |= neighbours(domain) & ~banned
        return domain

    rule_solves = ring_solves = rings = 0
    policy = {k: dict(solves=0, bound_solves=0, bounds=0, ring_solves=0, mismatches=0) for k in layers}
    contact = np.zeros(z.shape, bool)
    p = np.zeros(z.shape)
    for step in range(approach_steps):
        depth = 15 * d_jkr * (step + 1) / approach_steps
        if not contact.any():
            contact = (z - depth) < 0
            if not contact.any():
                continue
        banned = np.zeros_like(contact)
        high = contact.sum()
        contact, p, u, s = peel(contact, depth, p)
        rule_solves += s
        for k in layers:
            policy[k]["solves"] += s
        domains = {k: None for k in layers}
        while True:
            penetrating = ~contact & (z - depth + u < 0)
            ring = neighbours(contact) & ~banned & ~penetrating
            if not (penetrating.any() or ring.any()):
                break
            base = contact
            peeled, p_peeled, u_peeled, s = peel(base | ring | penetrating, depth, p)
            rule_solves += s
            ring_solves += s
            rings += 1
            for k in layers:
                entry = policy[k]
                if penetrating.any():
                    entry["solves"] += s
                    domains[k] = None
                    continue
                if domains[k] is None or not ((base | ring) <= domains[k][0]).all():
                    domain = reach(base, k, banned)
                    bound, _, _, s_bound = peel(domain, depth, p)
                    entry["solves"] += s_bound
                    entry["bound_solves"] += s_bound
                    entry["bounds"] += 1
                    domains[k] = (domain, bound)
                inside = (base | ring) & domains[k][1]
                if (inside == base).all():
                    result = base
                else:
                    result, _, _, s_inside = peel(inside, depth, p)
                    entry["solves"] += s_inside
                    entry["ring_solves"] += s_inside
                entry["mismatches"] += int(not (result == peeled).all())
            banned |= ring & ~peeled
            if (peeled == base).all():
                break
            contact, p, u = peeled, p_peeled, u_peeled
            if contact.sum() > high:
                high = contact.sum()
                banned[:] = False
    print(
        f"Fig. 1, N = {n}, {approach_steps} approach steps: {rings} rings; the rule: "
        f"{rule_solves / approach_steps:.2f} solves per step, {ring_solves / max(rings, 1):.2f} per ring"
    )
    for k in layers:
        e = policy[k]
        print(
            f"  look-ahead {k} layers: {e['solves'] / approach_steps:.2f} solves per step "
            f"({e['bounds']} bounds, {e['bound_solves']} solves for them), "
            f"{e['ring_solves'] / max(rings, 1):.2f} solves per ring inside the bound, "
            f"rings differing from the rule's: {e['mismatches']}"
        )


if __name__ == "__main__":
    main()
