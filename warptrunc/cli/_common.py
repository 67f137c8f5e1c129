# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared pieces of the sub-commands: the hand-written options, argument groups (surface
source, device, output folder) and argparse ``type=`` validators (the help formatter and the
parser class are in :mod:`warptrunc.cli._parser`).

Options
-------
An option that says *what is computed* is generated from a field of a parameter object
(:func:`warptrunc.params.add_options`: its default, unit, range and help in one place). Only
the options that say *where it runs and where it goes* (``--device``, ``--devices``,
``--workers``, ``--scheduler``, ``--out``, ``--no-plot``, ``--no-progress``, ``--overwrite``,
...) and *which source* is read (``--input``, ``--preset``) are written by hand, here, each
through :func:`shared_option`; ``tests/test_cli_fields.py`` checks every option of every
sub-command against that rule.

Validators
----------
Every numeric or path option should be declared with one of the validators below as its
``type=``, so that bad input stops while the command line is parsed, with one line that names
the option, the value and the allowed range, and exit status 2::

    warptrunc analyze: error: argument --Rt: must be in (0, inf) m, got '-1'

=======================================  ===================================================
validator                                accepts
=======================================  ===================================================
``real(lo, hi, lo_open=, hi_open=,       a finite float in the interval (``None`` = no bound;
unit=, allow_inf=)``                     NaN always refused, ±inf only with ``allow_inf``)
``positive(unit)``                       a finite float > 0
``fraction(lo_open=True)``               a float in (0, 1] (or [0, 1])
``integer(lo, hi=None)``                 an integer in [lo, hi] (no "2.5", no "1e3")
``odd_integer(lo)``                      an odd integer ≥ lo
``input_file``                           an existing regular file (not a folder)
``output_file``                          a path that is not a folder and whose nearest existing
                                         parent is a writable folder
``output_dir``                           a path that is a folder or can be created as one
                                         (not an existing file, writable parent)
=======================================  ===================================================

They raise :class:`argparse.ArgumentTypeError`, which argparse reports as
``argument --OPTION: MESSAGE``. Checks that need several options or the surface (``--depths``
up to R_t, LO < HI of a window) belong in ``run`` and raise ``ValueError`` naming the option;
:func:`warptrunc.cli.main` turns ``ValueError``, ``MemoryError`` and ``OSError`` into the same
one-line message with exit status 2. New sub-commands get all of this by importing from here.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .._support.messages import show
from .._support.validate import MAX_INCREMENTS
from ..material import Material
from ..params import add_options, from_args
from ..presets import PRESETS
from ..wm_params import WMSpec
from ._paths import input_file, output_dir, output_file

if TYPE_CHECKING:
    from ..surface import Surface

SHARED = "warptrunc_shared"
"""Attribute set on every hand-written option's argparse action (:func:`shared_option`)."""


def shared_option(p: Any, *flags: str, **kw: Any) -> argparse.Action:
    """A hand-written option (where it runs, where it goes, which source), tagged as such.

    Parameters
    ----------
    p : argparse.ArgumentParser or argument group
        Where the option goes.
    *flags : str
        Its option strings (``"--device"``).
    **kw
        As for :meth:`argparse.ArgumentParser.add_argument`.

    Returns
    -------
    argparse.Action
        The option's action.
    """
    action = p.add_argument(*flags, **kw)
    setattr(action, SHARED, True)
    return action


# --- validators for ``type=`` -----------------------------------------------------------------


def _interval(lo, hi, lo_open: bool, hi_open: bool) -> str:
    lo_s = "-inf" if lo is None else f"{lo:g}"
    hi_s = "inf" if hi is None else f"{hi:g}"
    return f"{'(' if lo_open or lo is None else '['}{lo_s}, {hi_s}{')' if hi_open or hi is None else ']'}"


