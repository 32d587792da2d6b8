"""Chapter 3 drawings (a compatibility module): see :mod:`gm_core.drawing.motion` (bodies,
velocities, moving world view) and :mod:`gm_core.drawing.connection` (connection fields, figures,
gait animation)."""
from __future__ import annotations

from .base import SingularFlag
from .connection import (
                         ROW_LABELS,
                         ConnectionFieldArtist,
                         ShapeCursorArtist,
                         connection_field,
                         connection_fields_figure,
                         draw_singular_set,
                         poor_pictures_figure,
                         regimes_figure,
                         shape_grid,
                         style_shape_axes,
)
from .gaits import animate_gait
from .motion import (
                         PART_STYLES,
                         MovingView,
                         SystemArtist,
                         VelocityArtist,
                         draw_system_naive,
                         style_world_axes,
                         system_extent,
)

_style_shape_axes = style_shape_axes

__all__ = ["PART_STYLES", "SystemArtist", "ConnectionFieldArtist", "ShapeCursorArtist", "VelocityArtist",
           "shape_grid", "connection_field", "system_extent", "style_world_axes", "draw_singular_set",
           "draw_system_naive", "connection_fields_figure", "regimes_figure", "poor_pictures_figure",
           "animate_gait", "ROW_LABELS", "SingularFlag", "MovingView"]
