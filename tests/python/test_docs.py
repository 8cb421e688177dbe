"""docs/python.md stays true: its ```python blocks run, in order, in one
namespace, from the repository's root (as the page says)."""

import contextlib
import re

from common import ROOT


def python_blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def test_the_python_chapter_runs(capsys):
    page = (ROOT / "docs" / "python.md").read_text()
    blocks = python_blocks(page)
    assert len(blocks) >= 5, "the chapter's examples were found"
    with contextlib.chdir(ROOT):
        namespace = {"__name__": "docs_python"}
        for i, block in enumerate(blocks):
            code = compile(block, f"docs/python.md, block {i + 1}", "exec")
            exec(code, namespace)
    printed = capsys.readouterr().out
    assert "checks passed" in printed and "astar:" in printed
