"""The book's manifest: its entries, their validation, the table of contents, the stamps.

The manifest lists one :class:`Entry` per execution of a notebook. lunarcap's book has no
manifest file: its entries and table of contents are derived from the registered pages
(:mod:`lunarcap.report.contents`, :func:`from_pages`); a throw-away book, as the tests
make, may carry its own ``notebooks/manifest.yml`` and ``book/_toc.yml`` instead.
:func:`load_manifest` validates the entries (every problem at once, :class:`ManifestError`),
:func:`check_toc` matches them against the table of contents, :func:`select` picks
entries with their dependencies, and :func:`stamp_for` / :func:`is_up_to_date` decide
whether an executed notebook is current.
"""

from __future__ import annotations

import ast
import dataclasses
import hashlib
import json
import re
from pathlib import Path

import yaml

from lunarcap.report import contents
from lunarcap.repro import paths

ENTRY_KEYS = {"name", "title", "notebook", "parameters", "quick_parameters", "depends_on",
              "outputs", "expected_s", "floors"}
REQUIRED_KEYS = {"name", "title", "notebook"}
#: Parameters every notebook declares and the book injects.
INJECTED = ("quick", "output_name")
KERNEL = "python3"
STAMP_VERSION = 1


class ManifestError(ValueError):
    """The manifest (or the table of contents) is invalid; the message lists every problem."""


@dataclasses.dataclass(frozen=True)
class Entry:
    """One execution of a notebook (see the module docstring for the fields)."""

    name: str
    title: str
    notebook: Path
    parameters: dict
    quick_parameters: dict
    depends_on: tuple
    outputs: tuple
    expected_s: float = 0.0
    floors: dict = dataclasses.field(default_factory=dict)

    def effective_parameters(self, quick: bool) -> dict:
        """Parameters papermill injects: parameters, quick overrides, ``quick``, ``output_name``."""
        p = dict(self.parameters)
        if quick:
            p.update(self.quick_parameters)
        p["quick"] = bool(quick)
        p["output_name"] = self.name
        return p

    @property
    def output(self) -> Path:
        """The executed notebook."""
        return paths.executed_notebook_path(self.name)

    @property
    def stamp_path(self) -> Path:
        """The stamp recording what the executed notebook was made from."""
        return paths.GENERATED / f"{self.name}.stamp.json"

    @property
    def failed_path(self) -> Path:
        """Where the executed notebook of a failed run is kept."""
        return paths.GENERATED / f"{self.name}.failed.ipynb"


# ====================================================================== manifest validation
def notebook_parameters(nb_path: Path) -> tuple[list[str], list[str]]:
    """Names assigned in the notebook's ``parameters`` cell, and problems found.

    Returns
    -------
    (names, problems) : list of str, list of str
    """
    import nbformat

    try:
        nb = nbformat.read(str(nb_path), as_version=4)
    except Exception as exc:  # nbformat raises assorted errors on bad JSON
        return [], [f"cannot read notebook {nb_path}: {exc}"]
    cells = [c for c in nb.cells if "parameters" in c.get("metadata", {}).get("tags", [])]
    if len(cells) != 1:
        return [], [f"notebook {nb_path.name} must have exactly one cell tagged 'parameters' "
                    f"(found {len(cells)})"]
    try:
        tree = ast.parse(cells[0].source)
    except SyntaxError as exc:
        return [], [f"notebook {nb_path.name}: parameters cell is not valid Python: {exc}"]
    names = []
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else (
            [node.target] if isinstance(node, ast.AnnAssign) else [])
        names += [t.id for t in targets if isinstance(t, ast.Name)]
    problems = [f"notebook {nb_path.name}: parameters cell must define {n!r}"
                for n in INJECTED if n not in names]
    return names, problems


