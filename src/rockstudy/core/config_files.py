"""Config files as the library reads them: YAML with a bound on its nodes (aliases expanded) before anything
walks it, and overlays that replace the sections they give instead of merging into them.

The values' declarations (type, unit, range, size) are in :mod:`rockstudy.studies.config_model`; this module
only bounds a file's shape and applies an overlay, so that a config is never walked unbounded.
"""
from __future__ import annotations

import copy
import re
from collections.abc import Mapping

from rockstudy.core import limits
from rockstudy.core import validation as v
from rockstudy.core.validation import InputError

REPLACED_BY_OVERLAY = ("block", "noise_levels", "reproduction.readings", "beyond.fragility.records", "risk.scenarios",
                       "risk.hazard_curves", "risk.hazard_units")
"""Config keys whose value an overlay replaces whole instead of merging into: sections with alternatives
(a block by preset or by dimensions, a record set by suite or by list) and every mapping of names (noise
levels, readings, earthquake scenarios, hazard curves), so a name the overlay leaves out does not stay
(a test keeps this list equal to the config model's mappings of names)."""

MAX_NODES = limits.MAX_NODES
"""Most nodes of a config (:data:`rockstudy.core.limits.MAX_NODES`)."""


def replace_sections(config: dict, overlay: dict) -> dict:
    """Give ``config`` (already deep-merged with ``overlay``, as Snakemake merges a ``--configfile``) the
    overlay's own value of every key of :data:`REPLACED_BY_OVERLAY` it sets: an overlay's ``block:`` with
    dimensions replaces the preset instead of being merged into it. Returns ``config`` (changed in place).
    A YTE template (``__use_yte__: true``) is left to Snakemake's merge: its text is not the values it makes.

    Parameters
    ----------
    config : dict
        The merged config; the keys of :data:`REPLACED_BY_OVERLAY` that ``overlay`` sets are replaced in place.
    overlay : dict
        The overlay config file's own values, as read from it (before any merge).
    """
    if overlay.get("__use_yte__"):
        return config
    for path in REPLACED_BY_OVERLAY:
        *parents, key = path.split(".")
        src: object = overlay
        dst: object = config
        for part in parents:
            src, dst = (src.get(part) if isinstance(src, dict) else None), (
                dst.get(part) if isinstance(dst, dict) else None)
        if isinstance(src, dict) and key in src and isinstance(dst, dict):
            dst[key] = src[key]
    return config


def merge(config: dict, overlay: dict) -> dict:
    """Merge ``overlay`` into ``config`` as Snakemake merges a config over another: a mapping into the
    mapping at the same key, any other value (a copy) in place of the old one.

    Parameters
    ----------
    config : dict
        The config, changed in place.
    overlay : dict
        The values merged into it.

    Returns
    -------
    dict
        ``config``.
    """
    for key, value in overlay.items():
        if isinstance(value, dict) and isinstance(config.get(key), dict):
            merge(config[key], value)
        else:
            config[key] = copy.deepcopy(value)
    return config


def command_line_overlay(parsed, words=None) -> dict:
    """The overlay of Snakemake's ``--config KEY=VALUE ...``, its values typed as in a config file.

    Snakemake reads a mapping or a list given on the command line with YAML's ``BaseLoader``, which leaves
    every value in it a string (``block={width: 0.5}`` gives the width ``'0.5'``). Each such value is read
    again from its text in ``words`` (the ``KEY=VALUE`` words as given, Snakemake's
    ``workflow.config_settings.config_args``) as a config file is read (:func:`yaml.safe_load`), and the
    whole is bounded (:func:`count_nodes`). A plain value (a number, a word) is kept as Snakemake reads it.
    A number YAML 1.1 does not read as written (``010``, :data:`NOT_DECIMAL`) is refused, as in a config file
    (Snakemake reads ``free_time=010`` as 10, a file ``free_time: 010`` is 8). A key given twice is merged, as
    Snakemake merges it (:func:`merge`).

    Parameters
    ----------
    parsed : Mapping
        The command line's config as Snakemake parsed it (``workflow.config_settings.config``).
    words : str or sequence of str, optional
        The ``KEY=VALUE`` words as given; without them, ``parsed`` is taken as it is.

    Returns
    -------
    dict
        The overlay, to apply after the ``--configfile`` overlays (:func:`apply_command_line`).
    """
    import yaml
    parsed = dict(parsed or {})
    if isinstance(words, str):
        words = [words]
    if not words:
        overlay = copy.deepcopy(parsed)
    else:
        overlay = {}
        for word in words:
            key, _, text = str(word).partition("=")
            if key not in parsed:
                continue
            value = parsed[key]
            if isinstance(value, (Mapping, list)):
                try:
                    node = yaml.compose(text, Loader=yaml.SafeLoader)
                except yaml.YAMLError as exc:
                    raise InputError(f"--config {key}: not valid YAML: {getattr(exc, 'problem', None) or exc}"
                                     ) from None
                check_numbers(node, "--config", key, line=False)
                value = yaml.safe_load(text)
                count_nodes(value, name=f"--config {key}")
            elif isinstance(value, (int, float)) and not isinstance(value, bool) and NOT_DECIMAL.fullmatch(text):
                raise InputError(not_as_written(f"--config {key}", text))  # Snakemake read 010 as 10
            merge(overlay, {key: value})
    count_nodes(overlay, name="--config")
    return overlay


