"""The glossary of reported quantities: one name, one unit, one label, one definition each.

Every CSV column and JSON key lunarcap writes is a name of this glossary, used alike in
code, tables, JSON, axis labels and the book's prose. The glossary is data: the package's
``data/glossary.yaml`` (the shared quantities, the unit suffixes, the composition prefixes
and suffixes, the retired names and the captures the book compares, with the format
described at its head) and the ``glossary.yaml`` of each study folder
(``studies/<study>/glossary.yaml``: that study's own quantities). This module reads them
once, on import, and serves them: :func:`lookup` resolves a name, direct or composed (a
prefix, :data:`PREFIXES`: ``paper_delta_v_mps`` is the delta-V as Song et al. (2011)
print it; or an LOI suffix, :data:`SUFFIXES`: ``loss_percent_loi1``), :func:`is_known`
and :func:`unknown` check names. A study's folder is found by its place, not imported,
so that any module (a figure's axis label) resolves every name without importing the
studies; a study outside the package hands its quantities to :func:`merge` (the studies'
registry does, :mod:`lunarcap.studies.registry`). A name defined twice is an error.

Examples
--------
>>> lookup("delta_v_loss_mps").unit, lookup("paper_delta_v_mps").label
('m/s', 'ΔV, paper')
>>> is_known("loss_mps")
False
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import yaml

_PACKAGE = Path(__file__).resolve().parent

#: The shared glossary and its tables (units, prefixes, suffixes, retired names, captures).
DATA = _PACKAGE / "data" / "glossary.yaml"

#: The study folders' own glossaries, merged after :data:`DATA` in name order.
STUDY_FILES = tuple(sorted(_PACKAGE.glob("studies/*/glossary.yaml")))

#: The JSON types a quantity may have (``kind``; :mod:`lunarcap.schemas` is generated from it).
KINDS = ("number", "integer", "string", "boolean", "array", "object")


@dataclass(frozen=True)
class Quantity:
    """A reported quantity.

    Attributes
    ----------
    name : str
        The column / JSON key, unit suffix included.
    unit : str
        The unit as printed (``"m/s"``); ``""`` for a dimensionless number or text.
    label : str
        Short words for a table header or an axis (without the unit).
    definition : str
        One sentence: what the number is, measured from where to where.
    kind : str
        JSON type: one of :data:`KINDS`.
    """

    name: str
    unit: str
    label: str
    definition: str
    kind: str = "number"

    @property
    def header(self) -> str:
        """Label and unit, e.g. ``"ΔV (m/s)"``."""
        return f"{self.label} ({self.unit})" if self.unit else self.label


class _UniqueKeys(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):
    """YAML's safe loader, refusing a key given twice in one mapping (YAML keeps the last).

    libyaml's loader where it is built: the glossary then loads in tens of ms, not hundreds.
    """

    def construct_mapping(self, node, deep=False):
        """The mapping of ``node``; ValueError naming a key given twice and its line."""
        seen = set()
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=deep)
            if key in seen:
                raise ValueError(f"{key_node.start_mark.name}, line "
                                 f"{key_node.start_mark.line + 1}: {key!r} is defined twice")
            seen.add(key)
        return super().construct_mapping(node, deep)


def read(path: str | Path) -> dict:
    """A glossary file's contents (a key given twice in one mapping is a ValueError)."""
    with open(path, encoding="utf-8") as f:
        return yaml.load(f, Loader=_UniqueKeys)


_TABLES = read(DATA)

#: Unit suffixes of names and the unit printed (matched longest first).
UNIT_SUFFIXES: dict = dict(_TABLES["units"])

#: Composition prefixes: ``prefix`` -> (label prefix, label suffix, how the definition reads).
PREFIXES: dict = {p: (*v["label"], v["definition"]) for p, v in _TABLES["prefixes"].items()}

#: Composition suffixes (after the unit): ``suffix`` -> (label suffix, definition).
SUFFIXES: dict = {s: (v["label"], v["definition"]) for s, v in _TABLES["suffixes"].items()}

#: Old names that must never appear (each had several meanings).
RETIRED: tuple = tuple(_TABLES["retired"])

