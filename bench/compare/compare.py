#!/usr/bin/env python3
"""Side-by-side benchmark of adhesim against ASPHER, Tamaas and ContactMechanics.

    python3 bench/compare/compare.py [--threads 1] [--quick] [--repeats 3]

Creates bench/compare/.venv (git-ignored) and installs the peers pinned in
requirements.txt into it, builds adhesim's `compare_peers` example, runs the three
problems for every code one after another (each peer in its own process, with the same
thread count), and writes bench/compare/results.md and results.json. See README.md.
Runs with the system Python 3 (standard library only); the peers run in the venv.
"""

import argparse
import datetime
import hashlib
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
VENV = HERE / ".venv"
PYTHON = VENV / "bin" / "python"
REQUIREMENTS = HERE / "requirements.txt"
PEERS = ["aspher", "tamaas", "contactmechanics"]
# which requirement lines each peer needs (numpy/scipy are common)
PEER_PACKAGES = {"aspher": ["aspher"], "tamaas": ["tamaas"], "contactmechanics": ["ContactMechanics", "Adhesion"]}
ADHESIM_EXAMPLE = ROOT / "target" / "release" / "examples" / "compare_peers"


def log(*args):
    print(*args, file=sys.stderr, flush=True)


def load_average():
    try:
        return [float(x) for x in Path("/proc/loadavg").read_text().split()[:3]]
    except OSError:
        return list(os.getloadavg())


def machine_info():
    model = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC"),
        "nproc": os.cpu_count(),
        "cpu_model": model,
        "platform": platform.platform(),
        "python": sys.version.split()[0],
    }


def requirement_lines():
    lines = []
    for line in REQUIREMENTS.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            lines.append(line)
    return lines