def real(
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = True,
    hi_open: bool = True,
    unit: str = "",
    allow_inf: bool = False,
):
    """A ``type=`` for a float in an interval.

    Parameters
    ----------
    lo, hi : float, optional
        Bounds (None: unbounded on that side).
    lo_open, hi_open : bool
        Exclude the bound itself (default: both open).
    unit : str
        Unit named in the message (e.g. ``"m"``, ``"Pa"``, ``"(fraction of R_t)"``).
    allow_inf : bool
        Accept ``inf`` (e.g. the modulus of a rigid flat) when the interval reaches it;
        the interval is then shown closed at inf.

    Returns
    -------
    callable
        ``parse(text) -> float``, raising :class:`argparse.ArgumentTypeError` with the allowed
        interval and the value given. NaN is always refused.
    """
    rng = _interval(lo, hi, lo_open, hi_open)
    if allow_inf and hi is None:
        rng = rng[:-1] + "]"
    u = f" {unit}" if unit else ""

    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"must be a number in {rng}{u}, got {show(text)}"
            ) from None
        bad = math.isnan(v) or (math.isinf(v) and not (allow_inf and v > 0))
        if lo is not None:
            bad |= v <= lo if lo_open else v < lo
        if hi is not None:
            bad |= v >= hi if hi_open else v > hi
        if bad:
            raise argparse.ArgumentTypeError(f"must be in {rng}{u}, got {show(text)}")
        return v

    parse.__name__ = "number"
    return parse


def positive(unit: str = "") -> object:
    """A ``type=`` for a finite float > 0 (``unit`` is named in the message)."""
    return real(0.0, None, unit=unit)


def fraction(lo_open: bool = True, unit: str = "(fraction of R_t)") -> object:
    """A ``type=`` for a fraction in (0, 1] (``lo_open=False``: [0, 1])."""
    return real(0.0, 1.0, lo_open=lo_open, hi_open=False, unit=unit)


def integer(lo: int, hi: int | None = None):
    """A ``type=`` for an integer in [lo, hi] (``hi=None``: no upper bound).

    Only plain integer literals are accepted ("64", "-3"); "2.5", "1e3" and "nan" are refused
    with the allowed range.
    """
    rng = f"[{lo}, {'inf)' if hi is None else f'{hi}]'}"

    def parse(text: str) -> int:
        try:
            v = int(text, 10)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"must be an integer in {rng}, got {show(text)}"
            ) from None
        if v < lo or (hi is not None and v > hi):
            raise argparse.ArgumentTypeError(f"must be an integer in {rng}, got {show(text)}")
        return v

    parse.__name__ = "integer"
    return parse


def add_workers(p, what: str, scheduler_what: str) -> None:
    """``--workers N|auto`` and ``--scheduler ADDRESS`` on a parser or group (one wording).

    Parameters
    ----------
    p : argparse.ArgumentParser or argument group
        Where the options go.
    what : str
        What runs on the cluster (``"the cases"``, ...), for the help text.
    scheduler_what : str
        What the existing scheduler runs, and what its workers need, for the help text.
    """
    shared_option(
        p,
        "--workers",
        type=workers_count,
        default=None,
        metavar="N|auto",
        help=f"run {what} on a local Dask cluster of N worker processes, started once "
        "per command, one per GPU (worker i on cuda:i mod #GPUs; dask-cuda's "
        "LocalCUDACluster where installed); auto: one per visible GPU, 1 on a machine "
        "without one; default: in this process",
    )
    shared_option(
        p,
        "--scheduler",
        default=None,
        help=f"address of an existing Dask scheduler (e.g. tcp://host:8786, or the "
        f"scheduler of a dask-jobqueue cluster) for {scheduler_what}",
    )


def count_or_auto(hi: int):
    """A ``type=`` for an option taking an integer in [1, ``hi``] or ``auto`` (kept as "auto")."""

    def parse(text: str) -> int | str:
        if text.strip().lower() == "auto":
            return "auto"
        try:
            return integer(1, hi)(text)
        except argparse.ArgumentTypeError:
            raise argparse.ArgumentTypeError(
                f"must be an integer in [1, {hi}] or 'auto', got {show(text)}"
            ) from None

    return parse


workers_count = count_or_auto(4096)
"""A ``type=`` for ``--workers``: an integer in [1, 4096], or ``auto``."""


DEVICES_HELP = (
    "spread each contact solve of {what} over N devices (one problem split in row slabs; JAX's "
    'default backend: pip install "warptrunc[distributed]", on CUDA machines "jax[cuda12]"), or '
    "auto: one device while the solver fits it, else the fewest that hold it; N must divide "
    "the map's rows; default: --device alone"
)
"""The help text of ``--devices`` (one wording for every command that solves contact)."""


def add_devices(p, what: str) -> None:
    """``--devices N|auto`` on a parser or group (:data:`DEVICES_HELP`).

    Parameters
    ----------
    p : argparse.ArgumentParser or argument group
        Where the option goes.
    what : str
        Which solves it spreads (``"the elastic cross-check"``, ...), for the help text.
    """
    shared_option(
        p,
        "--devices",
        type=devices_count,
        default=None,
        metavar="N|auto",
        help=DEVICES_HELP.format(what=what),
    )


