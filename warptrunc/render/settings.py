# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameters of the pictures of truncation sections: the picture
(:class:`RenderSettings`, read by :func:`~warptrunc.render.render_truncation` and, for the view
and the mesh, by :func:`~warptrunc.render.animate_truncation`) and the animation
(:class:`AnimationSettings`).

Declared once with :func:`warptrunc.params.param`: their defaults, units and ranges make the
options of ``warptrunc render``, their validation and their JSON. No Warp and no pyvista here:
the command-line parser imports this module.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..params import Parameters, check_fields, param

__all__ = ["DEFAULT_DEPTH_FRACTIONS", "MAX_MESH", "AnimationSettings", "RenderSettings"]

DEFAULT_DEPTH_FRACTIONS = (0.1, 0.2, 0.3, 0.4, 0.5)
"""Depths of the paper's Fig. 7, as fractions of R_t."""

MAX_MESH = 1024
"""Largest rendered mesh side (blocks) when the image would allow more."""

_SIZE = {"kind": "int", "ge": 16, "le": 16384, "length": 2, "metavar": ("W", "H")}


@dataclass(frozen=True)
class RenderSettings(Parameters):
    """What a picture of truncation sections shows and how (Fig. 7): the depths, the view, the
    picture's size and layout, the mesh and its colouring.

    Examples
    --------
    >>> RenderSettings(depth_fractions=(0.2, 0.4), top_view=True).pooling
    'area'
    """

    depth_fractions: tuple[float, ...] = param(
        DEFAULT_DEPTH_FRACTIONS,
        "truncation depths as fractions of R_t, each in (0, 1], one panel each (Fig. 7: 0.1–0.5)",
        gt=0.0,
        le=1.0,
        many=True,
        metavar="F",
        sweep=False,
    )
    depths: tuple[float, ...] | None = param(
        None,
        "truncation depths ω in metres, each in (0, R_t] of the map; override "
        "depth-fractions; none = the fractions",
        unit="m",
        gt=0.0,
        many=True,
        optional=True,
        metavar="OMEGA",
        sweep=False,
    )
    top_view: bool = param(
        False,
        "orthographic view from above, x to the right and y up (as imshow(z, "
        "origin='lower')); false: an oblique view from the −y side, 35° above the horizon",
        kind="bool",
        cli="top",
        sweep=False,
    )
    window_size: tuple[int, int] | None = param(
        None,
        "picture size in pixels (W H); none = 520×440 per panel",
        optional=True,
        cli="size",
        sweep=False,
        **_SIZE,
    )
    ncols: int | None = param(
        None, "panels per row; none = up to 3", kind="int", ge=1, optional=True, sweep=False
    )
    vertical_exaggeration: float | None = param(
        None,
        "factor on heights in the picture; none = R_t drawn as 1/10 of the side "
        "(auto_exaggeration)",
        gt=0.0,
        optional=True,
        cli="exaggeration",
        sweep=False,
    )
    downsample: int | None = param(
        None,
        "block side f of the drawn mesh in pixels; none = about one block per screen "
        "pixel, at most max-mesh blocks per side",
        kind="int",
        ge=1,
        optional=True,
        sweep=False,
    )
    pooling: str = param(
        "area",
        "colour of a block of pixels: 'area' = share of red equal to the fraction of its "
        "pixels in contact (red measures A_c/A); 'any' = max-pooling, red when any pixel "
        "touches (shows every contact spot, overstates the area)",
        choices=("area", "any"),
        sweep=False,
    )
    max_mesh: int = param(
        MAX_MESH,
        "largest number of blocks per side when downsample is none",
        kind="int",
        ge=1,
        sweep=False,
    )
    lighting: bool | None = param(
        None,
        "shade the surface by VTK lights; none = on in the oblique view, off in the top "
        "view (flat colours, so red pixels measure the contact area)",
        kind="bool",
        optional=True,
        sweep=False,
    )
    annotate: bool = param(
        True, "draw titles, axes in µm and the caption", kind="bool", sweep=False
    )

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class AnimationSettings(Parameters):
    """An animation of the truncation deepening from ω = 0 (the view and the mesh are those of
    :class:`RenderSettings`).

    Examples
    --------
    >>> AnimationSettings(frames=10).fps
    8.0
    """

    max_depth_fraction: float = param(
        0.5,
        "last depth of the animation as a fraction of R_t: the deepest of Fig. 7's "
        "sections, not the stiffness fit's 0.1 (a picture shows the contact spreading)",
        gt=0.0,
        le=1.0,
        sweep=False,
    )
    frames: int = param(
        26,
        "animation frames, at depths equally spaced from 0",
        kind="int",
        ge=2,
        le=100_000,
        sweep=False,
    )
    fps: float = param(8.0, "animation frames per second", gt=0.0, sweep=False)
    frame_size: tuple[int, int] = param(
        (640, 520), "animation frame size in pixels (W H)", sweep=False, **_SIZE
    )

    def __post_init__(self) -> None:
        check_fields(self)