def apply_command_line(config: dict, overlay: dict) -> dict:
    """Apply the command line's overlay (:func:`command_line_overlay`) to ``config``, after the
    ``--configfile`` overlays, as Snakemake applies ``--config`` last: its typed values merged in
    (:func:`merge`; Snakemake merged them as text), then the sections of :data:`REPLACED_BY_OVERLAY` it sets
    replaced (:func:`replace_sections`).

    Parameters
    ----------
    config : dict
        The config Snakemake made (files and command line merged), changed in place.
    overlay : dict
        The command line's overlay.

    Returns
    -------
    dict
        ``config``.
    """
    return replace_sections(merge(config, overlay), overlay)


LONG_LISTS = {"beyond.fragility.records": v.MAX_SUITE_RECORDS}
"""Lists allowed more than :data:`~rockstudy.core.validation.MAX_LIST_ITEMS` entries, by key path."""


def count_nodes(value, limit: int = MAX_NODES, name: str = "config") -> int:
    """Nodes of a parsed config, aliases expanded, refused (:class:`InputError`) beyond ``limit`` as soon as
    the count passes it (the walk never visits more than ``limit`` nodes), and no list or mapping longer
    than :data:`~rockstudy.core.validation.MAX_LIST_ITEMS` entries (:data:`LONG_LISTS`), naming its key path.

    Parameters
    ----------
    value : dict, list or scalar
        The parsed config (or any part of it) to walk.
    limit : int, default MAX_NODES
        Most nodes allowed; the walk stops with :class:`InputError` as soon as the count passes it.
    name : str, default "config"
        What the messages call the config (a file name, say).
    """
    count, stack = 0, [(value, "")]
    while stack:
        node, path = stack.pop()
        count += 1
        if isinstance(node, (dict, list, tuple)):
            most = LONG_LISTS.get(path, v.MAX_LIST_ITEMS)
            if len(node) > most:
                v.fail(f"{name}: {path}" if path else name, f"{len(node)} entries",
                       f"at most {most} entries (each one multiplies the workflow's jobs, which Snakemake plans "
                       "before any runs)")
            count += len(node)
            if count > limit:
                raise InputError(f"{name}: more than {limit} values (YAML aliases expanded) is not allowed; a "
                                 "config this large is an alias bomb or not a config")
            if isinstance(node, dict):
                stack.extend((item, f"{path}.{k}" if path else str(k)) for k, item in node.items())
            else:
                stack.extend((item, f"{path}[{i}]") for i, item in enumerate(node))
    return count


NOT_DECIMAL = re.compile(r"[-+]?(0[0-7_]+|0o[0-7_]+|0x[0-9a-fA-F_]+|0b[01_]+"  # octal, hexadecimal, binary
                         r"|[0-9][0-9_]*(:[0-5]?[0-9])+(\.[0-9_]*)?)")  # sexagesimal
"""Numbers YAML 1.1 (PyYAML, Snakemake) does not read as written: ``010`` is octal 8, ``0x10`` 16, ``0b10`` 2
and ``1:30`` sexagesimal 90, while ``--config free_time=010`` and YAML 1.2 read 10 or text. A config file or
``--config`` value holding one is refused on both paths (:func:`check_numbers`): which number was meant cannot
be known, and a file read as one number by Snakemake and another elsewhere is read two ways."""

