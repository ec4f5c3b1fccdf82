#!/usr/bin/env python3
"""Crates that `cargo test --release` and the Python wheel's build give different features.

Each such crate, and every crate above it, is compiled twice in CI (ARCHITECTURE.md, "One
build for the tests and the wheel"). Prints one line per crate and exits 1 if there is any.

    python3 scripts/feature_drift.py
"""
import subprocess
import sys


def features(*args: str) -> dict[str, set[str]]:
    """Each package of `cargo tree ARGS` with the feature sets it is built with."""
    out = subprocess.run(
        ["cargo", "tree", "--prefix", "none", "-f", "{p}|{f}", *args],
        capture_output=True, text=True, check=True,
    ).stdout
    table: dict[str, set[str]] = {}
    for line in out.splitlines():
        if "|" in line:
            package, names = line.split("|", 1)
            table.setdefault(package.split(" (")[0], set()).add(names.replace(" (*)", ""))
    return table


wheel = features("-p", "adhesim-py", "-e", "normal,build")
tests = features("-e", "normal,build,dev")
drift = [p for p in sorted(wheel.keys() & tests.keys()) if wheel[p] != tests[p]]
for package in drift:
    print(f"{package}: wheel {sorted(wheel[package])}, tests {sorted(tests[package])}")
sys.exit(1 if drift else 0)
