#!/usr/bin/env python3
"""Runs every code block of a documentation page (docs/python.md) as the page shows it, in
order, from a fresh folder that stands in for the repository root, so the page and its test
cannot drift apart.

- ``sh`` blocks run in bash (``-e -o pipefail``), as one shell would: once a block
  has created ``.venv`` (the page's install block does, and activates it), the later blocks
  run with it activated.
- ``python`` blocks run one by one as scripts (``python block.py``) with that venv's
  interpreter, so each block holds its own imports.
- A ``text`` block right after a code block is that block's expected standard output,
  compared line by line.
- A block whose first line is ``# not run in CI: REASON`` is not run, and the reason is
  printed; the reason is visible on the page. Any other language is an error, so no block
  is left out silently.

The venv holds only what the page installs. With ``--wheel W``, a page's ``pip install``
of ``./crates/adhesim-py`` installs the wheel W instead: the same package, which pip would
otherwise build from that folder with maturin (docs/python.md says so).

Standard library only: it runs with the system's python3 before any venv exists.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import List, Optional

REPO = Path(__file__).resolve().parents[3]
NOT_RUN = re.compile(r"^#\s*not run in CI:\s*(?P<reason>\S.*)$")
FENCE = re.compile(r"^(?P<indent> *)```(?P<lang>[\w-]*)\s*$")
LANGUAGES = ("sh", "python")
# Repository entries the blocks must not reach through the stand-in root: build outputs,
# run outputs (the page writes `out/...`) and the page's own venv.
NOT_LINKED = {"target", "out", ".venv", ".git"}


@dataclass
class Block:
    """A fenced code block of the page."""

    line: int  # of the opening fence, 1-based
    lang: str
    code: str
    expected_output: Optional[str] = None

    @property
    def not_run_reason(self) -> Optional[str]:
        """The reason on its ``# not run in CI: REASON`` first line, or None."""
        first = self.code.split("\n", 1)[0]
        match = NOT_RUN.match(first.strip())
        return match.group("reason") if match else None


def blocks(text: str) -> List[Block]:
    """The page's fenced blocks, dedented (a block inside a list item is indented), each
    ``text`` block attached to the code block before it as its expected output."""
    found: List[Block] = []
    lines = text.split("\n")
    index = 0
    while index < len(lines):
        opening = FENCE.match(lines[index])
        if not opening:
            index += 1
            continue
        indent, start = opening.group("indent"), index
        body: List[str] = []
        index += 1
        while index < len(lines) and lines[index].rstrip() != indent + "```":
            if lines[index].strip() and not lines[index].startswith(indent):
                raise ValueError(f"line {index + 1}: a line of the block at line {start + 1} is less indented than its fence")
            body.append(lines[index][len(indent) :])
            index += 1
        if index == len(lines):
            raise ValueError(f"line {start + 1}: the block is not closed")
        index += 1
        block = Block(start + 1, opening.group("lang"), "\n".join(body) + "\n")
        if block.lang == "text":
            if not found or found[-1].lang not in LANGUAGES or found[-1].expected_output is not None:
                raise ValueError(f"line {block.line}: a text block (expected output) must follow a code block")
            found[-1].expected_output = block.code
            continue
        if block.lang not in LANGUAGES and block.not_run_reason is None:
            raise ValueError(
                f"line {block.line}: a ```{block.lang} block cannot be run; run blocks are {LANGUAGES}, "
                "others need a first line `# not run in CI: REASON`"
            )
        found.append(block)
    return found


def with_wheel(code: str, wheel: Optional[Path]) -> str:
    """``code`` with its ``pip install``s of ``./crates/adhesim-py`` (extras kept) taking
    ``wheel`` instead, if given."""
    if wheel is None:
        return code
    return "\n".join(
        line.replace("./crates/adhesim-py", str(wheel)) if line.lstrip().startswith("pip install") else line
        for line in code.split("\n")
    )


def clean_environment() -> dict:
    """This process's environment without any active venv (CI runs inside one) or the
    test suite's variables, so that only the page's own venv is seen."""
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "PYTHONPATH", "PYTHONHOME", "ADHESIM_BIN")}
    kept = [p for p in env.get("PATH", "").split(os.pathsep) if p and not (Path(p).parent / "pyvenv.cfg").exists()]
    env["PATH"] = os.pathsep.join(kept)
    return env


def stand_in_root(work: Path) -> None:
    """``work`` as a fresh repository root: the repository's entries linked in, nothing else."""
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    for entry in REPO.iterdir():
        if entry.name not in NOT_LINKED:
            (work / entry.name).symlink_to(entry)


def run_block(block: Block, work: Path, page: str, wheel: Optional[Path], env: dict, timeout: float) -> str:
    """Runs one block in ``work`` and gives its standard output; raises on failure."""
    venv = work / ".venv"
    if block.lang == "sh":
        activate = ". .venv/bin/activate\n" if (venv / "bin" / "activate").exists() else ""
        command = ["bash", "-e", "-o", "pipefail", "-c", activate + with_wheel(block.code, wheel)]
    else:
        if not (venv / "bin" / "python").exists():
            raise RuntimeError(f"{page}:{block.line}: no .venv yet (the page's install block must come first)")
        script = work.parent / f"{work.name}-blocks" / f"line{block.line}.py"
        script.parent.mkdir(exist_ok=True)
        script.write_text(block.code)
        command = [str(venv / "bin" / "python"), str(script)]
        env = dict(env, VIRTUAL_ENV=str(venv), PATH=f"{venv / 'bin'}{os.pathsep}{env['PATH']}")
    done = subprocess.run(command, cwd=work, env=env, stdout=subprocess.PIPE, timeout=timeout, text=True)
    sys.stdout.write(done.stdout)
    if done.returncode != 0:
        raise RuntimeError(f"{page}:{block.line}: the {block.lang} block exited with status {done.returncode}")
    return done.stdout


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("page", type=Path, help="the markdown page, e.g. docs/python.md")
    parser.add_argument("--work", type=Path, required=True, help="folder made afresh as the stand-in root")
    parser.add_argument("--wheel", type=Path, help="the adhesim wheel that `pip install ./crates/adhesim-py` builds")
    parser.add_argument("--timeout", type=float, default=600, help="seconds per block")
    args = parser.parse_args(argv)
    page = args.page.resolve()
    name = str(page.relative_to(REPO)) if page.is_relative_to(REPO) else str(page)
    work = args.work.resolve()
    wheel = args.wheel.resolve() if args.wheel else None
    stand_in_root(work)
    shutil.rmtree(work.parent / f"{work.name}-blocks", ignore_errors=True)
    env = clean_environment()
    ran, not_run = 0, 0
    for block in blocks(page.read_text()):
        reason = block.not_run_reason
        if reason is not None:
            print(f"== {name}:{block.line} ({block.lang}): not run: {reason}", flush=True)
            not_run += 1
            continue
        print(f"== {name}:{block.line} ({block.lang})", flush=True)
        output = run_block(block, work, name, wheel, env, args.timeout)
        if block.expected_output is not None and output.rstrip().split("\n") != block.expected_output.rstrip().split("\n"):
            raise RuntimeError(
                f"{name}:{block.line}: printed\n{output.rstrip()}\nwhere the page shows\n{block.expected_output.rstrip()}"
            )
        ran += 1
    if ran == 0:
        raise RuntimeError(f"{name}: no block ran")
    print(f"== {name}: {ran} blocks ran as written, {not_run} not run (reasons above)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
