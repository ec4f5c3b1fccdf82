#!/usr/bin/env python3
"""Premise check of the one-shot upper bound on tension rises (docs/fast-step.md section 5).

Releasing the outer layer P of a disc contact C (a unit tension on each of its elements)
raises the tensions on C' = C minus P by q' = S_C' K_C'P 1 (S = K^-1, K the Love influence
matrix of square elements, Love 1929). Restricting the equations to C'' = C' within a disc
of radius Rw around element i (everything outside it free) gives an upper bound on q'_i
(docs/fast-step.md section 5). The bound could certify a predicted subset stable without its
verification solve only if it exceeds the exact rise by less than the margins sigma_c - t of
the new front. This prints, for contact radii a (in elements) and window radii Rw, the exact
rise on the new front and the bound's excess over it, in units of the released tension.

    python3 scripts/one_shot_bound.py 20 30 40     # needs numpy; a = 40 takes ~15 s

With --margins DIR it reads the fields of a run (`adhesim run scenarios/fig1.toml --set
output.snapshot_every=4 --out DIR`) and prints, per snapshot step, the largest tension of
the front (contact elements with a free edge neighbour) over sigma_c and the fraction of
the front above 0.85 sigma_c: the margins the bound would have to fit in.

    python3 scripts/one_shot_bound.py --margins DIR
"""
import json
import sys

import numpy as np


def love(x, y, half=0.5):
    """Displacement at (x, y) of a unit pressure on the square [-half, half]^2, times pi E*."""

    def primitive(a, b):
        r = np.hypot(a, b)
        return a * np.log(b + r) + b * np.log(a + r)

    return (
        primitive(x + half, y + half)
        - primitive(x + half, y - half)
        - primitive(x - half, y + half)
        + primitive(x - half, y - half)
    )


def influence(targets, sources):
    d = targets[:, None, :] - sources[None, :, :]
    return love(d[..., 0], d[..., 1])


def check(radius):
    n = int(2 * radius + 8)
    rows, columns = np.mgrid[0:n, 0:n]
    centre = (n - 1) / 2
    distance = np.hypot(rows - centre, columns - centre)
    contact = distance < radius
    released = contact & (distance >= radius - 1)
    kept = contact & ~released
    points = lambda mask: np.stack([rows[mask], columns[mask]], 1).astype(float)
    kept_points, released_points = points(kept), points(released)
    k_kept = influence(kept_points, kept_points)
    load = influence(kept_points, released_points).sum(1)
    exact = np.linalg.solve(k_kept, load)
    kept_distance = np.hypot(*(kept_points - centre).T)
    front = np.where(kept_distance >= radius - 2)[0]
    print(
        f"a = {radius:g}: |C'| = {len(kept_points)}, |P| = {len(released_points)}; exact rise on the"
        f" new front: mean {exact[front].mean():.3f}, max {exact[front].max():.3f}"
    )
    for window_radius in (4, 8, 12, 16, 24):
        pairs, sizes = [], []
        for i in front[::7]:
            window = np.where(np.hypot(*(kept_points - kept_points[i]).T) <= window_radius)[0]
            bound = np.linalg.solve(k_kept[np.ix_(window, window)], load[window])
            pairs.append((bound[np.searchsorted(window, i)], exact[i]))
            sizes.append(len(window))
        bound, truth = np.array(pairs).T
        print(
            f"  Rw = {window_radius:2d}: {np.mean(sizes):.0f} unknowns per window;"
            f" bound/exact mean {np.mean(bound / truth):.3f};"
            f" bound - exact mean {np.mean(bound - truth):.3f}, max {np.max(bound - truth):.3f}"
        )


def margins(folder):
    fields = np.load(f"{folder}/fields.npz")
    critical_stress = json.load(open(f"{folder}/summary.json"))["derived"]["critical_stress"]
    for step, depth in zip(fields["steps"], fields["depths"]):
        contact = fields[f"contact_{int(step):06d}"]
        if contact.sum() < 50:
            continue
        free = ~contact
        front = contact & (
            np.roll(free, 1, 0) | np.roll(free, -1, 0) | np.roll(free, 1, 1) | np.roll(free, -1, 1)
        )
        tension = -fields[f"pressure_{int(step):06d}"][front] / critical_stress
        print(
            f"step {int(step):4d} depth {depth:.4g}: {int(contact.sum())} in contact, front {int(front.sum())},"
            f" largest tension {tension.max():.3f} sigma_c, above 0.85 sigma_c: {(tension > 0.85).mean():.2f}"
        )


if __name__ == "__main__":
    if sys.argv[1:2] == ["--margins"]:
        margins(sys.argv[2])
    else:
        for argument in sys.argv[1:] or ["20", "30"]:
            check(float(argument))