devices_count = count_or_auto(64)
"""A ``type=`` for ``--devices``: an integer in [1, 64], or ``auto``."""


def prepare_devices(devices: int | str | None) -> int | str | None:
    """Before a solve over several devices: JAX importable (ValueError naming ``--devices``
    otherwise), and JAX told not to take 75 % of every GPU at start (Warp shares them):
    ``XLA_PYTHON_CLIENT_PREALLOCATE=false`` and ``XLA_PYTHON_CLIENT_MEM_FRACTION=0.95`` unless
    set already. Nothing for None or 1.

    Parameters
    ----------
    devices : int, "auto" or None
        The parsed ``--devices``.

    Returns
    -------
    int, "auto" or None
        ``devices``, unchanged.
    """
    if devices in (None, 1):
        return devices
    os.environ.setdefault("XLA_PYTHON_CLIENT_PREALLOCATE", "false")
    os.environ.setdefault("XLA_PYTHON_CLIENT_MEM_FRACTION", "0.95")
    try:
        from ..contact.sharded.grid import import_jax

        import_jax()
    except ImportError as exc:
        raise ValueError(f"--devices {devices}: {exc}") from None
    return devices


def odd_integer(lo: int = 1):
    """A ``type=`` for an odd integer ≥ ``lo``."""
    base = integer(lo)

    def parse(text: str) -> int:
        v = base(text)
        if v % 2 == 0:
            raise argparse.ArgumentTypeError(f"must be an odd integer ≥ {lo}, got {show(text)}")
        return v

    parse.__name__ = "odd integer"
    return parse


def check_increments(value: int | None, option: str = "--increments") -> None:
    """Refuse more depth increments than one run may have (bounded work), naming the cap.

    Parameters
    ----------
    value : int or None
        The option's value (None: not given).
    option : str
        The option, for the message.

    Raises
    ------
    ValueError
        ``value`` exceeds :data:`warptrunc._support.validate.MAX_INCREMENTS`.
    """
    if value is not None and value > MAX_INCREMENTS:
        raise ValueError(
            f"{option} {value} is more than the {MAX_INCREMENTS} increments one run may have "
            f"(a step below 10⁻⁶·ω_max is finer than float32 heights resolve, and each increment "
            f"is a row of the output: {value} rows take minutes to write); use at most "
            f"{MAX_INCREMENTS}"
        )


# --- argument groups --------------------------------------------------------------------------


def add_device(p: argparse.ArgumentParser) -> None:
    """``--device`` (checked when the command runs, against the devices Warp finds)."""
    shared_option(
        p,
        "--device",
        default=None,
        help="Warp device: cpu, cuda:0, ... (default: $WARPTRUNC_DEVICE, else CUDA if present, "
        "else cpu)",
    )


def add_streaming(p: argparse.ArgumentParser) -> None:
    """``--stream`` and ``--band-rows`` (how a generated map is held: whole or by row bands)."""
    shared_option(
        p,
        "--stream",
        action="store_true",
        help="generate and truncate by row bands, never holding the map (default: only when "
        "the map needs more than half of the free memory)",
    )
    shared_option(
        p,
        "--band-rows",
        type=integer(1),
        default=None,
        help="rows per band when streaming (default: about 2**28 pixels per band)",
    )


def slope_line(record: dict | None) -> str:
    """One line of a command's output: the rms slope h′_rms and curvature h″_rms of a
    :func:`warptrunc.slope.slope_record`, with the method, and the spectrum's where both are
    known ("" without a record)."""
    if not record or record.get("slope_rms") is None:
        return ""
    fd, sp = record.get("finite_differences"), record.get("spectrum")
    main = fd or sp
    how = "finite differences" if fd else "from its spectrum"
    line = (
        f"h′_rms = {main['slope_rms']:.3g}, h″_rms = {main['curvature_rms_per_m']:.3g} 1/m "
        f"at the {main['dx_m'] * 1e9:.4g} nm pixel ({how}"
    )
    if fd and sp:
        line += f"; spectrum {sp['slope_rms']:.3g}, {sp['curvature_rms_per_m']:.3g} 1/m"
    return line + ")\n"


def add_no_plot(p: argparse.ArgumentParser, what: str) -> None:
    """``--no-plot`` (skip the figures ``what``)."""
    shared_option(p, "--no-plot", action="store_true", help=f"skip {what}")


