"""The cache key: what invalidates a cached solve and what does not."""

import shutil

import pytest

from lunarcap.repro import cache


@pytest.fixture
def package_copy(tmp_path, monkeypatch):
    src = cache._PACKAGE_DIR
    dst = tmp_path / "lunarcap"
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(cache, "_PACKAGE_DIR", dst)
    cache.code_version.cache_clear()
    yield dst
    cache.code_version.cache_clear()


def _key():
    cache.code_version.cache_clear()
    return cache.code_version()


@pytest.mark.parametrize("path,expect_change", [
    ("cli/__init__.py", False),                          # help text of the CLI
    ("report/figures/__init__.py", False),      # a figure
    ("studies/engine_trade/trade.py", False),                   # the trade study's bookkeeping
    ("optim/transcription.py", True),           # the NLP
    ("physics/dynamics.py", True),              # the equations of motion
    ("mission/plans/song2011-150N.yaml", False),  # a plan file: its content keys its solves
    ("capture/chain.py", True),                    # the cached chain solves
])
def test_only_numerical_code_changes_the_key(package_copy, path, expect_change):
    before = _key()
    f = package_copy / path
    f.write_text(f.read_text() + "\n# edited\n")
    assert (_key() != before) == expect_change


def test_presentation_changes_the_book_stamp(package_copy):
    cache.code_version.cache_clear()
    before = cache.code_version(include_presentation=True)
    f = package_copy / "report" / "figures" / "__init__.py"
    f.write_text(f.read_text() + "\n# edited\n")
    cache.code_version.cache_clear()
    assert cache.code_version(include_presentation=True) != before
