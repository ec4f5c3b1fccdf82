#!/usr/bin/env python3
"""Premise check of sub-ring growth (docs/fast-step.md section 5). After a ring that grew the contact, the next ring tries
only the free neighbours near the elements just attached (the zipper's front); a full ring
is tried only when such a sub-ring fails completely, and the step ends only when a full ring
fails completely. By monotonicity of peel every sub-ring result is a subset of the least
fixed point, and the end is a fixed point: the same contact set as the trial-ring rule.

    python3 scripts/subring_growth.py 64 75 2      # N, approach steps, reach of a sub-ring; ~1 min
    python3 scripts/subring_growth.py 128 75 1     # ~5 min

Needs numpy; the solver and rule replica of scripts/lookahead_bound.py."""
import sys
import numpy as np
from lookahead_bound import Fig1, neighbours

n, approach_steps, reach = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
problem = Fig1(n)
z, d_jkr, peel = problem.z, problem.d_jkr, problem.peel

def dilate(mask, r):
    out = mask.copy()
    for _ in range(r):
        grown = out.copy()
        grown[1:, :] |= out[:-1, :]; grown[:-1, :] |= out[1:, :]
        grown[:, 1:] |= out[:, :-1]; grown[:, :-1] |= out[:, 1:]
        out = grown
    return out

def step(contact, p, depth, subrings):
    """One approach step of the rule (subrings False) or the sub-ring policy."""
    solves = rings = 0
    contact, p, u, s = peel(contact, depth, p); solves += s
    banned = np.zeros_like(contact); high = contact.sum(); recent = None
    while True:
        pen = ~contact & (z - depth + u < 0)
        full = neighbours(contact) & ~banned & ~pen
        sub = subrings and recent is not None
        ring = full & dilate(recent, reach) if sub else full
        if sub and not (ring.any() or pen.any()):
            recent = None
            continue
        if not (ring.any() or pen.any()):
            break
        peeled, pp, uu, s = peel(contact | ring | pen, depth, p); solves += s; rings += 1
        if (peeled == contact).all():
            if sub:
                recent = None          # the zipper stopped: try the full ring, nothing banned
                continue
            break                      # a full ring failed completely: the fixed point
        if not sub:
            banned |= ring & ~peeled
        recent = peeled & ~contact
        contact, p, u = peeled, pp, uu
        if contact.sum() > high:
            high = contact.sum(); banned[:] = False
    return contact, p, solves, rings

rule = dict(solves=0, rings=0); policy = dict(solves=0, rings=0); differing = 0
contact = np.zeros(z.shape, bool); p = np.zeros(z.shape)
for i in range(approach_steps):
    depth = 15 * d_jkr * (i + 1) / approach_steps
    if not contact.any():
        contact = (z - depth) < 0
        if not contact.any():
            continue
    c1, p1, s1, r1 = step(contact, p, depth, False)
    c2, _, s2, r2 = step(contact, p, depth, True)
    rule['solves'] += s1; rule['rings'] += r1; policy['solves'] += s2; policy['rings'] += r2
    differing += int(not (c1 == c2).all())
    contact, p = c1, p1
print(f"Fig. 1, N = {n}, {approach_steps} approach steps, reach {reach}: the rule {rule['solves']/approach_steps:.2f} solves/step, {rule['rings']/approach_steps:.2f} rings/step; sub-rings {policy['solves']/approach_steps:.2f} solves/step, {policy['rings']/approach_steps:.2f} rings/step; steps with another contact set: {differing}")
