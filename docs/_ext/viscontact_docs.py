"""Sphinx directives that generate reference pages from the package itself.

``.. case-keys::``
    Every case-file key, section by section, from the pydantic models of :mod:`viscontact.io.case`:
    key, type or allowed values, unit (``json_schema_extra["unit"]`` of the field), default,
    allowed range (the field's ``gt``/``ge``/``lt``/``le`` constraints) and description (the
    field's ``description``; the section's docstring above each table).
``.. result-variables::``
    The variables of a result file, from :data:`viscontact.io.results.VARIABLES` and
    :data:`viscontact.io.results.SCALES`, then its coordinates (:data:`viscontact.io.results.COORDINATES`).
Docstrings
    Absolute values written as in the numerics, ``|q|``, ``|sigma_z - sigma_r|``, are kept as text
    (reST would read them as substitutions) outside inline literals and literal blocks.
``.. command-help::``
    The ``--help`` text of ``viscontact`` and then of each of its sub-commands, as the command
    prints them (:func:`viscontact.cli.main` with ``--help``; the sub-commands are read from the
    top-level help).

A key, variable or option added to the package appears in the documentation on the next build.
"""
from __future__ import annotations

import contextlib
import io
import os
import re
import typing
from typing import Any

import annotated_types
from docutils import nodes
from docutils.statemachine import StringList
from pydantic import BaseModel
from pydantic_core import PydanticUndefined
from sphinx.util.docutils import SphinxDirective


# --- case keys --------------------------------------------------------------------------------------
def _strip_optional(annotation: Any) -> Any:
    args = typing.get_args(annotation)
    if typing.get_origin(annotation) in (typing.Union, getattr(__import__("types"), "UnionType", None)):
        rest = [a for a in args if a is not type(None)]
        if len(rest) == 1:
            return rest[0]
    return annotation


