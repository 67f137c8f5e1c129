# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared checks of the command line for the tests (not a test module)."""

from warptrunc.cli import main

__all__ = ["assert_refused_in_one_line"]


def assert_refused_in_one_line(args, out, capsys, needles) -> None:
    """``warptrunc ARGS --out OUT`` exits 2 with one stderr line holding every needle, and
    writes no OUT."""
    import pytest

    with pytest.raises(SystemExit) as e:
        raise SystemExit(main([*args, "--out", str(out)]))
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    for n in needles:
        assert n in err, (n, err)
    assert not out.exists()