def add_out(p: argparse.ArgumentParser, default: str = "out") -> None:
    """``--out DIR``."""
    shared_option(p, "--out", type=output_dir, default=Path(default), help="output folder")


def add_run_outputs(p: argparse.ArgumentParser, out: str, plot_help: str) -> None:
    """``--device``, ``--out DIR`` (default ``out``), ``--no-plot`` and ``--no-progress``."""
    add_device(p)
    add_out(p, out)
    shared_option(p, "--no-plot", action="store_true", help=plot_help)
    add_no_progress(p)


def add_no_progress(p: Any) -> None:
    """``--no-progress``: silence the progress report (:mod:`warptrunc._support.progress`),
    which every long command writes on stderr."""
    shared_option(
        p,
        "--no-progress",
        action="store_true",
        help="no progress report on stderr (default: a bar on a terminal, else a line every "
        "few seconds)",
    )


def add_output_file(p: Any, default: str, what: str) -> None:
    """``--output/-o FILE``: the file a command writes (``what`` it holds)."""
    shared_option(p, "--output", "-o", type=output_file, default=Path(default), help=what)


def file_name_with(suffixes: tuple[str, ...]):
    """A ``type=`` for a plain file name (written inside ``--out``) ending in one of
    ``suffixes`` (checked at parse time)."""

    def parse(text: str) -> str:
        if not text or Path(text).name != text or text in (".", ".."):
            raise argparse.ArgumentTypeError(f"must be a file name without folders, got {text!r}")
        if not text.lower().endswith(suffixes):
            raise argparse.ArgumentTypeError(f"must end in {' or '.join(suffixes)}, got {text!r}")
        return text

    parse.__name__ = "file name"
    return parse


def add_file_in_out(
    p: Any,
    option: str,
    suffixes: tuple[str, ...],
    default: str,
    what: str,
    *,
    optional: bool = False,
) -> None:
    """``option FILE``: a file written inside ``--out``, named with one of ``suffixes``.

    ``optional``: the file is written only when the option is given, named ``default`` when
    the option has no value (``--vtk`` or ``--vtk surface.vtk``); otherwise it is always
    written, named ``default`` unless the option names it.
    """
    kw: dict[str, Any] = {"type": file_name_with(suffixes), "help": what}
    if optional:
        kw.update(nargs="?", const=default, default=None, metavar="FILE")
    else:
        kw.update(default=default)
    shared_option(p, option, **kw)


def add_json_output(p: Any) -> None:
    """``--json PATH``: write the command's JSON to a file, or to stdout with ``-``."""

    def json_path(text: str) -> str:
        return text if text == "-" else str(output_file(text))

    json_path.__name__ = "path"
    shared_option(
        p,
        "--json",
        type=json_path,
        default=None,
        metavar="PATH",
        help="write JSON here ('-': stdout)",
    )


def add_figures_out(p: Any, what: str) -> None:
    """``--out DIR`` of a command whose figures are optional: written only when given."""
    shared_option(p, "--out", type=output_dir, default=None, help=f"folder for {what}")


def add_no_surface(p: Any, what: str) -> None:
    """``--no-surface``: write ``what`` only, not the surface file."""
    shared_option(p, "--no-surface", action="store_true", help=f"write {what} only")


SCAN_FILE_HELP = (
    "height map: .npz/.npy (warptrunc or plain), .csv/.txt matrix, or an instrument file (.sur, "
    ".x3p, .datx, ... over forty formats, through SurfaceTopography)"
)
"""The help of a command's FILE (``describe``, ``calibrate``)."""


def add_scan_file(p: argparse.ArgumentParser, *, required: bool = True) -> Any:
    """FILE (positional, or ``--input/-i FILE`` as in every other command) and the reader
    options (:func:`add_reader_options`), of a command that reads one height map.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    required : bool
        The command needs the file (else the targets may be typed in).

    Returns
    -------
    argparse group
        The group "reading the file".
    """
    shared_option(
        p,
        "file",
        type=input_file,
        nargs="?",
        default=None,
        metavar="FILE",
        help=SCAN_FILE_HELP + ("" if required else " (optional: the targets may be typed in)"),
    )
    g = p.add_argument_group("reading the file")
    shared_option(
        g,
        "--input",
        "-i",
        type=input_file,
        default=None,
        metavar="FILE",
        help="the height map, as FILE (the same file; give one of the two)",
    )
    add_reader_options(g)
    p.set_defaults(_file_required=required)
    return g


