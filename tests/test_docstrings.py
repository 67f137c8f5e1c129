# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Every public function, class, method and property has a numpydoc docstring.

Public names are those in the ``__all__`` of ``warptrunc`` and of each of its modules and
subpackages (found with :func:`pkgutil.walk_packages`; ``warptrunc.kernels``, ``warptrunc.cli``
and private ``_modules`` are skipped), plus, for classes, the public methods and properties
defined in the package. Each object is validated once, under the module that defines it (or
the first public module that exports it, when it is defined in a private one), with
:func:`numpydoc.validate.validate`. Only these error codes fail the test:

- ``GL08`` no docstring: the object has no documentation at all.
- ``SS01`` no summary: autosummary tables and ``help()`` show the summary line first.
- ``SS03`` summary without a final period: the summary is a sentence; autosummary cuts at
  the first period, so a missing one runs the summary into the extended description.
- ``PR01`` a parameter is not documented: callers need its meaning, shape and unit (m, Pa, ...).
- ``PR02`` an unknown parameter is documented: stale text after a rename or removal.
- ``RT01`` no Returns section although the function returns a value (numpydoc skips functions
  whose body has no ``return <value>``; properties are exempt): the result's type, shape and
  unit are half of the contract.

Style codes (``SS05`` infinitive verb, ``SS06`` one-line summary, ``PR04``/``PR06`` types,
``SA01`` See Also, ``EX01`` Examples, ...) are left to review: they would fail many correct
docstrings without telling a reader anything new.

Properties are checked for ``GL08`` only (their summary is their documentation). Dataclasses
are checked for ``GL08``, ``SS01`` and ``SS03``; their constructor parameters are the fields,
and each field must have an attribute docstring (a string literal right after the field,
the house style for result objects), read from the source with :mod:`ast`.

