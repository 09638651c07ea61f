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

One switch turns the cache off: ``with caching(False):`` (``--no-cache`` on the command
line). Inside the block nothing is read from or written to the cache, by any cached
function at any depth (a burn's earlier burns included). The switch is per thread (a
:class:`contextvars.ContextVar`); work shipped to another process or thread receives the
position explicitly (:func:`enabled` at submission, ``caching(...)`` in the task: see
:func:`lunarcap.studies.campaign.guarded`). Outside any block the switch stands where the
environment puts it: ``LUNARCAP_NO_CACHE=1`` for a whole process (the test suite, the book's
executed notebooks); lunarcap itself never edits the environment.

The optimiser's compiled NLPs are kept apart from the results, in :class:`NLPStore`
(``.cache/nlp``, keyed by :func:`code_version` too): built once per machine and loaded by
every later process and Dask worker. A loaded NLP computes the same bits as the one
built, so it is not a result and follows its own switch (:func:`nlp_store`), not
:func:`caching`.

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
import zlib
from collections import OrderedDict
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path

from lunarcap.repro import paths

#: What a cached result depends on: the numerical code (physics, the mission, the
#: optimiser), the error types, the module of the cached chain solves, and the open-loop
#: flights (which fly the exported steering segments). Editing anything
#: else (the CLI's help, the book, a figure, a plan file: a plan's content is part of the
#: key of each of its solves) keeps every cached solve.
NUMERICAL_CODE = ("physics/", "mission/", "optim/", "errors.py", "capture/chain.py",
                  "capture/openloop.py", "capture/export.py")

#: Besides those, the book's stamps hash the presentation code (a figure depends on it).
PRESENTATION_CODE = ("report/", "bookbuild/", "paper/", "studies/", "capture/", "cli/")

_PACKAGE_DIR = Path(__file__).resolve().parents[1]


#: The switch's position set by the innermost :func:`caching` block of this thread (None:
#: no block, the environment decides).
_SWITCH: ContextVar[bool | None] = ContextVar("lunarcap_cache_on", default=None)


def enabled() -> bool:
    """Whether cached functions read and write the disk cache here and now.

    The innermost :func:`caching` block's position; outside any block, on unless the
    environment sets ``LUNARCAP_NO_CACHE`` (to anything but "", 0, false or no).
    """
    on = _SWITCH.get()
    if on is not None:
        return on
    return os.environ.get("LUNARCAP_NO_CACHE", "").strip().lower() in ("", "0", "false", "no")


@contextmanager
def caching(on: bool = True) -> Iterator[None]:
    """Within the block, the disk cache is used (``on``) or neither read nor written.

    The one cache switch of lunarcap (see the module docstring); restored on leaving the
    block, exception or not.
    """
    token = _SWITCH.set(bool(on))
    try:
        yield
    finally:
        _SWITCH.reset(token)


def position(use_cache: bool | None) -> bool:
    """The switch's position to ship with a task to another process or thread.

    ``use_cache`` as given, or (None) the submitting thread's position (:func:`enabled`).
    """
    return enabled() if use_cache is None else bool(use_cache)


#: The joblib store, created on first use (joblib is imported only then): a process that
#: caches nothing (the switch off: :func:`caching`) does not pay for it.
memory = None


def get_memory():
    """The joblib Memory at :data:`lunarcap.repro.paths.JOBLIB_CACHE` (created once)."""
    global memory
    if memory is None:
        import joblib

        memory = joblib.Memory(location=str(paths.JOBLIB_CACHE), verbose=0)
    return memory


def location() -> str | None:
    """Where results are cached, or None when the switch is off (:func:`enabled`)."""
    return str(paths.JOBLIB_CACHE) if enabled() else None


def _selected(rel: str, prefixes) -> bool:
    return any(rel == p or (p.endswith("/") and rel.startswith(p)) for p in prefixes)


@functools.lru_cache(maxsize=None)
def code_version(*also: str, include_presentation: bool = False) -> str:
    """SHA-256 (hex, 16 characters) of the lunarcap source a result depends on.

    The one code version of lunarcap: the disk cache's key, a study table's
    ``code_version`` column and the book's stamps are all this function's value.

    Parameters
    ----------
    *also : str
        Further source files or folders, relative to the package (``"studies/missed/cases.py"``):
        a study's table depends on its own module too, not only on :data:`NUMERICAL_CODE`.
    include_presentation : bool
        Also hash :data:`PRESENTATION_CODE` (the book uses this for its stamps, since a
        figure depends on the plotting code).

    Returns
    -------
    str
        Hash over the relative path and content of every ``.py`` file of
        :data:`NUMERICAL_CODE`, ``also`` (and :data:`PRESENTATION_CODE`), in sorted order.
        Computed once per process and argument list.

    Raises
    ------
    ValueError
        If an entry of ``also`` names no source file of the package (a typo would silently
        leave it out of the version).
    """
    for rel in also:
        if not (_PACKAGE_DIR / rel).exists():
            raise ValueError(f"code_version: {rel!r} is no file or folder of lunarcap")
    prefixes = NUMERICAL_CODE + tuple(also) + (PRESENTATION_CODE if include_presentation else ())
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

    With the switch off (:func:`enabled`, checked at each call), ``func`` is simply called.

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
        Same signature as ``func``; attribute ``is_cached(*args, **kwargs)``. (To call
        it without the cache, turn the switch off: ``with caching(False): ...``.)
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
        if not enabled():
            return func(*args, **kwargs)
        return memorized()(*_split(args, kwargs))

    def is_cached(*args, **kwargs) -> bool:
        """True if a result for these arguments is already on disk."""
        if not enabled():
            return False
        return memorized().check_call_in_cache(*_split(args, kwargs))

    wrapper.is_cached = is_cached
    return wrapper


