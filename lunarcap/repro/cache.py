"""Disk cache of expensive results, keyed by the code that produced them.

:func:`get_memory` is a :class:`joblib.Memory` at ``.cache/joblib`` (see
:mod:`lunarcap.repro.paths`).
:func:`cached` wraps a function with it and adds two extra key parts:

* :func:`code_version`, a SHA-256 of the lunarcap source files that compute results
  (:data:`NUMERICAL_CODE`: physics, mission, optim, the chain), so any edit of the physics,
  the transcription or the solver invalidates the cache, and an edit of the CLI or the
  book does not;
* a hash of the wrapped function's own source, for functions defined outside lunarcap
  (in a notebook or a test).

Arguments are bound to the function's signature with defaults applied before hashing,
so ``f(1, b=2)`` and ``f(1, 2)`` share one entry.

Set ``LUNARCAP_NO_CACHE=1`` to compute everything afresh (nothing is read or written).

Examples
--------
>>> from lunarcap.repro.cache import cached
>>> @cached
... def slow_square(x, verbose=False):
...     return x * x
>>> slow_square(3)
9
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import os
from collections import OrderedDict
from pathlib import Path

from lunarcap.repro import paths

#: What a cached result depends on: the numerical code (physics, the mission, the
#: optimiser), the error types, and the module of the cached chain solves. Editing anything
#: else (the CLI's help, the book, a figure, a plan file: a plan's content is part of the
#: key of each of its solves) keeps every cached solve.
NUMERICAL_CODE = ("physics/", "mission/", "optim/", "errors.py", "runs/chain.py")

#: Besides those, the book's stamps hash the presentation code (a figure depends on it).
PRESENTATION_CODE = ("report/", "paper/", "runs/", "cli.py")

_PACKAGE_DIR = Path(__file__).resolve().parents[1]


def _enabled() -> bool:
    return os.environ.get("LUNARCAP_NO_CACHE", "").strip().lower() in ("", "0", "false", "no")


#: The joblib store, created on first use (joblib is imported only then): a process that
#: caches nothing (``LUNARCAP_NO_CACHE=1``, ``--no-cache``) does not pay for it.
memory = None


def get_memory():
    """The joblib Memory at :data:`lunarcap.repro.paths.JOBLIB_CACHE` (created once)."""
    global memory
    if memory is None:
        import joblib

        memory = joblib.Memory(location=str(paths.JOBLIB_CACHE), verbose=0)
    return memory


def location() -> str | None:
    """Where results are cached, or None when caching is off (``LUNARCAP_NO_CACHE``)."""
    return str(paths.JOBLIB_CACHE) if _enabled() else None


def _selected(rel: str, prefixes) -> bool:
    return any(rel == p or (p.endswith("/") and rel.startswith(p)) for p in prefixes)


@functools.lru_cache(maxsize=None)
def code_version(include_presentation: bool = False) -> str:
    """SHA-256 (hex, 16 characters) of the lunarcap source a result depends on.

    Parameters
    ----------
    include_presentation : bool
        Also hash :data:`PRESENTATION_CODE` (the book uses this for its stamps, since a
        figure depends on the plotting code).

    Returns
    -------
    str
        Hash over the relative path and content of every ``.py`` file of
        :data:`NUMERICAL_CODE` (and :data:`PRESENTATION_CODE`), in sorted order. Computed
        once per process.
    """
    prefixes = NUMERICAL_CODE + (PRESENTATION_CODE if include_presentation else ())
    h = hashlib.sha256()
    files = sorted(_PACKAGE_DIR.rglob("*.py"))
    for f in files:
        rel = f.relative_to(_PACKAGE_DIR).as_posix()
        if "__pycache__" in rel or not _selected(rel, prefixes):
            continue
        h.update(rel.encode())
        h.update(b"\0")
        h.update(f.read_bytes())
        h.update(b"\0")
    return h.hexdigest()[:16]


def _source_hash(func) -> str:
    try:
        src = inspect.getsource(func)
    except (OSError, TypeError):  # built-ins, some interactive definitions
        src = getattr(getattr(func, "__code__", None), "co_code", repr(func))
        src = src.hex() if isinstance(src, bytes) else str(src)
    return hashlib.sha256(src.encode()).hexdigest()[:16]


def cached(func=None, *, ignore=()):
    """Cache ``func`` on disk with :func:`get_memory`, keyed also by :func:`code_version`.

    With ``LUNARCAP_NO_CACHE`` set (checked at each call), ``func`` is simply called.

    Usable as ``@cached`` or ``@cached(ignore=["verbose"])``.

    Parameters
    ----------
    func : callable
        A function of hashable (picklable) arguments returning a picklable result.
    ignore : sequence of str
        Argument names left out of the key (verbosity, number of threads, ...).

    Returns
    -------
    callable
        Same signature as ``func``; attributes ``uncached`` (the original function),
        and ``is_cached(*args, **kwargs)``.
    """
    if func is None:
        return functools.partial(cached, ignore=ignore)
    sig = inspect.signature(func)
    ignore = tuple(ignore)
    unknown = [n for n in ignore if n not in sig.parameters]
    if unknown:
        raise ValueError(f"cached({func.__qualname__}): ignore names unknown arguments {unknown}")
    src_hash = _source_hash(func)

    def _call(code_version, source_hash, arguments, ignored):
        merged = {**arguments, **ignored}
        ordered = OrderedDict((n, merged[n]) for n in sig.parameters if n in merged)
        bound = inspect.BoundArguments(sig, ordered)
        return func(*bound.args, **bound.kwargs)

    # joblib names the store after module and qualified name: give each wrapped function
    # its own (deliberately no __wrapped__, so joblib sees _call's real signature).
    _call.__module__ = func.__module__
    _call.__name__ = func.__name__
    _call.__qualname__ = func.__qualname__
    made = {}

    def memorized():
        mem = get_memory()
        if id(mem) not in made:
            made.clear()
            made[id(mem)] = mem.cache(_call, ignore=["ignored"])
        return made[id(mem)]

    def _split(args, kwargs):
        bound = sig.bind(*args, **kwargs)
        bound.apply_defaults()
        key = {n: v for n, v in bound.arguments.items() if n not in ignore}
        ign = {n: v for n, v in bound.arguments.items() if n in ignore}
        return (code_version(), src_hash, key, ign)

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        if not _enabled():
            return func(*args, **kwargs)
        return memorized()(*_split(args, kwargs))

    def is_cached(*args, **kwargs) -> bool:
        """True if a result for these arguments is already on disk."""
        if not _enabled():
            return False
        return memorized().check_call_in_cache(*_split(args, kwargs))

    wrapper.uncached = func
    wrapper.is_cached = is_cached
    return wrapper


def clear() -> None:
    """Delete every cached result."""
    get_memory().clear(warn=False)