def _models_in(annotation: Any) -> list[type[BaseModel]]:
    """Pydantic models in an annotation (several for a discriminated union)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    found: list[type[BaseModel]] = []
    for arg in typing.get_args(annotation):
        found += _models_in(arg)
    return found


def _type_name(annotation: Any) -> str:
    annotation = _strip_optional(annotation)
    origin = typing.get_origin(annotation)
    if origin is typing.Literal:
        return "one of " + ", ".join(f'``"{v}"``' if isinstance(v, str) else f"``{v!r}``"
                                     for v in typing.get_args(annotation))
    if origin is typing.Annotated:
        return _type_name(typing.get_args(annotation)[0])
    if origin is list:
        (item,) = typing.get_args(annotation) or (Any,)
        inner = _type_name(item)
        return f"array of {inner}" if not inner.startswith("one of") else f"array, each {inner}"
    if origin in (typing.Union, getattr(__import__("types"), "UnionType", None)):
        return " or ".join(_type_name(a) for a in typing.get_args(annotation) if a is not type(None))
    names = {float: "number", int: "integer", str: "string", bool: "boolean"}
    return names.get(annotation, getattr(annotation, "__name__", str(annotation)))


_BOUNDS = ((annotated_types.Gt, "gt", ">"), (annotated_types.Ge, "ge", "≥"),
           (annotated_types.Lt, "lt", "<"), (annotated_types.Le, "le", "≤"))


def _bounds(metadata: list[Any]) -> list[str]:
    out = []
    for item in metadata:
        for kind, attr, sign in _BOUNDS:
            if isinstance(item, kind):
                out.append(f"{sign} {getattr(item, attr):g}")
    return out


def _range(info: Any) -> str:
    """Allowed range of a field: its own bounds, else those of its array items."""
    bounds = _bounds(info.metadata)
    if not bounds:
        annotation = _strip_optional(info.annotation)
        if typing.get_origin(annotation) is list:
            (item,) = typing.get_args(annotation) or (Any,)
            if typing.get_origin(item) is typing.Annotated:
                inner = []
                for extra in typing.get_args(item)[1:]:
                    inner += _bounds(getattr(extra, "metadata", [extra]))
                bounds = [f"each {b}" for b in inner]
    return ", ".join(bounds)


def _unit(info: Any) -> str:
    extra = info.json_schema_extra if isinstance(info.json_schema_extra, dict) else {}
    unit = extra.get("unit", "")
    return unit if unit not in ("", "1") else "–"


def _default(info: Any) -> str:
    if info.default is PydanticUndefined and info.default_factory is None:
        return "**required**"
    value = info.default if info.default_factory is None else info.default_factory()
    if value is None:
        return "none"
    if isinstance(value, BaseModel):
        return ""
    if isinstance(value, str):
        return f'``"{value}"``'
    if isinstance(value, (list, tuple)):
        return "``[" + ", ".join(f'"{v}"' if isinstance(v, str) else repr(v) for v in value) + "]``"
    if isinstance(value, float):
        return f"``{value:g}``"
    return f"``{value!r}``"


def _cell(text: str) -> str:
    return " ".join(text.split()) or " "


def _plain(text: str) -> str:
    """Plain text (a field description, a long name) made literal for reST: no markup, no
    substitution (``|q|``), no reference (``name_``)."""
    text = re.sub(r"([\\|*`])", r"\\\1", text)
    return re.sub(r"(\w)_(?=\W|$)", r"\1\\_", text)


def _first_paragraph(doc: str | None) -> str:
    return " ".join((doc or "").strip().split("\n\n")[0].split())


def key_table(model: type[BaseModel], prefix: str) -> list[str]:
    """reST list-table of the leaf keys of ``model`` (sub-sections are left to the caller)."""
    rows = [".. list-table::", "   :header-rows: 1", "   :widths: 22 20 9 12 12 25", "",
            "   * - key", "     - type", "     - unit", "     - default", "     - range", "     - description"]
    nested_rows: list[list[str]] = []
    from viscontact.io.case import required_first

    for name, info in required_first(model):  # required keys first (material.type)
        nested = _models_in(info.annotation)
        if nested:  # a table inside a section ([indenter.roughness], normal.oscillation): its keys follow
            if prefix:  # (the sections themselves have their own parts)
                nested_rows.append(key_table(nested[0], f"{prefix}{name}.")[10:-1])  # rows only
            continue
        rows += [f"   * - ``{prefix}{name}``", f"     - {_cell(_type_name(info.annotation))}",
                 f"     - {_cell(_unit(info))}", f"     - {_cell(_default(info))}",
                 f"     - {_cell(_range(info))}", f"     - {_cell(_plain(info.description or ''))}"]
    return rows + [row for table in nested_rows for row in table] + [""]


def _heading(title: str, char: str) -> list[str]:
    return [title, char * len(title), ""]


def case_key_lines(root: type[BaseModel]) -> list[str]:
    """reST of the whole key reference: top-level keys, then one part per section."""
    lines = _heading("Top-level keys", "-") + key_table(root, "")
    for name, info in root.model_fields.items():
        models = _models_in(info.annotation)
        if not models:
            continue
        required = info.is_required()
        lines += _heading(f"[{name}]", "-")
        lines += [("Required section." if required else "Optional section (every key has a default)."), ""]
        if len(models) == 1:
            lines += [_first_paragraph(models[0].__doc__), ""] + key_table(models[0], f"{name}.")
            continue
        for model in models:  # a discriminated union: one table per variant
            tag = typing.get_args(model.model_fields["type"].annotation)[0]
            lines += _heading(f'{name}.type = "{tag}"', "~")
            lines += [_first_paragraph(model.__doc__), ""] + key_table(model, f"{name}.")
    return lines


class CaseKeys(SphinxDirective):
    """``.. case-keys::`` — the case-file key reference, generated from :class:`viscontact.io.case.Case`."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from viscontact.io.case import Case

        return self._parse(case_key_lines(Case))

    def _parse(self, lines: list[str]) -> list[nodes.Node]:
        container = nodes.section()
        container.document = self.state.document
        self.state.nested_parse(StringList(lines, source="<case-keys>"), self.content_offset, container,
                                match_titles=True)
        return container.children