_NUMBER_TAGS = ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")


def not_as_written(where: str, text: str) -> str:
    """The message refusing the number ``text`` that YAML 1.1 does not read as written, at ``where`` (the file,
    line and key path, or the ``--config`` key): what each path would read and what to write instead.

    Parameters
    ----------
    where : str
        The place named first (``"my.yaml: line 3: free_time"``, ``"--config free_time"``).
    text : str
        The number as written (``"010"``).
    """
    import yaml
    as_yaml = yaml.safe_load(text)
    digits = text.replace("_", "")
    as_decimal = int(digits) if re.fullmatch(r"[-+]?[0-9]+", digits) else None
    readings = f"a config file reads it as {as_yaml!r} (YAML 1.1)"
    choices = [str(as_yaml)]
    if as_decimal is not None:
        readings += f", --config as {as_decimal}"
        choices.insert(0, str(as_decimal))
    return (f"{where}: {text} is not allowed: {readings}; write {' or '.join(dict.fromkeys(choices))} (decimal, "
            "without a leading zero), or quote it if it is text")


def check_numbers(node, name: str, prefix: str = "", line: bool = True) -> None:
    """Refuse (:class:`InputError`) the first number in a composed YAML document (:func:`yaml.compose`) that
    :data:`NOT_DECIMAL` matches, naming ``name``, its line and its key path (:func:`not_as_written`). A quoted
    value is text and is not refused. Each node is visited once, also when aliases repeat it.

    Parameters
    ----------
    node : yaml.Node or None
        The document's root node.
    name : str
        What the messages call the document (a file, ``--config block``).
    prefix : str, default ""
        The key path of ``node`` in the config (``"block"`` for ``--config block={...}``).
    line : bool, default True
        Name the line in the document (``"my.yaml: line 3: free_time"``); False for a one-line ``--config``
        value (``"--config block.width"``).
    """
    import yaml
    seen, stack = set(), [(node, prefix)]
    while stack:
        item, path = stack.pop()
        if item is None or id(item) in seen:
            continue
        seen.add(id(item))
        if isinstance(item, yaml.ScalarNode):
            if item.tag in _NUMBER_TAGS and NOT_DECIMAL.fullmatch(item.value):
                where = f"{name}: line {item.start_mark.line + 1}: {path or 'value'}" if line else f"{name} {path}"
                raise InputError(not_as_written(where, item.value))
        elif isinstance(item, yaml.MappingNode):
            for key, value in reversed(item.value):
                stack.append((value, f"{path}.{key.value}" if path else str(key.value)))
                stack.append((key, f"{path} (a key)" if path else "a key"))
        elif isinstance(item, yaml.SequenceNode):
            stack.extend((value, f"{path}[{i}]") for i, value in reversed(list(enumerate(item.value))))


def load_yaml(path, name: str | None = None) -> dict:
    """A YAML (or JSON) config file as a dict, refused when it is not a bounded mapping (:func:`count_nodes`),
    not a regular file of at most 1 MiB, not valid YAML, or holds a number YAML does not read as written
    (``010`` is octal 8 in YAML 1.1: :data:`NOT_DECIMAL`); the message names the file.

    Parameters
    ----------
    path : str or pathlib.Path
        The YAML or JSON file to read.
    name : str, optional
        What the messages call the file; ``str(path)`` when not given.
    """
    import yaml
    name = name or str(path)
    p = v.check_input_file(name, path, 2**20)
    try:
        with open(p, encoding="utf-8") as f:
            loader = yaml.SafeLoader(f)
            try:  # composed, its numbers checked as written, then built
                node = loader.get_single_node()
                check_numbers(node, name)
                data = None if node is None else loader.construct_document(node)
            finally:
                loader.dispose()
    except (yaml.YAMLError, UnicodeDecodeError) as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" (line {mark.line + 1})" if mark is not None else ""
        raise InputError(f"{name}: not valid YAML{where}: {getattr(exc, 'problem', None) or exc}") from None
    if not isinstance(data, dict):
        raise InputError(f"{name}: a config is a mapping of keys, got {type(data).__name__}")
    count_nodes(data, name=name)
    return data