def scan_file(args: argparse.Namespace) -> Path | None:
    """The file named by FILE or ``--input`` (None when neither is given and it is optional).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of :func:`add_scan_file`; ``args.file`` is set to the file.

    Returns
    -------
    Path or None
        The file to read.

    Raises
    ------
    ValueError
        Both forms name a file, or neither does and the command needs one.
    """
    f, i = args.file, getattr(args, "input", None)
    if f is not None and i is not None and f != i:
        raise ValueError(f"give the height map once, as FILE or --input FILE, got {f} and {i}")
    args.file = f if f is not None else i
    if args.file is None and getattr(args, "_file_required", True):
        raise ValueError("the height map is missing: give FILE or --input FILE")
    return args.file


def read_scan(args: argparse.Namespace) -> Surface | None:
    """The Surface named by FILE or ``--input`` (:func:`scan_file`), read with the reader
    options; None when neither is given and the file is optional."""
    path = scan_file(args)
    return None if path is None else read_input(path, args)


def add_overwrite(p: Any, what: str) -> None:
    """``--overwrite``: replace ``what`` (the results of an existing output folder)."""
    shared_option(p, "--overwrite", action="store_true", help=f"replace {what}")


def refuse_unconverged(name: str, status: int) -> int:
    """Say on stderr that ``warptrunc NAME`` exits ``status`` because a solve did not converge
    (without ``--accept-unconverged``); returns ``status``."""
    print(
        f"warptrunc {name}: exit {status}: not every solve converged "
        "(--accept-unconverged to exit 0)",
        file=sys.stderr,
    )
    return status


def add_accept_unconverged(p: Any, status: int) -> None:
    """``--accept-unconverged``: exit 0 even when a solve did not converge (else ``status``)."""
    shared_option(
        p,
        "--accept-unconverged",
        action="store_true",
        help=f"exit 0 even when a solve did not converge (default: exit {status})",
    )


def add_profile(p: Any, what: str, default: str | None) -> None:
    """``--profile NAME``: a profile of :data:`warptrunc.reproduce.profiles.PROFILES` (the sizes
    of a reproduction run; ``what`` it gives this command)."""
    from ..reproduce.profiles import PROFILES

    shared_option(p, "--profile", choices=sorted(PROFILES), default=default, help=what)


def add_stages(p: Any, stages: tuple[str, ...]) -> None:
    """``--stages NAME[,NAME...]``: compute only some of ``stages`` (the others reused)."""
    shared_option(
        p,
        "--stages",
        metavar="NAME[,NAME...]",
        default=None,
        help=f"compute only these stages (of {', '.join(stages)}); the others are reused when "
        "stored with the same parameters, else left out",
    )


def add_time_budget(p: Any, what: str) -> None:
    """``--time-budget SECONDS``: stop ``what`` cleanly after this long (a rerun continues)."""
    shared_option(
        p,
        "--time-budget",
        metavar="SECONDS",
        type=positive("s"),
        default=None,
        help=f"stop {what} after this many seconds; its finished work is kept and a rerun "
        "continues (default: no limit)",
    )


def add_commit(p: Any) -> None:
    """``--commit SHA``: the commit a report records."""
    shared_option(
        p,
        "--commit",
        metavar="SHA",
        default=None,
        help="commit recorded in the report (default: $WARPTRUNC_GIT_COMMIT, else git rev-parse "
        "HEAD of the checkout, else 'unknown')",
    )


def add_retry_failed(p: Any, what: str) -> None:
    """``--retry-failed``: run again ``what`` (the parts a store records as failed)."""
    shared_option(p, "--retry-failed", action="store_true", help=f"run again {what}")


def add_shards(p: Any) -> None:
    """``--shard-size`` and ``--shard-seconds``: how the cases of a sweep are cut into tasks and
    parts of its store (:class:`~warptrunc.sweep.options.SweepExecution`; not given: its
    defaults)."""
    shared_option(
        p,
        "--shard-size",
        type=integer(1, 10**6),
        default=None,
        help="with --workers/--scheduler: cases per Dask task, each written by its worker as "
        "one part (default: adaptive, about --shard-seconds of work)",
    )
    shared_option(
        p,
        "--shard-seconds",
        type=real(0.0, None, lo_open=False, unit="s"),
        default=None,
        help="work per part of the store (s; default 1); a hard kill loses at most about this "
        "much per worker",
    )


