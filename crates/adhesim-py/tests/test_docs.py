"""docs/python.md runs as written. CI runs every block of the page in a fresh venv with
tests/doc_page.py (.ci/run); here: that the page's blocks are all runnable or say why not,
that the runner compares, substitutes and fails as it should, and the Fig. 1b walk-through
at a small grid in this suite's environment."""

import os
import re
from pathlib import Path

import pytest

import adhesim
import doc_page  # tests/doc_page.py, beside this file

REPO = Path(__file__).resolve().parents[3]
PAGE = REPO / "docs" / "python.md"
HEADING = "## Walk-through 1: the paper's Fig. 1b from `adhesim.run`"


def walkthrough_code():
    text = PAGE.read_text()
    after = text[: text.index(HEADING)].count("\n") + 1
    return next(b for b in doc_page.blocks(text) if b.line > after and b.lang == "python").code


def test_every_block_of_the_page_runs_or_says_why_not():
    blocks = doc_page.blocks(PAGE.read_text())
    assert [b.lang for b in blocks[:2]] == ["sh", "python"], "the install block comes first"
    assert "pip install \"./crates/adhesim-py[extras]\"" in blocks[0].code
    not_run = {b.line: b.not_run_reason for b in blocks if b.not_run_reason is not None}
    assert list(not_run.values()) == ["it needs a SLURM cluster (and `pip install dask-jobqueue`)"]
    assert sum(b.expected_output is not None for b in blocks) >= 2
    assert len(blocks) - len(not_run) >= 7


def test_blocks_are_dedented_and_take_their_expected_output():
    page = "intro\n\n- item\n\n  ```python\n  print(1)\n  ```\n\n  ```text\n  1\n  ```\n\n```sh\n# not run in CI: needs a cluster\nsbatch x\n```\n"
    first, second = doc_page.blocks(page)
    assert (first.line, first.lang, first.code, first.expected_output) == (5, "python", "print(1)\n", "1\n")
    assert second.not_run_reason == "needs a cluster"


@pytest.mark.parametrize(
    "page, error",
    [
        ("```toml\na = 1\n```\n", "cannot be run"),
        ("```text\n1\n```\n", "must follow a code block"),
        ("```sh\necho\n", "not closed"),
    ],
)
def test_a_block_that_cannot_run_is_an_error_not_a_skip(page, error):
    with pytest.raises(ValueError, match=error):
        doc_page.blocks(page)


def test_the_wheel_replaces_the_source_folder_in_pip_installs_only():
    code = 'pip install "./crates/adhesim-py[extras]"\nls ./crates/adhesim-py\n'
    assert doc_page.with_wheel(code, Path("/w/a.whl")) == 'pip install "/w/a.whl[extras]"\nls ./crates/adhesim-py\n'
    assert doc_page.with_wheel(code, None) == code


def test_the_runner_compares_the_output_and_fails_on_a_failing_block(tmp_path, capsys):
    page = tmp_path / "page.md"
    work = tmp_path / "work"
    page.write_text("```sh\necho hello > note\ncat note\nls -d scenarios\n```\n\n```text\nhello\nscenarios\n```\n")
    assert doc_page.main([str(page), "--work", str(work)]) == 0
    assert (work / "note").read_text() == "hello\n" and not (REPO / "note").exists()
    page.write_text("```sh\necho other\n```\n\n```text\nhello\n```\n")
    with pytest.raises(RuntimeError, match="printed\nother\nwhere the page shows\nhello"):
        doc_page.main([str(page), "--work", str(work)])
    page.write_text("```sh\nfalse\necho unreachable\n```\n")
    with pytest.raises(RuntimeError, match="page.md:1: the sh block exited with status 1"):
        doc_page.main([str(page), "--work", str(work)])
    page.write_text("```python\nprint(1)\n```\n")
    with pytest.raises(RuntimeError, match="no .venv yet"):
        doc_page.main([str(page), "--work", str(work)])


def test_fig1b_walkthrough_runs(tmp_path, monkeypatch, capsys):
    """Executes the doc's code with every `adhesim.run` at n = 32 and 40 approach steps
    (the figure's code is unchanged; CI's tests/doc_page.py runs it at n = 128), in a
    temporary folder, with the scenario path resolved against the repository root. The
    figure file must appear and the printed ratios must be numbers."""
    pytest.importorskip("matplotlib")
    real_run = adhesim.run

    def small_run(scenario, *args, **kwargs):
        if isinstance(scenario, str) and not os.path.isabs(scenario):
            scenario = str(REPO / scenario)
        kwargs.setdefault("overrides", {}).update({"grid.n": 32, "protocol.steps": 40})
        return real_run(scenario, *args, **kwargs)

    monkeypatch.setattr(adhesim, "run", small_run)
    monkeypatch.chdir(tmp_path)
    exec(compile(walkthrough_code(), "docs/python.md (Fig. 1b)", "exec"), {})
    assert (tmp_path / "fig1b.png").stat().st_size > 10_000
    printed = capsys.readouterr().out
    assert re.search(r"γ1/γ0 = \d\.\d{3}, γ2/γ0 = \d\.\d{3}", printed), printed
