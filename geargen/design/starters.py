"""Starter designs for ``geargen new KIND FILE.toml``: complete, commented design files that build.

Each starter is data (:class:`Starter`: tables of keys, values and the reason for each value
that needs one), held by its drive kind (``geargen/drives/<kind>/starter.py``, one metric and
one inch, :attr:`geargen.drives.kind.DriveKind.starters`); :func:`starter_text` writes it as
TOML, every key followed by its meaning and unit from the schema
(:func:`geargen.design.schema.key_comment`), so the comments cannot disagree with what
``load_design`` reads. Every starter passes ``geargen check`` and builds (tests/test_new.py).
"""

from __future__ import annotations

import json
import textwrap
from dataclasses import dataclass
from typing import Any

from geargen.design.schema import key_comment
from geargen.design.validate import key_schema

#: where the value's comment starts (wider keys push it right)
COMMENT_COLUMN = 40
LINE_WIDTH = 100


@dataclass(frozen=True)
class Key:
    """One key of a starter: its value, and why this value (empty when the meaning says it all)."""

    key: str
    value: Any
    why: str = ""


@dataclass(frozen=True)
class Table:
    """``[header]`` (``""``: the top-level keys) with a note above it and its keys."""

    header: str
    keys: tuple[Key, ...]
    note: str = ""


@dataclass(frozen=True)
class Starter:
    """A starter design of drive ``kind`` in ``units`` (``"mm"`` or ``"in"``)."""

    kind: str
    summary: str
    intro: str
    tables: tuple[Table, ...]
    units: str = "mm"

    @property
    def command(self) -> str:
        """The ``geargen new`` command that writes it."""
        return f"geargen new {self.kind}" + ("" if self.units == "mm" else f" --units {self.units}")


# ---------------------------------------------------------------- writing


def toml_value(value: Any) -> str:
    """``value`` as TOML (numbers, strings, booleans and lists of them)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"no TOML form for {value!r}")


def _comment_lines(text: str, indent: str = "") -> list[str]:
    return [indent + "# " + line for line in textwrap.wrap(text, LINE_WIDTH - len(indent) - 2)]


def starter_data(starter: Starter, name: str) -> dict[str, Any]:
    """The parsed form of ``starter`` named ``name`` (what ``tomllib`` reads back)."""
    data: dict[str, Any] = {"name": name}
    for table in starter.tables:
        target = data
        for part in table.header.split(".") if table.header else ():
            target = target.setdefault(part, {})
        for k in table.keys:
            target[k.key] = k.value
    return data


def starter_text(starter: Starter, name: str) -> str:
    """The commented TOML of ``starter`` with ``name = name``."""
    kind = starter.kind
    data = starter_data(starter, name)
    lines = [f"# {name}: {starter.summary}.", "#"]
    lines += _comment_lines(starter.intro)
    lines += ["#"] + _comment_lines(f"Written by `{starter.command}`. Each key's comment gives its meaning and "
                                    "[unit]; docs/design-files.md lists every key of every section. Try it: "
                                    f"geargen check {name}.toml, then geargen build {name}.toml.") + [""]
    top = Table("", (Key("name", name),) + starter.tables[0].keys) if starter.tables[0].header == "" else None
    for table in ([top] if top else []) + [t for t in starter.tables if t.header]:
        path = tuple(table.header.split(".")) if table.header else ()
        if table.note:
            lines += _comment_lines(table.note)
        if table.header:
            lines.append(f"[{table.header}]")
        for k in table.keys:
            schema = key_schema(data, path + (k.key,))
            if schema is None or not schema.help:
                raise KeyError(f"starter {kind}: {'.'.join(path + (k.key,))} has no schema with a meaning")
            if k.why:
                lines += _comment_lines(k.why)
            assignment = f"{k.key} = {toml_value(k.value)}"
            column = max(COMMENT_COLUMN, len(assignment) + 2)
            if LINE_WIDTH - column < 40:  # a long value: its meaning goes above it
                lines += _comment_lines(key_comment(schema, k.key))
                lines.append(assignment)
                continue
            comment = textwrap.wrap(key_comment(schema, k.key), LINE_WIDTH - column - 2)
            lines.append(f"{assignment:<{column - 1}} # {comment[0]}")
            lines += [" " * column + "# " + more for more in comment[1:]]
        lines.append("")
    return "\n".join(lines)


__all__ = ["Starter", "Table", "Key", "starter_text", "starter_data", "toml_value"]
