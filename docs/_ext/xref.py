# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Resolve cross-references to re-exported names (``warptrunc.truncate``) and short names.

Each public object is documented once, at its home (``docs/_ext/apigen.py``); a reference to
another name that exports it (``:func:`warptrunc.truncate```, ``:class:`warptrunc.Surface```)
or to a short name that names exactly one documented object (```Surface```, ```to_dict```
inside a class) is resolved to that page here, instead of being left as a broken link.
"""

from __future__ import annotations

ALIASES: dict[str, str] = {}


def set_aliases(exports, home, objects) -> None:
    """Record every exported qualified name that is not the object's home."""
    for qual, obj in objects.items():
        target = home.get(id(obj))
        if target and target != qual:
            ALIASES[qual] = target


def _candidates(env, node) -> list[str]:
    target = node["reftarget"].lstrip("~.")
    mod = node.get("py:module") or ""
    cls = node.get("py:class") or ""
    names = [target]
    if cls:
        names.append(f"{mod}.{cls}.{target}")
    if mod:
        names.append(f"{mod}.{target}")
        parts = mod.split(".")
        for i in range(len(parts) - 1, 0, -1):
            names.append(".".join(parts[:i]) + "." + target)
    out = []
    for n in names:
        out.append(ALIASES.get(n, n))
        # an attribute of a re-exported class: warptrunc.Surface.heights
        head, _, tail = n.rpartition(".")
        if head in ALIASES:
            out.append(f"{ALIASES[head]}.{tail}")
    # a short name that names exactly one documented object
    objs = env.get_domain("py").objects
    suffix = "." + target
    hits = {k for k in objs if k.endswith(suffix)}
    if len(hits) == 1:
        out.append(hits.pop())
    elif cls and mod:  # a method/attribute of the class being documented
        own = [k for k in hits if k.startswith(f"{mod}.{cls}.")]
        out.extend(own[:1])
    return out


def missing_reference(app, env, node, contnode):
    """``missing-reference`` handler: try the aliases and unique short names."""
    if node.get("refdomain") != "py":
        return None
    domain = env.get_domain("py")
    objs = domain.objects
    for cand in _candidates(env, node):
        if cand in objs:
            newnode = node.deepcopy()
            newnode["reftarget"] = cand
            res = domain.resolve_any_xref(env, node["refdoc"], app.builder, cand, newnode,
                                          contnode)
            for role, ref in res:
                return ref
    return None


def setup(app):
    app.connect("missing-reference", missing_reference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