def clear() -> None:
    """Delete every cached result."""
    get_memory().clear(warn=False)


# ====================================================================== the NLP store
#: Format of a stored NLP file (a new format ignores the files of the old).
NLP_STORE_FORMAT = 1

#: How many code versions' NLP folders a store keeps (the newest; :meth:`NLPStore.prune`):
#: an edit of the numerical code starts a new folder (0.5 MB per shape).
NLP_VERSIONS_KEPT = 4

#: ``LUNARCAP_NLP_CACHE=0`` (or false, no) keeps NLPs in memory only: every process builds
#: its own (:func:`nlp_store`).
NLP_CACHE_ENV = "LUNARCAP_NLP_CACHE"


def nlp_store() -> NLPStore | None:
    """The machine's NLP store (:class:`NLPStore` at ``.cache/nlp``), or None if disabled.

    Independent of the results' switch (:func:`caching`): a stored NLP is compiled code,
    not a result; a loaded one computes the same bits as the one built, so ``--no-cache``
    (recompute every result) still loads it. :data:`NLP_CACHE_ENV` turns it off.
    """
    if os.environ.get(NLP_CACHE_ENV, "").strip().lower() in ("0", "false", "no", "off"):
        return None
    return NLPStore(paths.NLP_CACHE)


class NLPStore:
    """The optimiser's compiled NLPs and node libraries on disk, once per machine.

    An NLP (:meth:`save`, :meth:`load`) is a file ``<code version>/<key>.nlp`` below
    ``directory``, the key a SHA-256 of its description (kind, shape, CasADi version, how
    its derivatives run) and of :func:`code_version`: an edit of the numerical code
    builds every NLP again, in a new folder. A file is the SHA-256 of its content followed
    by that content (zlib): written to a temporary file and moved into place, so a
    reader sees a whole file or none; one that fails its checksum or its decoding is
    deleted with one line on stderr, and the caller builds the NLP again.
    :meth:`locked` lets one process build what another waits for. :meth:`file` is a
    plain path in the store for the optimiser's compiled node functions (``nodes/``,
    named by their C source's hash, whatever the code version).
    """

    def __init__(self, directory: str | os.PathLike):
        self.directory = Path(directory)

    def _key(self, parts) -> str:
        if isinstance(parts, str):
            return parts
        text = repr((NLP_STORE_FORMAT, code_version(), *parts))
        return hashlib.sha256(text.encode()).hexdigest()[:32]

    def path(self, parts) -> Path:
        """The file of the NLP described by ``parts``."""
        return self.directory / code_version() / f"{self._key(parts)}.nlp"

    def load(self, parts, decode):
        """``decode(bytes)`` of the stored NLP, or None (absent, or unreadable: deleted)."""
        path = self.path(parts)
        try:
            raw = path.read_bytes()
        except FileNotFoundError:
            return None
        except OSError as exc:
            _store_warning(f"the stored NLP {path} cannot be read ({exc.strerror}); building "
                           f"it in this process")
            return None
        try:
            digest, body = raw[:64], raw[64:]
            if hashlib.sha256(body).hexdigest().encode() != digest:
                raise ValueError("its checksum does not match: truncated or damaged")
            return decode(zlib.decompress(body))
        except Exception as exc:   # any failure to read it back: build it again
            why = str(exc).strip().splitlines()[0][:160] if str(exc).strip() else \
                type(exc).__name__
            _store_warning(f"the stored NLP {path} is unreadable ({why}); building it again")
            path.unlink(missing_ok=True)
            return None

    def save(self, parts, data: bytes) -> Path | None:
        """Store ``data`` for ``parts`` (atomically); its path, or None if it cannot be written."""
        path = self.path(parts)
        body = zlib.compress(data, 1)
        fresh = not path.parent.exists()
        try:
            with paths.atomic_path(path) as tmp:
                tmp.write_bytes(hashlib.sha256(body).hexdigest().encode() + body)
        except OSError:
            return None   # a read-only cache: the NLP stays in this process
        if fresh:
            self.prune()
        return path

    def prune(self, keep: int = NLP_VERSIONS_KEPT) -> list:
        """Delete all but the ``keep`` most recently written code versions' folders."""
        import shutil

        folders = sorted((f for f in self.directory.iterdir()
                          if f.is_dir() and f.name != "nodes"),
                         key=lambda f: f.stat().st_mtime, reverse=True)
        for old in folders[keep:]:
            shutil.rmtree(old, ignore_errors=True)
        return folders[keep:]

    @contextmanager
    def locked(self, parts) -> Iterator[None]:
        """Hold an exclusive lock on ``parts`` (an NLP's, or a name) while in the block.

        A lock file that cannot be created (a read-only cache) does not stop the caller,
        which then builds without waiting for anyone.
        """
        import fcntl

        folder = self.directory / ("nodes" if isinstance(parts, str) else code_version())
        try:
            folder.mkdir(parents=True, exist_ok=True)
            fh = open(folder / f".{self._key(parts)}.lock", "w")
        except OSError:
            yield
            return
        try:
            fcntl.flock(fh, fcntl.LOCK_EX)
            yield
        finally:
            fh.close()

    def file(self, name: str, suffix: str) -> Path:
        """A path ``nodes/<name><suffix>`` in the store (its folder created)."""
        folder = self.directory / "nodes"
        folder.mkdir(parents=True, exist_ok=True)
        return folder / f"{name}{suffix}"


def _store_warning(msg: str) -> None:
    """One line on the process's stderr (a terminal, or a notebook kernel's log)."""
    import sys

    print(f"lunarcap: {msg}", file=sys.__stderr__ or sys.stderr, flush=True)
