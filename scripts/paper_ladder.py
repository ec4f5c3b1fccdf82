#!/usr/bin/env python3
"""The resolution ladder of docs/paper.md, from the committed sweep tables.

Reads docs/data/paper/ladder_256.csv (8 elements per wavelength), fig3_amplitude_512.csv
(16) and, where present, ladder_1024.csv (32): the `table.csv` files of
`adhesim sweep sweeps/ladder_256.toml`, `adhesim sweep sweeps/fig3_amplitude_512.toml` and
`adhesim sweep sweeps/ladder_1024.toml`. For every alpha of the ladder and every quantity
(gamma1, gamma2 with both radius definitions, F_ad, the mean (gamma1 + gamma2)/2) it prints
the values per rung and an extrapolation to zero element size:
- with three rungs, the observed order p = log2((X8 - X16)/(X16 - X32)) and
  X0 = X32 + (X32 - X16)/(2^p - 1) (Richardson), where the differences keep their sign
  and shrink (0.5 < p < 4); else, where 16 -> 32 moves by at most 5 %, X32 with that
  change as its uncertainty, marked "no order"; else "no order";
- with two rungs, the first-order estimate X0 = 2 X16 - X8, marked "(1st order)", where
  the two differ by at most 10 % ("moves > 10 %" and no estimate otherwise: such a change
  is not the first-order tail): the smooth sphere's adhesive force converges at first
  order in the element size (docs/physics.md section 4), an assumption the third rung
  tests.

    python3 scripts/paper_ladder.py                   # print the tables (standard library only)
    python3 scripts/paper_ladder.py --update docs/paper.md   # replace the ladder block there
"""

import csv
import math
import os
import sys

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "data", "paper")
RUNGS = [("ladder_256.csv", 8), ("fig3_amplitude_512.csv", 16), ("ladder_1024.csv", 32)]
LADDER_ALPHAS = [0.4, 0.5, 0.6, 0.7, 1.0, 2.0, 4.0]
QUANTITIES = [
    ("γ1/γ0 (farthest)", lambda r: num(r, "gamma_approach_norm")),
    ("γ2/γ0 (farthest)", lambda r: num(r, "gamma_pulloff_norm")),
    ("γ1/γ0 (√(A/π))", lambda r: num(r, "gamma_approach_area_norm")),
    ("γ2/γ0 (√(A/π))", lambda r: num(r, "gamma_pulloff_area_norm")),
    ("\\|F_ad\\|/\\|F_JKR\\|", lambda r: num(r, "adhesive_force_ratio")),
    ("(γ1+γ2)/(2γ0) (farthest)", lambda r: mean(num(r, "gamma_approach_norm"), num(r, "gamma_pulloff_norm"))),
    ("(γ1+γ2)/(2γ0) (√(A/π))", lambda r: mean(num(r, "gamma_approach_area_norm"), num(r, "gamma_pulloff_area_norm"))),
]


def num(row, key):
    try:
        value = float(row.get(key, ""))
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def mean(a, b):
    return None if a is None or b is None else 0.5 * (a + b)


def read(name):
    path = os.path.join(DATA, name)
    if not os.path.exists(path):
        return {}
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r.get("status") == "ok"]
    return {round(float(r["alpha"]), 6): r for r in rows}


def extrapolate(values):
    """Zero-element-size estimate and how it was made, from the rungs' values (8, 16, 32)."""
    x8, x16, x32 = (values + [None, None, None])[:3]
    if x8 is not None and x16 is not None and x32 is not None:
        d1, d2 = x8 - x16, x16 - x32
        if d1 != 0 and d2 != 0 and (d1 > 0) == (d2 > 0) and abs(d2) < abs(d1):
            order = math.log2(d1 / d2)
            if 0.5 < order < 4:
                return x32 + (x32 - x16) / (2**order - 1), f"p = {order:.2f}"
        # Rungs 8 -> 16 outside the asymptotic range (the transition's mesh effect), yet
        # 16 -> 32 within 5 %: the 32 rung, with that change as its uncertainty.
        if abs(d2) <= 0.05 * abs(x32):
            return x32, f"± {abs(d2):.3f} (16 → 32: {100 * abs(d2 / x32):.1f} %; no order)"
        return None, "no order"
    if x8 is not None and x16 is not None:
        # A change of more than 10 % between the rungs is no first-order tail: no estimate.
        if abs(x16 - x8) > 0.1 * abs(x16):
            return None, "moves > 10 %"
        return 2 * x16 - x8, "(1st order)"
    return None, ""


def fmt(value):
    return "" if value is None else f"{value:.3f}"


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--update":
        return update(sys.argv[2])
    print_tables()
    return 0


def update(path):
    """Replaces the text between the ladder markers of `path` with the tables."""
    import contextlib
    import io

    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        print_tables()
    with open(path) as f:
        text = f.read()
    begin = "<!-- ladder: the output of `python3 scripts/paper_ladder.py` -->"
    end = "<!-- end of ladder -->"
    if begin not in text or end not in text:
        print(f"{path}: no ladder markers", file=sys.stderr)
        return 1
    head, rest = text.split(begin, 1)
    _, tail = rest.split(end, 1)
    with open(path, "w") as f:
        f.write(head + begin + "\n\n" + buffer.getvalue().rstrip() + "\n\n" + end + tail)
    return 0


def print_tables():
    tables = [(read(name), per_lambda) for name, per_lambda in RUNGS]
    alphas = [a for a in LADDER_ALPHAS if any(round(a, 6) in table for table, _ in tables)]
    for label, quantity in QUANTITIES:
        print(f"**{label}**\n")
        print("| elements per λ | " + " | ".join(f"α = {a:g}" for a in alphas) + " |")
        print("|---|" + "---|" * len(alphas))
        columns = []
        for alpha in alphas:
            values = [quantity(t[round(alpha, 6)]) if round(alpha, 6) in t else None for t, _ in tables]
            columns.append((values, extrapolate(values)))
        for rung, (table, per_lambda) in enumerate(tables):
            if table:
                print(f"| {per_lambda} | " + " | ".join(fmt(v[rung]) for v, _ in columns) + " |")
        cells = [f"{fmt(e)} {how}".strip() for _, (e, how) in columns]
        print("| Δ → 0 | " + " | ".join(cells) + " |\n")


if __name__ == "__main__":
    sys.exit(main())