def find_cycle(graph: dict[str, list[str]]) -> list[str] | None:
    """A dependency cycle ``[a, b, ..., a]`` in ``graph`` (name -> dependencies), or None."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for d in graph.get(n, ()):
            if state.get(d) == 1:
                return stack[stack.index(d):] + [d]
            if d in graph and state.get(d) is None:
                found = visit(d)
                if found:
                    return found
        stack.pop()
        state[n] = 2
        return None

    for n in graph:
        if state.get(n) is None:
            found = visit(n)
            if found:
                return found
    return None


def _entry_keys_problems(raw, i: int) -> tuple[str, list[str], bool]:
    """Where an entry is (for messages), problems with its keys, and whether to go on."""
    where = f"entry {i + 1}"
    if not isinstance(raw, dict):
        return where, [f"{where}: must be a mapping, got {type(raw).__name__}"], False
    name = raw.get("name")
    if isinstance(name, str):
        where = f"entry {i + 1} ({name!r})"
    errors = []
    unknown = sorted(set(raw) - ENTRY_KEYS)
    if unknown:
        errors.append(f"{where}: unknown key(s) {unknown}; allowed: {sorted(ENTRY_KEYS)}")
    missing = sorted(REQUIRED_KEYS - set(raw))
    if missing:
        return where, errors + [f"{where}: missing key(s) {missing}"], False
    try:
        paths.check_name(name)
    except ValueError as exc:
        return where, errors + [f"{where}: {exc}"], False
    return where, errors, True


def _parameter_problems(where: str, params, quick) -> list[str]:
    """``parameters`` and ``quick_parameters`` must be mappings not setting injected names."""
    errors = []
    for key, val in (("parameters", params), ("quick_parameters", quick)):
        if not isinstance(val, dict):
            errors.append(f"{where}: {key} must be a mapping")
        else:
            bad = [k for k in val if k in INJECTED]
            if bad:
                errors.append(f"{where}: {key} may not set {bad} (injected by the book)")
    return errors


def _declared_problems(where: str, nb: Path, params: dict, quick: dict,
                       nb_params: dict) -> list[str]:
    """Parameters the manifest gives that the notebook's parameters cell does not define."""
    if nb not in nb_params:
        nb_params[nb] = notebook_parameters(nb)
    names, problems = nb_params[nb]
    errors = [f"{where}: {p}" for p in problems]
    if names:
        undeclared = sorted((set(params) | set(quick)) - set(names))
        if undeclared:
            errors.append(f"{where}: parameter(s) {undeclared} are not defined in the "
                          f"parameters cell of {nb.name}")
    return errors


def _lists(where: str, raw: dict) -> tuple[list, list, list[str]]:
    """``depends_on`` and ``outputs`` of an entry (empty when invalid) and their problems."""
    errors = []
    deps = raw.get("depends_on") or []
    if not isinstance(deps, list) or not all(isinstance(d, str) for d in deps):
        errors.append(f"{where}: depends_on must be a list of entry names")
        deps = []
    outputs = raw.get("outputs") or []
    if not isinstance(outputs, list) or not all(
            isinstance(o, str) and not o.startswith("/") and ".." not in Path(o).parts
            for o in outputs):
        errors.append(f"{where}: outputs must be a list of paths relative to book/generated")
        outputs = []
    return deps, outputs, errors


def _entry(raw: dict, where: str, notebooks_dir: Path, check_notebooks: bool,
           nb_params: dict) -> tuple[Entry | None, list[str]]:
    """One entry whose keys are valid, and the problems of its values."""
    errors = []
    if not isinstance(raw["title"], str) or not raw["title"].strip():
        errors.append(f"{where}: title must be a non-empty string")
    nb = (Path(notebooks_dir) / str(raw["notebook"])).resolve()
    if not str(raw["notebook"]).endswith(".ipynb") or not nb.is_file():
        errors.append(f"{where}: notebook {raw['notebook']!r} not found in {notebooks_dir}")
        nb = None
    params = raw.get("parameters") or {}
    quick = raw.get("quick_parameters") or {}
    errors += _parameter_problems(where, params, quick)
    deps, outputs, more = _lists(where, raw)
    errors += more
    expected_s = raw.get("expected_s", 0.0)
    if isinstance(expected_s, bool) or not isinstance(expected_s, (int, float)) \
            or not expected_s >= 0:
        errors.append(f"{where}: expected_s must be a number of seconds >= 0, got "
                      f"{expected_s!r}")
        expected_s = 0.0
    floors, more = _floors(where, raw.get("floors") or {}, params)
    errors += more
    if nb is None:
        return None, errors
    if check_notebooks and isinstance(params, dict) and isinstance(quick, dict):
        errors += _declared_problems(where, nb, params, quick, nb_params)
    return Entry(raw["name"], str(raw["title"]).strip(), nb,
                 dict(params) if isinstance(params, dict) else {},
                 dict(quick) if isinstance(quick, dict) else {},
                 tuple(deps), tuple(outputs), float(expected_s), floors), errors


