"""Provenance of a generated page: code, environment, ephemeris, notebook and parameters.

:func:`collect` returns a plain dict (JSON-friendly); :func:`render_markdown` turns it
into a small MyST admonition, and :func:`header` displays that admonition at the top
of an executed notebook. :func:`source_note` is the one-line "made by" note placed
under each table and figure.

Examples
--------
>>> p = collect(ephemeris=False)
>>> sorted(k for k in p if k in ("lunarcap", "python", "git_commit"))
['git_commit', 'lunarcap', 'python']
"""

from __future__ import annotations

import ctypes
import datetime as _dt
import functools
import glob
import os
import platform
import subprocess

from lunarcap import __version__
from lunarcap.repro import paths
from lunarcap.repro.cache import code_version


def _git(*args: str) -> str | None:
    try:
        out = subprocess.run(["git", *args], cwd=paths.ROOT, capture_output=True, text=True,
                             timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 else None


def git_state() -> dict:
    """Git commit of :data:`lunarcap.repro.paths.ROOT` and whether tracked files differ from it.

    Returns
    -------
    dict with ``git_commit`` (40 hex digits or None outside a repository) and
    ``git_dirty`` (bool or None).
    """
    commit = _git("rev-parse", "HEAD")
    if commit is None:
        return {"git_commit": None, "git_dirty": None}
    status = _git("status", "--porcelain", "--untracked-files=no")
    return {"git_commit": commit, "git_dirty": bool(status) if status is not None else None}


@functools.lru_cache(maxsize=None)
def ipopt_version() -> str | None:
    """Version of the IPOPT library shipped with CasADi, e.g. ``"3.14.19"`` (None if absent)."""
    try:
        import casadi
    except ImportError:
        return None
    libdir = os.path.dirname(casadi.__file__)
    for name in ("libipopt.so", "libipopt.dylib", "ipopt-3.dll", "libipopt-3.dll"):
        path = os.path.join(libdir, name)
        if not os.path.exists(path):
            continue
        try:
            lib = ctypes.CDLL(path)
            a, b, c = ctypes.c_int(), ctypes.c_int(), ctypes.c_int()
            lib.GetIpoptVersion(ctypes.byref(a), ctypes.byref(b), ctypes.byref(c))
            return f"{a.value}.{b.value}.{c.value}"
        except (OSError, AttributeError):
            break
    # fall back on the versioned file name (libipopt.so.3.14.19)
    hits = sorted(glob.glob(os.path.join(libdir, "libipopt.so.*.*.*")))
    return hits[-1].rsplit("libipopt.so.", 1)[1] if hits else None


def _version(module: str) -> str | None:
    try:
        mod = __import__(module)
    except ImportError:
        return None
    return getattr(mod, "__version__", None)


def collect(ephemeris=None, solver: dict | None = None) -> dict:
    """Provenance record of the current process.

    Parameters
    ----------
    ephemeris : lunarcap.physics.ephemeris.Ephemeris, None or False
        The ephemeris used (default: the process-wide DE405); ``False`` to leave it out.
    solver : dict, optional
        Solver settings to record (transcription, mesh, tolerances), added as ``solver``.

    Returns
    -------
    dict
        ``lunarcap``, ``code_version``, ``git_commit``, ``git_dirty``, ``python``,
        ``platform``, ``numpy``, ``casadi``, ``ipopt``, ``ephemeris``,
        ``ephemeris_sha256`` (of every file the ephemeris reads, the libration angles of
        the Moon's body frame included: :meth:`~lunarcap.physics.ephemeris.Ephemeris.
        data_files`), ``date_utc`` (and ``solver`` if given).
    """
    rec = {"lunarcap": __version__, "code_version": code_version(include_presentation=True)}
    rec.update(git_state())
    rec.update({
        "python": platform.python_version(),
        "platform": f"{platform.system()} {platform.machine()}",
        "numpy": _version("numpy"),
        "casadi": _version("casadi"),
        "ipopt": ipopt_version(),
    })
    if ephemeris is not False:
        if ephemeris is None:
            from lunarcap.physics.ephemeris import default_ephemeris

            ephemeris = default_ephemeris()
        desc = ephemeris.describe()
        rec["ephemeris"] = desc["ephemeris"]
        rec["ephemeris_sha256"] = desc["sha256"]
    rec["date_utc"] = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
    if solver:
        rec["solver"] = dict(solver)
    return rec


#: What a parameter left at None means, as the book says it (never a bare "None").
NONE_MEANS = {"dynamics": "each plan's own", "previous_starts": "the paper's best (Table B1)",
              "starts": "the paper's best (Table B1)", "thrusts_N": "the paper's engines"}


def format_value(name: str, v) -> str:
    """One parameter's value as the book shows it: ``repr``, or what None means.

    >>> format_value("dynamics", None), format_value("thrust_N", 150.0)
    ("(each plan's own)", '150.0')
    """
    if v is None:
        return f"({NONE_MEANS.get(name, 'default')})"
    return repr(v)


def format_parameters(parameters: dict | None) -> str:
    """``a=1, b='x'`` from a parameter dict (in its order; None as its meaning)."""
    if not parameters:
        return "(none)"
    return ", ".join(f"{k}={format_value(k, v)}" for k, v in parameters.items())


def source_note(notebook: str, parameters: dict | None = None) -> str:
    """One line naming the notebook and parameters that made a table or figure (MyST)."""
    return f"Made by `{notebook}` with {format_parameters(parameters)}."


def _code(v) -> str:
    return f"`{v}`" if v not in (None, "") else "unknown"


def render_markdown(prov: dict, notebook: str | None = None, parameters: dict | None = None,
                    quick: bool = False) -> str:
    """A MyST admonition listing the provenance, notebook and parameters of a page.

    Parameters
    ----------
    prov : dict from :func:`collect`
    notebook : str, the source notebook (path relative to the repository root)
    parameters : dict of the parameters this execution used
    quick : bool, whether the page was produced by a quick (CI) run

    Returns
    -------
    str
        MyST Markdown (needs the ``colon_fence`` extension and
        ``nb_render_markdown_format: myst``, as set in ``book/_config.yml``).
    """
    commit = prov.get("git_commit")
    if commit:
        commit_txt = f"git `{commit[:12]}`" + (" with uncommitted changes"
                                               if prov.get("git_dirty") else "")
    else:
        commit_txt = "not a git checkout"
    rows = []
    if notebook:
        rows.append(("Notebook", f"`{notebook}`"))
    if parameters is not None:
        rows.append(("Parameters", f"`{format_parameters(parameters)}`"))
    rows += [
        ("Code", f"lunarcap {prov.get('lunarcap')}, {commit_txt}, source hash "
                 f"{_code(prov.get('code_version'))}"),
        ("Environment", f"Python {prov.get('python')} ({prov.get('platform')}), "
                        f"NumPy {prov.get('numpy')}, CasADi {prov.get('casadi')}, "
                        f"IPOPT {prov.get('ipopt')}"),
    ]
    if "ephemeris" in prov:
        rows.append(("Ephemeris", f"{prov['ephemeris']}, SHA-256 "
                                  f"{_code(prov.get('ephemeris_sha256'))} (its positions and "
                                  f"the DE405 libration angles of the Moon's body frame)"))
    else:
        rows.append(("Ephemeris", "not used"))
    if prov.get("solver"):
        rows.append(("Solver", ", ".join(f"{k}={v}" for k, v in prov["solver"].items())))
    rows.append(("Executed", prov.get("date_utc", "")))
    if quick:
        title = "Provenance: quick run (coarse settings for CI, not the book's final numbers)"
        kind = "warning"
    else:
        title, kind = "Provenance", "note"
    body = "\n".join(f"{k}\n: {v}\n" for k, v in rows)
    return f":::{{admonition}} {title}\n:class: {kind} provenance\n\n{body}:::\n"


def header(notebook: str, parameters: dict | None = None, quick: bool = False,
           ephemeris=None, solver: dict | None = None, display: bool = True):
    """Show the provenance admonition in a notebook (call it right after the parameters).

    Parameters
    ----------
    notebook : str
        The source notebook, relative to the repository root (``notebooks/x.ipynb``).
    parameters : dict
        The parameters of this execution.
    quick : bool
        The notebook's ``quick`` parameter.
    ephemeris, solver : see :func:`collect`
    display : bool
        Display the Markdown (default); otherwise only return it.

    Returns
    -------
    dict
        The provenance record (to store beside results if wanted).
    """
    prov = collect(ephemeris=ephemeris, solver=solver)
    prov["notebook"] = notebook
    prov["parameters"] = dict(parameters or {})
    prov["quick"] = bool(quick)
    text = render_markdown(prov, notebook, parameters, quick)
    if display:
        from IPython.display import Markdown
        from IPython.display import display as _display

        _display(Markdown(text))
    return prov