#: The captures of the paper's arrival the book compares, by the name every page uses for
#: them ("the 150 N capture" is one of these, in some dynamics; each page names which):
#: key -> (name, definition).
CAPTURES: dict = {k: (v["name"], v["definition"]) for k, v in _TABLES["captures"].items()}


def unit_of(name: str) -> str:
    """The unit a name's suffix states (``""`` if none)."""
    for suffix in sorted(UNIT_SUFFIXES, key=len, reverse=True):
        if name.endswith(suffix) and len(name) > len(suffix):
            return UNIT_SUFFIXES[suffix]
    return ""


#: Every quantity, in the order merged; by name (:data:`GLOSSARY`); where each was defined.
_Q: list = []
GLOSSARY: dict = {}
_SOURCES: dict = {}


def _quantity(name: str, entry: dict, source: str) -> Quantity:
    """The :class:`Quantity` of one glossary entry (its unit from its name's suffix)."""
    if not isinstance(entry, dict) or {"label", "definition"} - set(entry) \
            or set(entry) - {"label", "definition", "kind"}:
        raise ValueError(f"{source}: {name}: an entry is its label, definition and kind "
                         f"(optional), got {entry!r}")
    kind = entry.get("kind", "number")
    if kind not in KINDS:
        raise ValueError(f"{source}: {name}: kind must be one of {', '.join(KINDS)}, "
                         f"got {kind!r}")
    return Quantity(name, unit_of(name) if kind in ("number", "integer") else "",
                    entry["label"], entry["definition"], kind)


def merge(entries: dict, source: str) -> list:
    """Add quantities to the glossary (``{name: {label, definition, kind}}``, as the files).

    ``source`` names where they are defined (a file, a study); merging the same source
    again adds nothing. Returns the names added. ValueError if a name is already defined
    by another source (a name is defined once), or an entry is malformed.
    """
    if source in _SOURCES.values():
        return []
    new = {name: _quantity(name, e, source) for name, e in (entries or {}).items()}
    twice = {n: _SOURCES[n] for n in new if n in GLOSSARY}
    if twice:
        where = ", ".join(f"{n} (already in {s})" for n, s in twice.items())
        raise ValueError(f"{source}: {where} defined twice in the glossary")
    for name, q in new.items():
        _Q.append(q)
        GLOSSARY[name] = q
        _SOURCES[name] = source
    return list(new)


def merge_file(path: str | Path) -> list:
    """Add a glossary file's ``quantities`` (see :func:`merge`; its source is its path)."""
    return merge(read(path).get("quantities"), str(Path(path).resolve()))


merge(_TABLES["quantities"], str(DATA))
for _path in STUDY_FILES:
    merge_file(_path)


def lookup(name: str) -> Quantity:
    """The quantity named ``name`` (direct or composed); KeyError if not in the glossary."""
    if name in GLOSSARY:
        return GLOSSARY[name]
    for suffix, (lab, text) in SUFFIXES.items():
        if name.endswith(suffix) and name[: -len(suffix)] in GLOSSARY:
            q = GLOSSARY[name[: -len(suffix)]]
            return Quantity(name, q.unit, q.label + lab, text.format(q.definition), q.kind)
    for prefix, (before, after, text) in PREFIXES.items():
        if name.startswith(prefix) and name not in RETIRED:
            try:
                q = lookup(name[len(prefix):])
            except KeyError:
                continue
            return Quantity(name, q.unit, before + q.label + after,
                            text.format(q.definition[0].lower() + q.definition[1:]), q.kind)
    raise KeyError(f"{name!r} is not in the glossary of quantities (lunarcap.quantities)")


def is_known(name: str) -> bool:
    """True if ``name`` is a glossary quantity (directly or composed)."""
    try:
        lookup(name)
    except KeyError:
        return False
    return True


def unknown(names) -> list:
    """The names of ``names`` that are not in the glossary, in order."""
    return [n for n in names if not is_known(n)]


def capture_name(key: str) -> str:
    """The glossary name of a capture (:data:`CAPTURES`), e.g. "the paper's fixed timings".

    >>> capture_name("free")
    'free ignitions'
    """
    return CAPTURES[key][0]
