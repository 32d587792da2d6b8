"""Widget layer (ipywidgets): panels that pair controls with a drawing.

A panel's ``update(**values)`` only moves artists and calls ``self.redraw()``. Every panel
class registers itself with :func:`register` so ``benchmarks/widget_latency.py`` and the
headless tests can find all interactive figures of the course.
"""
from gm_core.widgets.base import PANELS, Panel, all_panels, register

__all__ = ["Panel", "PANELS", "register", "all_panels"]