# --- result variables -------------------------------------------------------------------------------
class ResultVariables(CaseKeys):
    """``.. result-variables::`` — the variables a result file may hold, with units."""

    def run(self) -> list[nodes.Node]:
        from viscontact.io import results

        rows = [".. list-table::", "   :header-rows: 1", "   :widths: 25 10 65", "",
                "   * - variable", "     - unit", "     - meaning"]
        for table, kind in ((results.VARIABLES, ""), (results.SCALES, ""), (results.COORDINATES, "coordinate: ")):
            for name, (unit, long_name) in table.items():
                rows += [f"   * - ``{name}``", f"     - {_cell(_plain(unit))}",
                         f"     - {_cell(kind + _plain(long_name))}"]
        return self._parse(rows + [""])


# --- command-line help ------------------------------------------------------------------------------
class CommandHelp(SphinxDirective):
    """``.. command-help::`` — ``viscontact --help``, then a heading and the ``--help`` of every sub-command."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        top = self._help([])
        out: list[nodes.Node] = [self._block(top)]
        for command in _subcommands(top):
            out += [nodes.rubric(text=f"viscontact {command}", ids=[f"command-{command}"]),
                    self._block(self._help([command]))]
        return out

    def _help(self, args: list[str]) -> str:
        from viscontact.cli import main

        text = io.StringIO()
        columns = os.environ.get("COLUMNS")
        os.environ["COLUMNS"] = "100"  # argparse wraps at the terminal width
        try:
            with contextlib.redirect_stdout(text):
                main([*args, "--help"])
        except SystemExit as done:
            if done.code not in (0, None):
                raise self.error(f"viscontact {' '.join(args)} --help exited with {done.code}") from None
        finally:
            if columns is None:
                os.environ.pop("COLUMNS", None)
            else:
                os.environ["COLUMNS"] = columns
        return text.getvalue()

    @staticmethod
    def _block(text: str) -> nodes.literal_block:
        block = nodes.literal_block(text, text)
        block["language"] = "text"
        return block


def _subcommands(top_help: str) -> list[str]:
    """Sub-command names listed under ``COMMAND`` in the top-level help of argparse."""
    names, inside = [], False
    for line in top_help.splitlines():
        if line.strip() == "COMMAND":
            inside = True
            continue
        if inside:
            match = re.match(r"^ {4}(\w[\w-]*)(\s|$)", line)
            if match:
                names.append(match.group(1))
            elif line and not line.startswith(" "):
                break
    return names


# --- docstrings --------------------------------------------------------------------------------------
_ABSOLUTE = re.compile(r"(?<![\\`|])\|(?=[^\s|])([^|\n]*?[^\s|\\])\|(?![`|_])")
_LITERAL = re.compile(r"(``.+?``)")


def escape_absolute_values(lines: list[str]) -> list[str]:
    r"""``|x|`` made literal text (``\|x\|``) in docstring lines, except in inline literals, in
    literal blocks (the lines indented under one ending in ``::``), tables and line blocks."""
    out: list[str] = []
    parent: int | None = None     # indent of the line that opened a literal block
    opened: int | None = None     # a line ending in "::" was seen at this indent
    for line in lines:
        indent = len(line) - len(line.lstrip())
        if line.strip():
            if opened is not None:
                parent, opened = (opened if indent > opened else None), None
            elif parent is not None and indent <= parent:
                parent = None
        literal = parent is not None or line.lstrip().startswith(("+", "| "))
        if not literal:
            line = "".join(part if part.startswith("``") else _ABSOLUTE.sub(r"\\|\1\\|", part)
                           for part in _LITERAL.split(line))
            if line.rstrip().endswith("::"):
                opened = indent
        out.append(line)
    return out


def _escape_docstring(app: Any, what: str, name: str, obj: Any, options: Any, lines: list[str]) -> None:
    lines[:] = escape_absolute_values(lines)


def setup(app: Any) -> dict[str, Any]:
    app.connect("autodoc-process-docstring", _escape_docstring)
    app.add_directive("case-keys", CaseKeys)
    app.add_directive("result-variables", ResultVariables)
    app.add_directive("command-help", CommandHelp)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