def setup_venv():
    """Creates the venv and installs each peer separately; returns {peer: error or None}."""
    lines = requirement_lines()
    digest = hashlib.sha256(REQUIREMENTS.read_bytes()).hexdigest()[:16]
    marker = VENV / f".installed-{digest}.json"
    if marker.exists():
        return json.loads(marker.read_text())
    if not PYTHON.exists():
        log("creating", VENV)
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        subprocess.run([str(PYTHON), "-m", "pip", "install", "-q", "--upgrade", "pip"], check=False)
    common = [line for line in lines if not any(line.lower().startswith(p.lower()) for ps in PEER_PACKAGES.values()
                                                 for p in ps)]
    pip = [str(PYTHON), "-m", "pip", "install", "-q"]
    status = {}
    result = subprocess.run(pip + common, capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit("installing " + " ".join(common) + " failed:\n" + result.stderr[-3000:])
    for peer, packages in PEER_PACKAGES.items():
        wanted = [line for line in lines if any(line.lower().startswith(p.lower()) for p in packages)]
        log("installing", peer, ":", " ".join(wanted), "(builds from source: minutes)" if peer == "aspher" else "")
        env = dict(os.environ, CMAKE_BUILD_PARALLEL_LEVEL="2")
        result = subprocess.run(pip + wanted, capture_output=True, text=True, env=env)
        if result.returncode != 0:
            tail = result.stdout[-2000:] + result.stderr[-2000:]
            reason = "pip install failed"
            if peer == "aspher" and ("eigen" in tail.lower()):
                reason += (" (its sdist looks for Eigen 3.4 and otherwise downloads it at build time: install "
                           "the headers, e.g. apt-get install libeigen3-dev, and rerun)")
            status[peer] = reason
            log(reason, "\n", tail)
        else:
            status[peer] = None
    marker.write_text(json.dumps(status))
    return status


def thread_env(threads):
    env = dict(os.environ)
    for name in ("OMP_NUM_THREADS", "RAYON_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                 "NUMEXPR_NUM_THREADS", "VECLIB_MAXIMUM_THREADS", "TAMAAS_NUM_THREADS"):
        env[name] = str(threads)
    env["OMP_PROC_BIND"] = "false"
    return env


def build_adhesim():
    cargo = shutil.which("cargo")
    if cargo is None:
        raise SystemExit("cargo not found")
    log("building adhesim's compare_peers example (release)")
    subprocess.run([cargo, "build", "--release", "-p", "adhesim", "--example", "compare_peers"], cwd=ROOT,
                   check=True)


def run_json(command, env, timeout):
    start = time.perf_counter()
    try:
        result = subprocess.run(command, capture_output=True, text=True, env=env, timeout=timeout, cwd=HERE)
    except subprocess.TimeoutExpired:
        return {"error": f"killed after {timeout:.0f} s"}, time.perf_counter() - start
    elapsed = time.perf_counter() - start
    if result.returncode != 0:
        lines = [line for line in result.stderr.strip().splitlines() if line.strip()]
        return {"error": (lines[-1] if lines else f"exit {result.returncode}")[:300]}, elapsed
    try:
        return json.loads(result.stdout.strip().splitlines()[-1]), elapsed
    except (ValueError, IndexError):
        return {"error": "no JSON output: " + result.stdout[-300:]}, elapsed


def median(values):
    return statistics.median(values) if values else None


def fmt_time(seconds):
    if seconds is None:
        return "–"
    if seconds < 1e-3:
        return f"{seconds * 1e6:.0f} µs"
    if seconds < 1:
        return f"{seconds * 1e3:.1f} ms"
    return f"{seconds:.2f} s"


def fmt_ratio(ours, theirs):
    if ours is None or theirs is None or theirs <= 0:
        return "–"
    return f"{ours / theirs:.2f}"


def fmt_err(value):
    return "–" if value is None else f"{value:+.2e}"


def runs_note(entry, key, repeats):
    count = len(entry.get(key) or [])
    return "" if count >= repeats else f" ({count} run{'s' if count != 1 else ''})"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--threads", type=int, default=1, help="threads for every code (default 1)")
    parser.add_argument("--quick", action="store_true", help="N = 256 and 512 only")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per entry (median reported)")
    parser.add_argument("--budget", type=float, default=120.0,
                        help="seconds: a peer run over it is not repeated, and larger N of that peer are skipped")
    parser.add_argument("--adhesive-budget", type=float, default=300.0,
                        help="seconds (default 300): an adhesive cycle still running after it stops, reported as "
                        "unfinished")
    parser.add_argument("--peers", default=",".join(PEERS),
                        help="comma-separated subset of " + ",".join(PEERS) + " (with --update also adhesim)")
    parser.add_argument("--sizes", help="comma-separated N list (overrides --quick; for smoke tests)")
    parser.add_argument("--skip-adhesive", action="store_true", help="leave out problem (c)")
    parser.add_argument("--problems", default="hertz,operator,adhesive", help="subset of hertz,operator,adhesive")
    parser.add_argument("--update", metavar="JSON",
                        help="rerun --problems for --peers only and merge them into this results JSON")
    parser.add_argument("--render", metavar="JSON", help="only rewrite the markdown from a results JSON")
    parser.add_argument("--skip-build", action="store_true", help="use the existing release example binary")
    parser.add_argument("--output", default=str(HERE / "results"), help="path stem of the .md and .json results")
    args = parser.parse_args()
    sizes = [256, 512] if args.quick else [256, 512, 1024]
    if args.sizes:
        sizes = [int(n) for n in args.sizes.split(",")]
    peers = [p for p in args.peers.split(",") if p]
    if args.skip_adhesive:
        args.problems = ",".join(p for p in args.problems.split(",") if p != "adhesive")
    if args.render:
        results = json.loads(Path(args.render).read_text())
        args.repeats = results["machine"]["repeats"]
        report = render(results, results["sizes"], args)
        Path(args.render).with_suffix(".md").write_text(report)
        print(report)
        return

    problems = [p for p in args.problems.split(",") if p]
    if args.update:
        results = json.loads(Path(args.update).read_text())
        info = results["machine"]
        info.setdefault("updates", []).append({"date": machine_info()["date"], "peers": peers,
                                               "problems": problems, "load_before": load_average()})
        sizes = results["sizes"]
        args.threads, args.repeats = info["threads"], info["repeats"]
    else:
        info = machine_info()
        info["load_before"] = load_average()
        info["threads"] = args.threads
        info["repeats"] = args.repeats
        info["budget"] = args.budget
        info["adhesive_budget"] = args.adhesive_budget
        results = None
    log("machine:", info)
    install = setup_venv()
    if not args.skip_build and not args.update:
        build_adhesim()
    env = thread_env(args.threads)

    if results is None:
        results = {"machine": info, "install": install, "sizes": sizes, "adhesim": None, "peers": {}}
        log("running adhesim")
        skip = ["--skip-" + p for p in ("hertz", "operator", "adhesive") if p not in problems]
        adhesim, _ = run_json([str(ADHESIM_EXAMPLE), "--sizes", ",".join(map(str, sizes)), "--repeats",
                               str(args.repeats), "--tolerance", "1e-8"] + skip, env, timeout=3600)
        results["adhesim"] = adhesim

    if args.update and "adhesim" in peers:
        log("running adhesim")
        skip = ["--skip-" + p for p in ("hertz", "operator", "adhesive") if p not in problems]
        adhesim, _ = run_json([str(ADHESIM_EXAMPLE), "--sizes", ",".join(map(str, sizes)), "--repeats",
                               str(args.repeats), "--tolerance", "1e-8"] + skip, env, timeout=3600)
        if "error" in adhesim:
            log("adhesim failed:", adhesim["error"])
        else:
            # the problems rerun, and the settings they ran with
            results["adhesim"].update({k: v for k, v in adhesim.items()
                                       if k in problems or k in ("hertz_solver", "tolerance", "nested_tolerance",
                                                                 "threads")})
    for peer in [p for p in peers if p != "adhesim"]:
        entry = results["peers"].setdefault(peer, {"hertz": {}, "operator": {}, "adhesive": None})
        if install.get(peer):
            entry["error"] = install[peer]
            continue
        for problem in ("hertz", "operator"):
            if problem not in problems:
                continue
            too_slow = None
            for n in sizes:
                if too_slow:
                    entry[problem][str(n)] = {"skipped": too_slow}
                    continue
                log(f"running {peer} {problem} N={n}")
                command = [str(PYTHON), str(HERE / "peers.py"), peer, problem, "--n", str(n), "--repeats",
                           str(args.repeats), "--threads", str(args.threads), "--budget", str(args.budget)]
                out, elapsed = run_json(command, env, timeout=max(600.0, 6 * args.budget))
                entry[problem][str(n)] = out
                times = out.get("solve_s") or []
                if "error" in out or (times and max(times) > args.budget):
                    too_slow = (f"skipped: N={n} took over {args.budget:.0f} s per run" if "error" not in out
                                else f"skipped after the error at N={n}")
        if "adhesive" not in problems:
            continue
        log(f"running {peer} adhesive")
        command = [str(PYTHON), str(HERE / "peers.py"), peer, "adhesive", "--n", "128", "--repeats",
                   str(args.repeats), "--threads", str(args.threads), "--budget", str(args.budget), "--cap",
                   str(args.adhesive_budget)]
        out, _ = run_json(command, env, timeout=args.adhesive_budget + args.budget * args.repeats + 600)
        entry["adhesive"] = out

    if args.update:
        info["updates"][-1]["load_after"] = load_average()
        stem = Path(args.update).with_suffix("")
        stem.with_suffix(".json").write_text(json.dumps(results, indent=1) + "\n")
        report = render(results, sizes, args)
        stem.with_suffix(".md").write_text(report)
        print(report)
        return

    info["load_after"] = load_average()
    stem = Path(args.output)
    stem.with_suffix(".json").write_text(json.dumps(results, indent=1) + "\n")
    report = render(results, sizes, args)
    stem.with_suffix(".md").write_text(report)
    print(report)


def render(results, sizes, args):
    info = results["machine"]
    ours = results["adhesim"] or {}
    lines = [
        "# adhesim vs. peers (generated by bench/compare/compare.py)",
        "",
        f"- date: {info['date']}; machine: {info['nproc']} cores, {info['cpu_model']}; {info['platform']}",
        f"- load average (1/5/15 min): before {info['load_before']}, after {info['load_after']}",
        f"- threads per code: {info['threads']}; timed runs per entry: {info['repeats']} (median shown; fewer when "
        f"a run exceeded the budget of {info.get('budget', args.budget):.0f} s; an adhesive cycle is cut at "
        f"{info.get('adhesive_budget', args.adhesive_budget):.0f} s)",
        "- ratio = adhesim time / peer time (below 1: adhesim faster). Timings are wall-clock on a shared "
        "machine: read them with the load average above.",
    ]
    for update in info.get("updates", []):
        lines.append(f"- rerun of {', '.join(update['problems'])} for {', '.join(update['peers'])} at "
                     f"{update['date']}: load average before {update['load_before']}, after "
                     f"{update.get('load_after')}")
    lines.append("")
    if "error" in ours:
        lines += [f"**adhesim failed**: {ours['error']}", ""]
    versions = {peer: (entry.get("hertz", {}).get(str(sizes[0]), {}) or {}).get("versions")
                for peer, entry in results["peers"].items()}
    lines.append("Peers: " + "; ".join(
        (", ".join(f"{k} {v}" for k, v in versions[peer].items()) if versions[peer] else f"{peer} (not run)") + (f" — **{entry['error']}**" if entry.get("error") else "")
        for peer, entry in results["peers"].items()))
    lines.append("")

    # (a) Hertz
    lines += ["## (a) Hertz, free half-space, contact radius N/4 elements, cold start", "",
              "| N | code | setup | solve (median) | iterations | rel. force error vs Hertz | adhesim/peer (solve) |",
              "|---|---|---|---|---|---|---|"]
    our_hertz = {str(e["n"]): e for e in ours.get("hertz", [])}
    for n in sizes:
        mine = our_hertz.get(str(n), {})
        my_solve = median(mine.get("solve_s", []))
        solver = ("nested active set, residual 1e-10" if ours.get("hertz_solver") == "nested"
                  else f"Ccg, tol {ours.get('tolerance', 1e-8):g}")
        lines.append(f"| {n} | adhesim ({solver}) | {fmt_time(median(mine.get('setup_s', [])))} | "
                     f"{fmt_time(my_solve)} | {mine.get('iterations', '–')} | {fmt_err(mine.get('rel_force_error'))} "
                     f"| 1 |")
        for peer, entry in results["peers"].items():
            out = entry.get("hertz", {}).get(str(n))
            if entry.get("error"):
                lines.append(f"| {n} | {peer} | not installed | | | | |")
                continue
            if out is None:
                continue
            if "error" in out or "skipped" in out:
                lines.append(f"| {n} | {peer} | {out.get('error') or out.get('skipped')} | | | | |")
                continue
            solve = median(out.get("solve_s", []))
            iterations = out.get("iterations")
            label = f"{peer} ({out['mode']})" if out.get("mode") else peer
            lines.append(f"| {n} | {label} | {fmt_time(median(out.get('setup_s', [])))} | {fmt_time(solve)}"
                         f"{runs_note(out, 'solve_s', args.repeats)} | {iterations if iterations is not None else '–'}"
                         f" | {fmt_err(out.get('rel_force_error'))} | {fmt_ratio(my_solve, solve)} |")
    lines.append("")

    # (b) operator
    lines += ["## (b) One elastic operator application (pressure → displacement)", "",
              "| N | adhesim | " + " | ".join(f"{p} | adhesim/{p}" for p in results["peers"]) + " |",
              "|---|---|" + "---|---|" * len(results["peers"])]
    our_op = {str(e["n"]): e for e in ours.get("operator", [])}
    for n in sizes:
        mine = median(our_op.get(str(n), {}).get("apply_s", []))
        cells = [str(n), fmt_time(mine)]
        for peer, entry in results["peers"].items():
            out = entry.get("operator", {}).get(str(n)) or {}
            theirs = median(out.get("apply_s", []))
            if theirs is None:
                cells += [out.get("error") or out.get("skipped") or ("not installed" if entry.get("error") else "–"),
                          "–"]
            else:
                cells += [fmt_time(theirs), fmt_ratio(mine, theirs)]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")

    # (c) adhesive
    lines += ["## (c) Adhesive smooth sphere, load–unload cycle (R = 1, E* = 1, a_JKR = 32 elements)", "",
              "| code | adhesion model | grid | steps | wall (median) | F_pull-off / F_JKR | adhesim/peer (wall) |",
              "|---|---|---|---|---|---|---|"]
    mine = ours.get("adhesive") or {}
    my_wall = median(mine.get("wall_s", []))
    if mine:
        lines.append(f"| adhesim | JKR active set (Griffith criterion per element), rel. tol "
                     f"{mine.get('relative_tolerance', 0):g} | free {mine.get('n')}² | {mine.get('steps')} | "
                     f"{fmt_time(my_wall)} | {mine.get('pull_off_over_f_jkr', float('nan')):.4f} | 1 |")
    for peer, entry in results["peers"].items():
        out = entry.get("adhesive") or {}
        if entry.get("error"):
            lines.append(f"| {peer} | not installed | | | | | |")
        elif not out:
            lines.append(f"| {peer} | not run | | | | | |")
        elif out.get("unsupported"):
            lines.append(f"| {peer} | none offered in this version | | | | | |")
        elif "error" in out:
            lines.append(f"| {peer} | failed: {out['error']} | | | | | |")
        else:
            wall = median(out.get("wall_s", []))
            note = out.get("note")
            finished = not note
            ratio = fmt_ratio(my_wall, wall) if finished else "–"
            pull = f"{out['pull_off_over_f_jkr']:.4f}" if finished else "n/a (cycle not finished)"
            unconverged = out.get("unconverged_steps")
            if unconverged:
                note = (note + "; " if note else "") + f"{unconverged} step(s) not converged"
            lines.append(f"| {peer} | {out.get('model')}; Maugis λ ≈ {out.get('maugis_parameter', 0):.1f} | "
                         f"{out.get('grid')} | {out.get('steps')} | {fmt_time(wall)}"
                         f"{runs_note(out, 'wall_s', args.repeats)}{' — ' + note if note else ''} | {pull} | {ratio} |")
    lines += ["", "Notes per entry (tolerances, control, corrections) are in results.json and README.md.", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    main()
