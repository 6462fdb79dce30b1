"""A case's validation errors as one line: the first error of pydantic's ValidationError becomes one
:class:`~viscontact.errors.ParameterError` naming the dotted case-file key, the allowed range or values
with their unit and, for an unknown key, the closest valid one (:func:`parameter_error`, raised by
:meth:`viscontact.io.case.Case.from_toml_text`)."""
from __future__ import annotations

import difflib
import typing
from collections.abc import Mapping, Sequence
from typing import Any

from pydantic import BaseModel, ValidationError

from viscontact.errors import ParameterError

__all__ = ["closest", "model_of", "parameter_error"]


def closest(name: str, valid: Sequence[str]) -> str | None:
    """The entry of ``valid`` closest to a mistyped ``name`` (difflib ratio >= 0.6), else None."""
    close = difflib.get_close_matches(name, list(valid), n=1, cutoff=0.6)
    return close[0] if close else None


def model_of(annotation: Any) -> type[BaseModel] | None:
    """The pydantic model in a field annotation (through Optional/Annotated), if any."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = model_of(arg)
        if found is not None:
            return found
    return None


def _resolve(loc: tuple, root: type[BaseModel], materials: Mapping[str, type[BaseModel]]
             ) -> tuple[list[str], type[BaseModel] | None, Any]:
    """Dotted key parts, the model holding the key and the key's FieldInfo (None when unknown), from
    the model ``root`` down.

    The discriminator tag pydantic puts after ``material`` (``material.zener.x``) is dropped from
    the key and selects the material model of ``materials`` (tag -> model).
    """
    loc = list(loc)
    material_model = None
    if len(loc) >= 2 and loc[0] == "material" and loc[1] in materials:
        material_model = materials[loc.pop(1)]
    parts: list[str] = []
    model: type[BaseModel] | None = root
    parent, info = None, None
    for item in loc:
        if isinstance(item, int):  # index into an array: keep the array's FieldInfo
            parts[-1] = f"{parts[-1]}[{item}]"
            model = None
            continue
        parts.append(str(item))
        parent = model
        info = model.model_fields.get(item) if model is not None else None
        if model is root and item == "material":
            model = material_model
        else:
            model = model_of(info.annotation) if info is not None else None
    return parts, parent, info


def _kind(value: Any) -> str:
    names = {bool: "a boolean", int: "an integer", float: "a number", str: "a string", list: "an array",
             dict: "a table"}
    return names.get(type(value), type(value).__name__)


def _unit(info: Any) -> str:
    extra = getattr(info, "json_schema_extra", None) or {}
    unit = extra.get("unit", "") if isinstance(extra, dict) else ""
    return f" {unit}" if unit else ""


def _paren(unit: str) -> str:
    return f" ({unit.strip()})" if unit else ""


def _describe(err: dict, info: Any, key: str, parent: type[BaseModel] | None, materials: Sequence[str]) -> str:
    """The message of the pydantic error ``err`` at ``key`` (FieldInfo ``info``, in model ``parent``;
    ``materials``: the material types)."""
    kind, ctx, value = err["type"], err.get("ctx", {}), err.get("input")
    unit = _unit(info)
    bounds = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}
    if kind in bounds:
        limit = next(iter(ctx.values()))
        return f"must be {bounds[kind]} {limit:g}{unit}, got {value!r}"
    if kind == "missing":
        if info is not None and model_of(info.annotation) is not None:
            return f"required section [{key}] is missing"
        return "required key is missing"
    if kind == "extra_forbidden":
        name = key.rsplit(".", 1)[-1]
        valid = sorted(parent.model_fields) if parent is not None else []
        close = closest(name, valid)
        hint = f"did you mean '{close}'? " if close else ""
        return f"unknown key; {hint}valid keys here: {', '.join(valid)}"
    if kind == "literal_error":
        return f"must be one of {ctx.get('expected')}, got {value!r}"
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        allowed = ", ".join(repr(t) for t in materials)
        got = f", got {ctx.get('tag')!r}" if kind == "union_tag_invalid" else " (missing)"
        return f"must be one of {allowed}{got}"
    if kind == "finite_number":
        return f"must be a finite number{_paren(unit)}, got {value!r}"
    if kind in ("int_type", "int_from_float", "int_parsing"):
        return f"must be an integer, got {_kind(value)} {value!r}"
    if kind in ("float_type", "float_parsing"):
        return f"must be a number{_paren(unit)}, got {_kind(value)} {value!r}"
    if kind in ("string_type", "str_type"):
        return f"must be a string, got {_kind(value)} {value!r}"
    if kind == "list_type":
        return f"must be an array, got {_kind(value)} {value!r}"
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return f"must be a table ([{key}] section), got {_kind(value)} {value!r}"
    return err["msg"]


def parameter_error(exc: ValidationError, root: type[BaseModel], materials: Mapping[str, type[BaseModel]]
                    ) -> ParameterError:
    """The first error of a pydantic ValidationError of the model ``root`` (the case) as a ParameterError
    naming the dotted key; ``materials``: the material types (tag -> model) of its ``[material]``."""
    errors = exc.errors()
    # an unknown key first: it usually explains the "missing" error that comes with it (typos)
    err = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
    original = err.get("ctx", {}).get("error")
    if isinstance(original, ParameterError):
        return original
    loc = tuple(err["loc"])
    if err["type"] in ("union_tag_invalid", "union_tag_not_found"):
        loc = loc + ("type",)
    parts, parent, info = _resolve(loc, root, materials)
    key = ".".join(parts) or "case file"
    message = _describe(err, info, key, parent, tuple(materials))
    if len(errors) > 1:
        message += f" (and {len(errors) - 1} more problem{'s' if len(errors) > 2 else ''})"
    return ParameterError(key, message)