def _floors(where: str, raw, params) -> tuple[dict, list[str]]:
    """An entry's ``floors`` (parameter -> :class:`lunarcap.report.contents.Floor`), problems.

    Each names a parameter the entry gives, with one kind, its value and why.
    """
    if not isinstance(raw, dict):
        return {}, [f"{where}: floors must be a mapping of parameter -> floor"]
    floors, errors = {}, []
    for name, spec in raw.items():
        try:
            floors[name] = contents.Floor.from_dict(spec)
        except contents.ContentsError as exc:
            errors.append(f"{where}: floor of {name!r}: {exc}")
            continue
        if not isinstance(params, dict) or name not in params:
            errors.append(f"{where}: floor of {name!r}: no such parameter in its parameters")
    return floors, errors


def _dependency_problems(entries: list[Entry], seen: set[str]) -> list[str]:
    """Unknown dependencies, self-dependencies and cycles."""
    errors = []
    names = {e.name for e in entries} | seen
    for e in entries:
        for d in e.depends_on:
            if d not in names:
                errors.append(f"entry {e.name!r}: depends_on unknown entry {d!r}")
            if d == e.name:
                errors.append(f"entry {e.name!r}: depends on itself")
    cycle = find_cycle({e.name: [d for d in e.depends_on if d != e.name] for e in entries})
    if cycle:
        errors.append("dependency cycle: " + " -> ".join(cycle))
    return errors


#: ``depends_on: ["*"]``: the entry depends on every other entry of the manifest.
ALL = "*"


def expand_all_dependencies(entries: list[Entry]) -> list[Entry]:
    """Entries with ``depends_on: ["*"]`` made to depend on every other entry, in file order.

    An entry that reads what every page made (the findings page) runs last and is
    stamped with every other entry's digest, so any change reruns it.
    """
    names = [e.name for e in entries]
    return [dataclasses.replace(e, depends_on=tuple(n for n in names if n != e.name))
            if ALL in e.depends_on else e for e in entries]


def validate_manifest(data, notebooks_dir: Path | None = None,
                      check_notebooks: bool = True) -> list[Entry]:
    """Validate a parsed manifest and return its entries in file order.

    Parameters
    ----------
    data : dict
        The parsed YAML: ``{"entries": [ {...}, ... ]}``.
    notebooks_dir : Path, optional
        Directory the ``notebook`` fields are relative to (default ``notebooks/``).
    check_notebooks : bool
        Also open each notebook and check its parameters cell declares every parameter
        the manifest gives (and ``quick``, ``output_name``).

    Raises
    ------
    ManifestError
        Listing every problem found (unknown or missing keys, duplicate names, missing
        notebooks, unknown parameters, unknown dependencies, dependency cycles).
    """
    notebooks_dir = Path(notebooks_dir or paths.NOTEBOOKS)
    if not isinstance(data, dict) or set(data) != {"entries"} or not isinstance(
            data.get("entries"), list):
        raise ManifestError("manifest must be a mapping with one key 'entries' holding a list")
    errors: list[str] = []
    entries: list[Entry] = []
    seen: set[str] = set()
    nb_params: dict[Path, tuple] = {}
    for i, raw in enumerate(data["entries"]):
        where, problems, usable = _entry_keys_problems(raw, i)
        errors += problems
        if not usable:
            continue
        if raw["name"] in seen:
            errors.append(f"{where}: duplicate name {raw['name']!r}")
        seen.add(raw["name"])
        entry, problems = _entry(raw, where, notebooks_dir, check_notebooks, nb_params)
        errors += problems
        if entry is not None:
            entries.append(entry)
    entries = expand_all_dependencies(entries)
    errors += _dependency_problems(entries, seen)
    if errors:
        raise ManifestError("invalid manifest:\n  - " + "\n  - ".join(errors))
    return entries


