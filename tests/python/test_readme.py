"""The README's section "CSF from Python": its example, run as a doctest from the top of the tree."""
import doctest
import os

import pytest

from conftest import TOP


def test_readme_example(monkeypatch):
    pytest.importorskip("pandas")
    text = open(os.path.join(TOP, "README.md")).read()
    section = text[text.index("## CSF from Python"):]
    block = section[section.index("```pycon\n") + 9:]
    block = block[:block.index("```\n")]
    monkeypatch.chdir(TOP)
    test = doctest.DocTestParser().get_doctest(block, {}, "README.md", "README.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0 and runner.tries >= 10
