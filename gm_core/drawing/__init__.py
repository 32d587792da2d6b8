"""Drawing layer (matplotlib): artists that are created once and then moved in place.

Imports gm_core's mathematics; the mathematics never imports this package. Importing it applies
the course's figure standard to matplotlib (see :mod:`gm_core.drawing.toolkit`).
"""
from gm_core.drawing.toolkit.primitives import (
           BodyArtist,
           FrameArtist,
           SingularFlag,
           TrailArtist,
           animate,
           jshtml,
           n_frames,
           testing,
)
from gm_core.drawing.toolkit.style import PALETTE, PathText, Scene, figure, new_figure

__all__ = ["BodyArtist", "FrameArtist", "TrailArtist", "SingularFlag", "animate", "jshtml",
           "n_frames", "new_figure", "testing", "PALETTE", "PathText", "Scene", "figure"]