def add_grid_file(p: Any) -> None:
    """``--grid FILE``: a sweep grid read from a TOML file
    (:meth:`~warptrunc.sweep.SweepGrid.from_toml`)."""
    shared_option(
        p,
        "--grid",
        type=input_file,
        default=None,
        help="TOML file with D = [...], delta = [...], seeds = '0-4' and optionally a table "
        "[axes] of more axes (e.g. M = [8, 10])",
    )


def add_truncation(
    g: Any,
    *,
    only: tuple[str, ...] | None = None,
    defaults: dict | None = None,
    many: bool = False,
) -> None:
    """The options of :class:`~warptrunc.truncation.settings.TruncationSettings` (``--increments``,
    ``--max-depth-fraction``, ``--max-depth``, ``--beta-prime``, ``--islands``,
    ``--connectivity``) on the group ``g``; ``only`` some of them, with the command's
    ``defaults``; ``many``: the sweepable ones take several values (a sweep axis)."""
    from ..truncation.settings import TruncationSettings

    add_options(g, TruncationSettings, only=only, defaults=defaults, many=many)


def add_fit_range(g: Any, *, exclude: tuple[str, ...] = ("spikes",), many: bool = False) -> None:
    """The options of :class:`~warptrunc.truncation.settings.FitRange` (``--fit-range``,
    ``--min-pixels``, ``--depth-window``, ``--rt-percentile``) on the group ``g``; the rule's
    ``spikes`` follows ``--spikes`` (:func:`fit_range_from_args`)."""
    from ..truncation.settings import FitRange

    add_options(g, FitRange, exclude=exclude, many=many)


def truncation_from_args(args: argparse.Namespace, defaults: dict | None = None) -> Any:
    """The :class:`~warptrunc.truncation.settings.TruncationSettings` of the parsed options."""
    from ..truncation.settings import TruncationSettings

    return from_args(TruncationSettings, args, defaults=defaults)


def fit_range_from_args(args: argparse.Namespace, **overrides: Any) -> Any:
    """The :class:`~warptrunc.truncation.settings.FitRange` of the parsed options; ``spikes``
    is on where ``--spikes auto`` is (the default of the commands that apply the rule)."""
    from ..truncation.settings import FitRange

    how = getattr(args, "spikes", "auto")  # None: not given, the reader's default applies
    how = read_options_from_args(args).spikes if how is None else how
    overrides.setdefault("spikes", how == "auto")
    return from_args(FitRange, args, **overrides)


def add_input(g: Any, help: str) -> None:
    """``--input FILE`` (``-i``): the height-map file a command reads (checked to exist)."""
    shared_option(g, "--input", "-i", type=input_file, default=None, help=help)


SURFACE_EXCLUDE = ("method",)
"""WMSpec fields with no command-line option: the evaluation method (``"direct"`` is a
reference for tests, not a surface parameter)."""


def add_surface_source(
    p: argparse.ArgumentParser, *, defaults: dict | None = None, scan_rule: str | None = None
) -> None:
    """A height-map file, a preset, or WM generation parameters (all SI).

    The WM options (``--D``, ``--Wr``, ``--L``, ``--n``, ``--Rt``, ``--G``, ``--M``,
    ``--gamma``, ``--Wc``, ``--cutoff``, ``--seed``) are generated from :class:`WMSpec`
    (:func:`warptrunc.params.add_options`); ``defaults`` are the command's own defaults where
    they differ from the class's (pass the same to :func:`wm_spec_from_args`); ``scan_rule``
    as :func:`add_reader_options` takes it.
    """
    g = p.add_argument_group(
        "surface source (a height-map file, a preset, or WM generation parameters)"
    )
    add_input(
        g,
        "height map file (.npz/.npy written by warptrunc, .npy/.csv/.txt matrix with "
        "--dx, or an instrument file); overrides the generation parameters",
    )
    add_reader_options(g, scan_rule=scan_rule)
    add_generation(g, defaults=defaults)


SELF_AFFINE_SHARED = ("L", "n", "seed")
"""Fields of :class:`~warptrunc.selfaffine.SelfAffineSpec` that share the WM options of the same
name (``--L``, ``--n``, ``--seed``: the grid and the phases' seed mean the same for both)."""