def from_pages() -> bool:
    """Whether the book is the registered pages' (no ``notebooks/manifest.yml`` in the tree).

    lunarcap's book declares its pages in :data:`lunarcap.report.pages.PAGES`; a manifest
    file is the input of a throw-away book (the tests' trees), executed as written.
    """
    return not paths.MANIFEST.is_file()


def registered_pages() -> list:
    """The registered pages (:func:`lunarcap.report.contents.registered`), checked.

    Raises
    ------
    ManifestError
        Naming each page without a notebook, notebook without a page, unknown part...
    """
    try:
        pages = contents.registered()
    except contents.ContentsError as exc:
        raise ManifestError(str(exc)) from exc
    errors = contents.problems(pages, paths.NOTEBOOKS)
    if errors:
        raise ManifestError("the registered pages are invalid:\n  - " + "\n  - ".join(errors))
    return pages


def load_manifest(path: Path | None = None, check_notebooks: bool = True) -> list[Entry]:
    """The book's entries, validated (see :func:`validate_manifest`).

    From ``path`` if given, else from ``notebooks/manifest.yml`` if the tree has one, else
    from the registered pages (:func:`from_pages`).
    """
    if path is None and from_pages():
        return validate_manifest(contents.manifest(registered_pages(), paths.NOTEBOOKS),
                                 paths.NOTEBOOKS, check_notebooks)
    path = Path(path or paths.MANIFEST)
    if not path.is_file():
        raise ManifestError(f"manifest not found: {path}")
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except yaml.YAMLError as exc:
        raise ManifestError(f"manifest {path} is not valid YAML: {exc}") from exc
    return validate_manifest(data, path.parent, check_notebooks)


def toc_files(toc_path: Path | None = None) -> list[str]:
    """Every ``file:`` of the jupyter-book table of contents, root first (no extension).

    Of ``toc_path`` if given, else of the registered pages (:func:`from_pages`), else of
    the tree's ``book/_toc.yml``.
    """
    if toc_path is None and from_pages():
        return contents.toc_files(registered_pages())
    toc = yaml.safe_load(Path(toc_path or paths.TOC).read_text(encoding="utf-8"))
    out = [toc["root"]]

    def walk(node):
        if isinstance(node, dict):
            if "file" in node:
                out.append(node["file"])
            for v in node.values():
                walk(v)
        elif isinstance(node, list):
            for v in node:
                walk(v)

    walk({k: v for k, v in toc.items() if k != "root"})
    return [re.sub(r"\.(md|ipynb)$", "", f) for f in out]


def check_toc(entries: list[Entry], toc_path: Path | None = None) -> None:
    """Every entry must appear in the toc as ``generated/<name>`` and vice versa.

    Every other file it lists must exist in ``book/``. The table of contents is
    ``toc_path``'s if given, else as :func:`toc_files` finds it.

    Raises
    ------
    ManifestError
    """
    toc_path = Path(toc_path or paths.TOC)
    files = toc_files(None if toc_path == paths.TOC else toc_path)
    gen = {f.split("/", 1)[1] for f in files if f.startswith("generated/")}
    names = {e.name for e in entries}
    errors = [f"manifest entry {n!r} is not in {toc_path.name} (add '- file: generated/{n}')"
              for n in sorted(names - gen)]
    errors += [f"{toc_path.name} lists generated/{n}, which no manifest entry produces"
               for n in sorted(gen - names)]
    book_dir = Path(toc_path).parent
    for f in files:
        if not f.startswith("generated/") and not any(
                (book_dir / f"{f}{ext}").is_file() for ext in (".md", ".ipynb")):
            errors.append(f"{toc_path.name} lists {f}, which does not exist in {book_dir}")
    if errors:
        raise ManifestError("table of contents does not match the manifest:\n  - "
                            + "\n  - ".join(errors))


