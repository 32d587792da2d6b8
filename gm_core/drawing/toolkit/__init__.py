"""The drawing toolkit every topic's scenes use (not a topic itself).

* :mod:`.style`: the figure standard (dpi, fonts, palette), figures, text, arrows and :class:`Scene`;
* :mod:`.axes`: planes, 3-D axes and wireframes; :mod:`.primitives`: frames, bodies, trails, animation;
* :mod:`.player`: the play/pause player of animations; :mod:`.blit`: fast redraws of live panels.
"""
from __future__ import annotations

from gm_core.drawing.toolkit.axes import (
    plain_3d,
    plane,
    square_axes,
    wire,
)
from gm_core.drawing.toolkit.blit import (
    Blitter,
    KeyFrames,
    can_blit,
    hold_pictures_until_view,
    sends_differences,
)
from gm_core.drawing.toolkit.player import (
    MODES,
    player_html,
)
from gm_core.drawing.toolkit.primitives import (
    BodyArtist,
    FrameArtist,
    ProgressNote,
    SingularFlag,
    TrailArtist,
    animate,
    jshtml,
    n_frames,
    testing,
)
from gm_core.drawing.toolkit.style import (
    DPI,
    MATH_PT,
    MAX_WIDTH_IN,
    MIN_TEXT_PT,
    MIN_TEXT_PX,
    PALETTE,
    STYLE,
    ArrowSet,
    PathText,
    Scene,
    apply_style,
    arrow,
    axes_row,
    axis_label,
    figure,
    freeze_layout,
    margins,
    new_figure,
    readout,
    set_arrows,
    signed,
    text_panel,
    title,
    xticks,
    yticks,
)

__all__ = [
    "signed", "DPI", "MAX_WIDTH_IN", "MIN_TEXT_PX", "MIN_TEXT_PT", "MATH_PT", "PALETTE", "STYLE",
    "apply_style", "new_figure", "figure", "margins", "freeze_layout", "PathText", "readout",
    "ArrowSet", "arrow", "set_arrows", "title", "xticks", "yticks", "axis_label", "axes_row",
    "text_panel", "Scene", "plane", "square_axes", "plain_3d", "wire", "testing",
    "n_frames", "FrameArtist", "BodyArtist", "TrailArtist", "SingularFlag", "animate", "jshtml",
    "ProgressNote",
    "player_html", "MODES", "Blitter", "KeyFrames", "can_blit", "hold_pictures_until_view",
    "sends_differences",
]
