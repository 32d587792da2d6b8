"""Chapter 2 drawings (a compatibility module): see :mod:`gm_core.drawing.chains`."""
from __future__ import annotations

from .chains import ArrowsArtist, ChainArtist, draw_accessible_manifold, draw_chain_naive, link_outline
from .toolkit import readout

__all__ = ["link_outline", "ChainArtist", "ArrowsArtist", "draw_chain_naive", "draw_accessible_manifold",
           "readout"]