def write_contents(directory: Path) -> Path | None:
    """Write the registered pages' manifest and ``_toc.yml`` in ``directory``.

    Returns the table of contents to give jupyter-book (``--toc``), or None for a book
    with its own ``_toc.yml`` (:func:`from_pages`). Files are rewritten only when their
    content changes.
    """
    if not from_pages():
        return None
    pages = registered_pages()
    toc = Path(directory) / "_toc.yml"
    for path, data, head in (
            (Path(directory) / "manifest.yml", contents.manifest(pages, paths.NOTEBOOKS),
             "# What the build executed: generated from lunarcap.report.pages.PAGES.\n"),
            (toc, contents.toc(pages),
             "# The table of contents: generated from lunarcap.report.pages.PAGES.\n")):
        text = head + yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=100)
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            paths.write_text_atomic(path, text)
    return toc


def check_floors(entries: list[Entry]) -> None:
    """Refuse a full book whose pages run below their floors, before any of them runs.

    Each entry's parameters (the full book's, never the quick ones) must meet the floors
    its page declares (:class:`lunarcap.report.contents.Floor`): the sizes the page's
    claims need.

    Raises
    ------
    ManifestError
        Naming each entry, parameter and floor missed, with the floor's reason.
    """
    errors = [f"{e.name}: {p}" for e in entries
              for p in contents.below_floors(e.parameters, e.floors)]
    if errors:
        raise ManifestError("pages below their floors (the size their claims need; "
                            "`build --quick` runs the small book):\n  - "
                            + "\n  - ".join(errors))


def select(entries: list[Entry], only: list[str] | None) -> list[Entry]:
    """The entries named in ``only`` and everything they depend on (all if ``only`` is empty)."""
    if not only:
        return list(entries)
    by_name = {e.name: e for e in entries}
    unknown = [n for n in only if n not in by_name]
    if unknown:
        raise ManifestError(f"--only: unknown entr{'y' if len(unknown) == 1 else 'ies'} "
                            f"{unknown}; known: {sorted(by_name)}")
    keep: set[str] = set()
    todo = list(only)
    while todo:
        n = todo.pop()
        if n not in keep:
            keep.add(n)
            todo += list(by_name[n].depends_on)
    return [e for e in entries if e.name in keep]


# ====================================================================== stamps
def _sha256_file(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def stamp_for(entry: Entry, quick: bool, dep_digests: dict[str, str]) -> dict:
    """What an executed notebook is made from (its ``digest`` summarises the rest)."""
    from lunarcap.repro.cache import code_version

    lock = paths.ROOT / "environment-lock.txt"
    rec = {
        "stamp_version": STAMP_VERSION,
        "name": entry.name,
        "title": entry.title,
        "notebook": entry.notebook.relative_to(paths.ROOT).as_posix()
        if entry.notebook.is_relative_to(paths.ROOT) else str(entry.notebook),
        "notebook_sha256": _sha256_file(entry.notebook),
        "parameters": entry.effective_parameters(quick),
        "code_version": code_version(include_presentation=True),
        "environment_lock_sha256": _sha256_file(lock) if lock.is_file() else None,
        "depends_on": {d: dep_digests.get(d) for d in entry.depends_on},
    }
    rec["digest"] = hashlib.sha256(json.dumps(rec, sort_keys=True, default=str).encode()
                                   ).hexdigest()
    return rec


def read_stamp(entry: Entry) -> dict | None:
    """The stamp on disk, or None."""
    try:
        return json.loads(entry.stamp_path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def is_up_to_date(entry: Entry, stamp: dict) -> bool:
    """True if the stamp on disk matches ``stamp`` and every output exists and is non-empty."""
    old = read_stamp(entry)
    if not old or old.get("digest") != stamp["digest"] or not entry.output.is_file():
        return False
    return all((paths.GENERATED / o).is_file() and (paths.GENERATED / o).stat().st_size > 0
               for o in entry.outputs)