Besides, every public function, method and class whose signature takes parameters (beyond
``self``/``cls``) has a ``Parameters`` section (parsed with :mod:`numpydoc.docscrape`; for a
class, in its docstring or its ``__init__``'s), or, for a dataclass, documents each of its
constructor parameters as a field (an attribute docstring, or the description of a
:func:`~warptrunc.params.param` field): ``test_parameters_documented``. Exception classes
whose constructor is the built-in one (a message) are exempt.
"""

from __future__ import annotations

import ast
import dataclasses
import functools
import importlib
import inspect
import itertools
import textwrap

import pytest

numpydoc_validate = pytest.importorskip("numpydoc.validate")
numpydoc_docscrape = pytest.importorskip("numpydoc.docscrape")


from warptrunc._support.public import SKIP_PREFIXES, public_modules  # noqa: E402

FUNCTION_CODES = frozenset({"GL08", "SS01", "SS03", "PR01", "PR02", "RT01"})
CLASS_CODES = frozenset({"GL08", "SS01", "SS03", "PR01", "PR02"})
DATACLASS_CODES = frozenset({"GL08", "SS01", "SS03"})
PROPERTY_CODES = frozenset({"GL08"})


def _is_private_module(modname: str) -> bool:
    return any(part.startswith("_") for part in modname.split("."))


def _home(obj: object, exported_as: str) -> str:
    """Qualified name to validate an object under: where it is defined, if that is public,
    else the public package closest to its private module (``warptrunc.fractal.FractalFit``
    for ``warptrunc.fractal._common.FractalFit``)."""
    mod = getattr(obj, "__module__", None) or ""
    qual = getattr(obj, "__qualname__", "")
    if "<" in qual:
        return exported_as
    if not _is_private_module(mod):
        return f"{mod}.{qual}"
    parts = mod.split(".")
    while parts and _is_private_module(".".join(parts)):
        parts.pop()
    package = importlib.import_module(".".join(parts))
    if getattr(package, qual, None) is obj:
        return f"{package.__name__}.{qual}"
    return exported_as


def _members(cls: type, cls_name: str) -> list[tuple[str, str]]:
    """(qualified name, kind) of the public methods and properties a class defines."""
    out = []
    for klass in cls.__mro__:
        if not (getattr(klass, "__module__", "") or "").startswith("warptrunc"):
            continue
        owner = cls_name if klass is cls or klass.__name__.startswith("_") else None
        if owner is None:
            owner = _home(klass, cls_name)
        for attr, value in vars(klass).items():
            if attr.startswith("_"):
                continue
            if isinstance(value, property | functools.cached_property):
                out.append((f"{owner}.{attr}", "property"))
            elif isinstance(value, staticmethod | classmethod) or inspect.isfunction(value):
                out.append((f"{owner}.{attr}", "function"))
    return out


def _dataclass_fields(cls: type, cls_name: str) -> list[tuple[str, str]]:
    own = {f.name for f in dataclasses.fields(cls)}
    return [(f"{cls_name}.{name}", "field") for name in sorted(own) if not name.startswith("_")]


def _collect() -> dict[str, str]:
    """Map qualified name -> kind ("function", "class", "dataclass", "property", "field")."""
    found: dict[str, str] = {}
    for modname in public_modules():
        module = importlib.import_module(modname)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if not (getattr(obj, "__module__", "") or "").startswith("warptrunc"):
                continue  # constants, re-exported third-party objects
            if inspect.isclass(obj):
                qual = _home(obj, f"{modname}.{name}")
                if qual in found:
                    continue
                if dataclasses.is_dataclass(obj):
                    found[qual] = "dataclass"
                    found.update(_dataclass_fields(obj, qual))
                else:
                    found[qual] = "class"
                found.update((q, k) for q, k in _members(obj, qual) if q not in found)
            elif callable(obj):
                found.setdefault(_home(obj, f"{modname}.{name}"), "function")
    return dict(sorted(found.items()))


PUBLIC = _collect()


def _resolve(qualname: str) -> tuple[object, list[str]]:
    parts = qualname.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        rest = parts[i:]
        for part in rest:
            obj = getattr(obj, part)
        return obj, rest
    raise ImportError(qualname)


@functools.cache
def _field_docstrings(cls: type) -> frozenset[str]:
    """Names of the annotated class attributes followed by a string literal, over the MRO."""
    names: set[str] = set()
    for klass in cls.__mro__:
        try:
            source = textwrap.dedent(inspect.getsource(klass))
        except (OSError, TypeError):
            continue
        body = ast.parse(source).body[0].body
        for stmt, nxt in itertools.pairwise(body):
            if (
                isinstance(stmt, ast.AnnAssign)
                and isinstance(stmt.target, ast.Name)
                and isinstance(nxt, ast.Expr)
                and isinstance(nxt.value, ast.Constant)
                and isinstance(nxt.value.value, str)
                and nxt.value.value.strip()
            ):
                names.add(stmt.target.id)
    return frozenset(names)


def _field_doc_problem(cls: type, field: str) -> str | None:
    """Why a dataclass field is undocumented, or None when it is documented: a parameter field
    (:func:`~warptrunc.params.param`) by its description, any other by an attribute
    docstring."""
    meta = {f.name: f.metadata for f in dataclasses.fields(cls)}.get(field, {})
    if "warptrunc" in meta:  # a parameter field: its description is the param() metadata
        return None if meta["warptrunc"].doc.strip() else "parameter without a description"
    if field in _field_docstrings(cls):
        return None
    return (
        "GL08 dataclass field has no attribute docstring "
        "(a string literal on the line after the field)"
    )


@pytest.mark.parametrize("qualname", list(PUBLIC), ids=str)
def test_numpydoc(qualname: str) -> None:
    kind = PUBLIC[qualname]
    if kind == "field":
        cls_name, field = qualname.rsplit(".", 1)
        cls, _ = _resolve(cls_name)
        problem = _field_doc_problem(cls, field)
        assert problem is None, f"{qualname}: {problem}"
        return
    codes = {
        "function": FUNCTION_CODES,
        "class": CLASS_CODES,
        "dataclass": DATACLASS_CODES,
        "property": PROPERTY_CODES,
    }[kind]
    result = numpydoc_validate.validate(qualname)
    errors = [(code, msg) for code, msg in result["errors"] if code in codes]
    assert not errors, f"{qualname} ({kind}):\n" + "\n".join(
        f"  {code}: {msg}" for code, msg in errors
    )


CALLABLES = [q for q, kind in PUBLIC.items() if kind in ("function", "class", "dataclass")]


def _parameters(obj: object) -> list[str] | None:
    """The names a callable's signature takes beyond ``self``/``cls``; None for an exception
    class with the built-in constructor (no signature to read: it takes the message)."""
    try:
        sig = inspect.signature(obj)
    except ValueError:
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            return None
        raise
    return [name for name in sig.parameters if name not in ("self", "cls")]


def _has_parameters_section(obj: object) -> bool:
    """Whether numpydoc finds a non-empty Parameters section in the docstring (for a class,
    its own or its ``__init__``'s)."""
    docs = [inspect.getdoc(obj) or ""]
    if inspect.isclass(obj) and "__init__" in vars(obj):
        docs.append(inspect.getdoc(vars(obj)["__init__"]) or "")
    return any(numpydoc_docscrape.NumpyDocString(doc)["Parameters"] for doc in docs)


@pytest.mark.parametrize("qualname", CALLABLES, ids=str)
def test_parameters_documented(qualname: str) -> None:
    """A public callable that takes parameters documents them in a Parameters section, or, a
    dataclass, as its fields (each constructor parameter a documented field)."""
    obj, _ = _resolve(qualname)
    names = _parameters(obj)
    if not names or _has_parameters_section(obj):
        return
    assert PUBLIC[qualname] == "dataclass", (
        f"{qualname}: no Parameters section, although it takes {', '.join(names)}"
    )
    fields = {f.name for f in dataclasses.fields(obj)}
    problems = [
        f"{name}: " + ("not a field" if name not in fields else _field_doc_problem(obj, name))
        for name in names
        if name not in fields or _field_doc_problem(obj, name) is not None
    ]
    assert not problems, (
        f"{qualname}: no Parameters section, and parameters not documented as fields:\n  "
        + "\n  ".join(problems)
    )


def test_collects_the_api() -> None:
    """The walk finds the top-level API and the subpackages' names (guards an empty test)."""
    assert len(PUBLIC) > 200
    assert "warptrunc.stiffness.curve.stiffness_curve" in PUBLIC  # under its defining module
    assert PUBLIC["warptrunc.stiffness.curve.StiffnessCurve"] == "dataclass"
    assert PUBLIC["warptrunc.material.Material.contact_modulus"] == "property"
    assert not any(q.startswith(SKIP_PREFIXES) for q in PUBLIC)
    assert len(CALLABLES) > 350
    assert "warptrunc.contact.solver.ContactSolver.solve" in CALLABLES
    assert "warptrunc.indent.protocol.IndentProtocol" in CALLABLES  # documents its fields