def add_generation(g: Any, *, defaults: dict | None = None) -> None:
    """A generated surface: ``--surface`` (which generator), ``--preset`` and the fields of
    :class:`WMSpec` (``--D``, ``--Wr``, ...) and of
    :class:`~warptrunc.selfaffine.SelfAffineSpec` (``--hurst``, ``--rolloff``, ``--long-cutoff``,
    ``--short-cutoff``, ``--rms-height``, ``--rms-slope``; ``--L``, ``--n``, ``--seed`` shared).
    ``defaults`` are the command's own WM defaults (pass the same to :func:`wm_spec_from_args`)."""
    from ..selfaffine import SelfAffineSpec

    shared_option(
        g,
        "--surface",
        choices=("wm", "self-affine"),
        default="wm",
        help="the generator: a Weierstrass–Mandelbrot surface (Eq. 4, the --D ... options) or a "
        "self-affine one from its power spectrum (warptrunc.selfaffine: --hurst, the cut-offs, "
        "--rms-height or --rms-slope)",
    )
    from ..presets import SELF_AFFINE

    shared_option(
        g,
        "--preset",
        choices=[*PRESETS, *SELF_AFFINE],
        default=None,
        help="start from the paper's Table 1 simulated surface (warptrunc.presets: D_in and R_t' "
        "calibrated to D_vs as Fig. 6, or to D_tri with -tri; Table 1's W_r, 10240² over 1 mm; "
        "-sa: the self-affine surface of the same descriptors, with --surface self-affine); "
        "options given win over it",
    )
    add_options(g, WMSpec, exclude=SURFACE_EXCLUDE, defaults=defaults)
    add_options(g, SelfAffineSpec, exclude=SELF_AFFINE_SHARED)


def self_affine_from_args(args: argparse.Namespace) -> Any:
    """The :class:`~warptrunc.selfaffine.SelfAffineSpec` of the parsed options (with
    ``--surface self-affine``): a ``-sa`` preset's fields, then the options given."""
    from ..presets import SELF_AFFINE
    from ..selfaffine import SelfAffineSpec

    name = getattr(args, "preset", None)
    base = SELF_AFFINE[name].to_dict() if name in SELF_AFFINE else {}
    if base:
        base.update(L=SELF_AFFINE[name].L, n=SELF_AFFINE[name].n)
        if getattr(args, "rms_slope", None) is not None:
            base["rms_height"] = None  # the slope given sets the scale instead
    return from_args(SelfAffineSpec, args, defaults=base)


def spec_from_args(args: argparse.Namespace, defaults: dict | None = None) -> Any:
    """The generated surface's spec: a :class:`WMSpec` (:func:`wm_spec_from_args`), or a
    :class:`~warptrunc.selfaffine.SelfAffineSpec` with ``--surface self-affine``."""
    from ..presets import SELF_AFFINE

    name = getattr(args, "preset", None)
    if getattr(args, "surface", "wm") == "self-affine" or name in SELF_AFFINE:
        if name is not None and name not in SELF_AFFINE:
            raise ValueError(
                f"--preset {name} is a WM surface; with --surface self-affine give one of "
                f"{', '.join(SELF_AFFINE)}"
            )
        return self_affine_from_args(args)
    return wm_spec_from_args(args, defaults)


def generate_surface(spec: Any, device: Any) -> Surface:
    """The surface of a spec from :func:`spec_from_args`, on ``device``."""
    from ..selfaffine import SelfAffineSpec

    if isinstance(spec, SelfAffineSpec):
        from ..selfaffine import self_affine_surface

        return self_affine_surface(spec, device=device)
    from ..wm import wm_surface  # Warp's import, when the surface is made

    return wm_surface(spec, device=device)


def add_wm_shape(g: argparse._ActionsContainer, *, many: bool = False) -> None:
    """WM options other than D, R_t/G and the seed: W_r, L, n, M, γ, W_c, cut-off (SI).

    ``many``: the sweepable ones take one or more values (several: a sweep axis).
    """
    add_options(g, WMSpec, exclude=("D", "Rt", "G", "seed", *SURFACE_EXCLUDE), many=many)


def add_material(
    g: argparse._ActionsContainer,
    *,
    exclude: tuple[str, ...] = ("hardness",),
    many: bool = False,
) -> None:
    """``--E``, ``--nu``, ``--E-i``/``--E-flat``, ``--nu-i``/``--nu-flat`` from :class:`Material`.

    ``hardness`` is left out by default: the truncation commands are elastic (E* only).
    """
    add_options(g, Material, exclude=exclude, many=many)


