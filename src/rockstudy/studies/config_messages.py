"""At most three lines for a config key pydantic refuses: the key path, the value, what is allowed and, for
an unknown key, the closest known one (:func:`message`). The config's models are in
:mod:`rockstudy.studies.config_model`, which words its errors with these.
"""
from __future__ import annotations

import difflib

from pydantic import BaseModel, ValidationError


class KeyRelationError(ValueError):
    """A relation between config keys does not hold; the message names the keys (``"convergence.noise_level:
    'R002' is not one of noise_levels (R000, R001)"``) and is given as it is."""


def _short(value, width: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= width else text[:width - 3] + "..."


_TYPE_TAGS = ("str", "int", "float", "bool", "dict", "list", "none", "literal", "union", "function", "constrained",
              "lax", "strict", "json", "tagged")


def _path(loc, model_names=()) -> str:
    """``a.b[0].c`` from a pydantic location, without pydantic's union tags."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif "[" in str(part) or str(part) in model_names or str(part).split("-")[0] in _TYPE_TAGS:
            continue
        else:
            out += f".{part}" if out else str(part)
    return out or "config"


def _model_at(model, loc):
    """The section model at a location (for the known keys of an unknown one), or None."""
    for part in loc:
        field = model.model_fields.get(part) if isinstance(part, str) else None
        if field is None:
            return None
        ann = field.annotation
        for arg in (ann, *getattr(ann, "__args__", ())):
            if isinstance(arg, type) and issubclass(arg, BaseModel):
                model = arg
                break
        else:
            return None
    return model


def message(error: ValidationError, model=None, prefix: str = "", model_names=()) -> str:
    """At most three lines for the first error of ``error``: the key path, the value, what is allowed and,
    for an unknown key, the closest known one.

    The first error is the one deepest in the config (pydantic reports one per branch of a union).

    Parameters
    ----------
    error : pydantic.ValidationError
        The error pydantic raised for a config.
    model : type of pydantic.BaseModel, optional
        The model the config was checked against, which lists the known keys next to an unknown one;
        None: no hint.
    prefix : str, optional
        Text put before the key path (``"config.yaml: "``).
    model_names : collection of str, optional
        The models' class names, which pydantic puts into the location of an error inside a union (left out
        of the key path).
    """
    errors = error.errors(include_url=False)
    first = max(errors, key=lambda e: len([p for p in e["loc"] if not str(p).startswith(_TYPE_TAGS)]))
    loc = first["loc"]
    path = prefix + _path(loc, model_names)
    if first["type"] == "extra_forbidden":
        known = sorted(_model_at(model, loc[:-1]).model_fields) if model is not None and _model_at(
            model, loc[:-1]) is not None else []
        close = difflib.get_close_matches(str(loc[-1]), known, n=1)
        hint = f"; did you mean `{close[0]}`?" if close else ""
        listing = f"\nknown keys here: {', '.join(known)}" if known and len(", ".join(known)) < 200 else ""
        return f"{path}: unknown key{hint}{listing}"
    if first["type"] == "missing":
        return f"{path}: the key is missing (required)"
    if first["type"] == "value_error" and isinstance(first.get("ctx", {}).get("error"), KeyRelationError):
        return prefix + str(first["ctx"]["error"])  # a relation between keys, worded by the model's validator
    text = f"{path} = {_short(first.get('input'))} is not allowed: {first['msg']}"
    if len(errors) > 1:
        text += f"\n({len(errors) - 1} more problem(s) after this one)"
    return text
