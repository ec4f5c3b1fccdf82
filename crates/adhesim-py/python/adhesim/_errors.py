"""The fields of ``adhesim.ScenarioError``, documented on the class: the Rust extension
sets them on each raised instance (``src/convert.rs``, ``scenario_error``)."""

from __future__ import annotations

from typing import Any, Optional

from ._adhesim import ScenarioError


class _Field:
    """A field read from the instance (set when raised); None on an instance without it."""

    def __init__(self, name: str, doc: str) -> None:
        self.name = name
        self.__doc__ = doc

    def __get__(self, instance: Any, owner: Optional[type] = None) -> Any:
        if instance is None:
            return self
        return instance.__dict__.get(self.name)


_FIELDS = {
    "key": (
        "The dotted scenario key at fault (``grid.n``), or None when no single key is (a syntax "
        "error, a quantity derived from several keys that the message names). The checks of a "
        "sweep's own tables (``adhesim.sweep``'s ``vary``, ``zip``, ``random``, ``derived``, or a "
        "sweep file) give the sweep file's key, a TOML dotted key quoted where it holds a dot: "
        "``random.seed``, ``random.cases``, ``vary.alpha``, ``zip.\"grid.n\"`` (a list that is "
        "empty, no list, or of another length; a key given twice), "
        "``random.\"grid.size\".min`` (``.max``, ``.scale``: a range), ``derived.alpha``; a "
        "case's value of a scenario key keeps the scenario key (``grid.n``)."
    ),
    "value": (
        "The value at fault as written (``-4``, ``\"many\"``; a file key's path; a derived "
        "quantity's own value), or None (a missing key)."
    ),
    "requirement": "What the value must satisfy (``>= 2``; when a missing key is required), or None where unknown.",
    "kind": "syntax, unknown_key, missing_key, invalid_value, file or resources.",
}
for _name, _doc in _FIELDS.items():
    setattr(ScenarioError, _name, _Field(_name, _doc))
