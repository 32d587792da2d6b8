"""Drawing layer (matplotlib): artists that are created once and then moved in place.

Imports gm_core's mathematics; the mathematics never imports this package.
"""
from .base import (BodyArtist, FrameArtist, TrailArtist, SingularFlag, animate, jshtml, n_frames,
                   new_figure, testing)

__all__ = ["BodyArtist", "FrameArtist", "TrailArtist", "SingularFlag", "animate", "jshtml",
           "n_frames", "new_figure", "testing"]