def wm_spec_from_args(args: argparse.Namespace, defaults: dict | None = None) -> WMSpec:
    """The :class:`WMSpec` of the parsed options: the command's ``defaults``, then the
    ``--preset``, then the options given. ``--G`` given: the heights are not rescaled
    (``Rt`` is None)."""
    base = dict(defaults or {})
    name = getattr(args, "preset", None)
    if name is not None and name not in PRESETS:
        raise ValueError(
            f"--preset {name} is a self-affine surface: use it with --surface self-affine"
        )
    if name is not None:
        base.update(PRESETS[name].to_dict() | {"L": PRESETS[name].L, "n": PRESETS[name].n})
    over = {"Rt": None} if getattr(args, "G", None) is not None else {}
    return from_args(WMSpec, args, defaults=base, **over)


def material_from_args(args: argparse.Namespace, **overrides) -> Material:
    """The :class:`Material` of the parsed options (``overrides`` win)."""
    return from_args(Material, args, **overrides)


def add_reader_options(g: argparse._ActionsContainer, *, scan_rule: str | None = None) -> None:
    """Options for reading a height-map file, from :class:`~warptrunc.io.options.ReadOptions`
    (spacing, units, missing points, levelling, reader, channel, spikes).

    ``scan_rule``: the command applies the automatic rule of :mod:`warptrunc.robust` to a map
    read from a file: ``"fit"`` (``analyze``: the analysis decides), ``"read"`` (``compare``,
    ``indent``: spikes that set R_t are masked as the map is read); either refuses a map under
    32 pixels a side and makes ``--spikes auto`` the default. None: ``--spikes report``.
    """
    from ..io.options import ReadOptions

    add_options(g, ReadOptions, defaults={"spikes": "auto" if scan_rule else "report"})
    g.set_defaults(_scan_rule=scan_rule)


def read_options_from_args(args: argparse.Namespace) -> Any:
    """The :class:`~warptrunc.io.options.ReadOptions` of the parsed options."""
    from ..io.options import ReadOptions

    rule = getattr(args, "_scan_rule", None)
    return from_args(ReadOptions, args, defaults={"spikes": "auto" if rule else "report"})


def read_input(path: Path, args: argparse.Namespace) -> Surface:
    """Read ``path`` with the options of :func:`add_reader_options`; reports filled points."""
    from ..io import read_height_map  # the readers (and Warp) only when a map is read

    opts = read_options_from_args(args)
    s = read_height_map(path, **opts.reader_kwargs())
    if getattr(args, "_scan_rule", None):
        from ..robust import check_map_size

        check_map_size(s, str(path))
    n_missing = s.params.get("n_missing", 0)
    if n_missing:
        print(f"{path}: {n_missing} missing points filled ({opts.fill})", file=sys.stderr)
    return _map_checks(s, args, opts.spikes)


def _map_checks(s: Surface, args: argparse.Namespace, how: str) -> Surface:
    """Spike check of a map read from a file (``--spikes``): warnings printed on stderr and
    kept in ``args._warnings`` for the command's JSON (:func:`warnings_of`). ``auto`` masks
    the spikes that set R_t here for ``compare`` and ``indent``; ``analyze`` decides in the
    analysis (:func:`warptrunc.analysis.analyze`, ``auto_spikes``)."""
    from .. import plausibility, robust

    if how == "auto" and getattr(args, "_scan_rule", None) == "fit":
        return s
    if how == "auto":
        masked, found, sets = robust.spike_rule(s)
        found = robust.spike_warning(found, sets, masked if sets else None)
        s = masked if sets else s
    elif how == "mask":
        s, found = plausibility.mask_spikes(s)
    elif how == "report":
        found = plausibility.check_spikes(s)
    else:
        found = []
    add_warnings(args, found)
    return s


def add_warnings(args: argparse.Namespace, found: list) -> None:
    """Print ``found`` (PlausibilityWarning) on stderr and keep them for :func:`warnings_of`."""
    from ..plausibility import report

    report(found)
    args._warnings = [*getattr(args, "_warnings", []), *found]


def warnings_of(args: argparse.Namespace) -> list[dict]:
    """The ``"warnings"`` list of a command's JSON: every warning kept by :func:`add_warnings`."""
    return [w.to_dict() for w in getattr(args, "_warnings", [])]


def surface_from_args(args: argparse.Namespace) -> Surface:
    """Read ``--input`` or generate the surface of the parameters (WM, or self-affine with
    ``--surface self-affine``)."""
    if args.input is not None:
        return read_input(args.input, args)
    return generate_surface(spec_from_args(args), args.device)
