"""The locomotion lab's panel (notebook 12): a system of sysplotter's library, a gait and three numbers
(scene of :mod:`gm_core.drawing.catalog`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.catalog import LAB_FRAMES, OBJECTIVES, LabScene, add_lab_system, lab_names
from gm_core.drawing.curvature import ROWS
from gm_core.drawing.toolkit.primitives import jshtml
from gm_core.geometry import OptimalGait
from gm_core.systems import LocomotionSystem
from gm_core.systems.gaits import Gait, GaitLike
from gm_core.validation import SingularShapeError
from gm_core.widgets.base import TablePanel, register, slider

if TYPE_CHECKING:
    from IPython.display import HTML
    from matplotlib.backend_bases import MouseEvent

__all__ = ["LabPanel"]


@register
class LabPanel(TablePanel):
    """Pick a system by sysplotter's name and a body frame, shape, draw, load or optimise a gait on its
    curvature map, read exact g(T), Stokes and ∫ξ dt.

    Under the table: "draw gait" (while it is down, clicks on the map add points; from 3 on, the
    gait is the periodic spline through them), "clear", the objective and "optimise", and a status
    line. ``panel.load_gait(points)`` uses a gait from a code cell, ``panel.run(objective)`` does
    what the optimise button does, ``panel.add_system(system)`` offers a system of your own and
    ``panel.animation()`` is the gait in the course's player, for a cell of its own below the panel
    (panel and player together would not fit a laptop's screen).
    """

    title = "Locomotion lab: any system of sysplotter's library"
    scene_class = LabScene
    scene: LabScene
    # blitted: a gait or phase moves only the gait, the dot and the body; switching systems or
    # frames makes or hides artists and changes the map, which the blitter sees and draws whole

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"system": W.Dropdown(options=list(lab_names()), value="three_link_lowRe", description="system"),
                "frame": W.Dropdown(options=list(LAB_FRAMES), value=LAB_FRAMES[0], description="body frame"),
                "row": W.ToggleButtons(options=[(r, i) for i, r in enumerate(ROWS)], value=0, description="map row",
                                       style={"button_width": "3.5em"}),
                "c1": slider(0.0, -0.8, 0.8, description="centre r₁"),
                "c2": slider(0.0, -0.8, 0.8, description="centre r₂"),
                "a": slider(0.5, 0.05, 0.9, description="size a"),
                "b": slider(0.3, 0.05, 0.9, description="size b"),
                "tilt": slider(0.78, -1.6, 1.6, description="tilt"),
                "phase": slider(0.0, 0.0, 1.0, description="body at t/T")}

    @override
    def build(self) -> None:
        super().build()
        self.draw = W.ToggleButton(value=False, description="draw gait", icon="pencil",
                                   tooltip="while down, a click on the map adds a point of the gait (3 or more)")
        self.clear = W.Button(description="clear", tooltip="forget the drawn or loaded gait: the sliders' gait")
        self.objective = W.Dropdown(options=list(OBJECTIVES), value="speed", layout=W.Layout(width="110px"))
        self.button = W.Button(description="optimise", button_style="primary", icon="play",
                               tooltip="optimise the gait shown (a few seconds)")
        self.status = W.HTML("")
        self.clear.on_click(lambda _: self.clear_gait())
        self.button.on_click(lambda _: self.run())
        self.draw.observe(self._on_draw, names="value")
        self.fig.canvas.mpl_connect("button_press_event", self._on_click)

    @override
    def after_update(self, values: dict[str, Any]) -> None:
        """The table, and row buttons that name the rows of the system shown (ωx, ωy, ωz for
        twin_rotor)."""
        super().after_update(values)
        buttons = self.controls["row"]
        names = list(self.scene.row_names)
        if [label for label, _ in buttons.options] != names:
            with self.hold():
                buttons.options = [(r, i) for i, r in enumerate(names)]
                buttons.value = self.scene.row

    def _on_draw(self, change: dict[str, Any]) -> None:
        if change["new"]:
            self.status.value = "click 3 or more points on the map: the gait is the closed spline through them"

    def _on_click(self, event: MouseEvent) -> None:
        if self.draw.value and event.inaxes is self.scene.ax and event.xdata is not None and event.ydata is not None:
            self.add_point(event.xdata, event.ydata)

    def add_point(self, x: float, y: float) -> None:
        """What a click on the map does while "draw gait" is down: add the shape (x, y) and redraw."""
        n = self.scene.add_point(x, y)
        self.refresh()
        self.status.value = (f"{n} point{'s' * (n > 1)}: 3 or more are needed for a gait" if n < 3
                             else f"drawn gait: the closed spline through {n} points")

    def clear_gait(self) -> None:
        """What "clear" does: forget the drawn or loaded gait and show the sliders' gait."""
        self.scene.clear_points()
        self.refresh()
        self.status.value = ""

    def add_system(self, system: LocomotionSystem, name: str | None = None) -> str:
        """Add your own ``system`` (two shape variables) to the dropdown and show it; returns its name
        (:func:`~gm_core.drawing.catalog.add_lab_system`, whose errors it raises)."""
        name = add_lab_system(system, name)
        menu = self.controls["system"]
        if name not in menu.options:
            menu.options = list(lab_names())
        menu.value = name
        return name

    def load_gait(self, gait: GaitLike, period: float = 1.0) -> Gait:
        """Show ``gait`` (closed-path shapes (K, 2), a callable t -> r of period ``period``, or a Gait)
        and its numbers, until a gait slider or the system changes; returns the Gait. Raises
        ValueError or TypeError naming ``gait`` for anything else."""
        loaded = self.scene.load_gait(gait, period)
        self.refresh()
        self.status.value = "gait loaded" if loaded.name == "loaded gait" else f"gait loaded: {loaded.name}"
        return loaded

    def run(self, objective: str | None = None) -> OptimalGait | None:
        """Optimise the gait shown for ``objective`` (default: the dropdown's), then draw the optimum.
        The status says "done" only once its picture has been sent to the page. Returns the
        OptimalGait, or None when the optimiser cannot run (the reason is in the status line)."""
        objective = self.objective.value if objective is None else objective
        self.button.disabled = True
        self.status.value = "optimising …"

        def progress(it: int, value: float) -> None:
            self.status.value = f"optimising … step {it}: {objective} {value:.4f}"

        try:
            res = self.scene.optimize(objective, callback=progress)
            self.status.value = "drawing the best gait …"
            self.refresh()
            self.draw_now()
        except (TypeError, ValueError, SingularShapeError) as e:
            self.status.value = f"<span style='color:darkred'>cannot optimise: {e}</span>"
            return None
        finally:
            self.button.disabled = False
        value = res.efficiency if OBJECTIVES[objective] == "efficiency" else res.displacement
        self.status.value = (f"done: {objective} {value:.4f} after {res.nit} steps "
                             "(its animation: lab.animation() in a cell below)")
        return res

    def animation(self, n_frames: int = 32, cycles: int = 2) -> HTML:
        """The gait shown, the body moving along it, in the course's player
        (:func:`~gm_core.drawing.toolkit.primitives.jshtml`): the output of a cell of its own."""
        anim, _, _ = self.scene.animation(n_frames=n_frames, cycles=cycles)
        return jshtml(anim)

    @property
    @override
    def widget(self) -> W.Widget:
        """The panel, its table of numbers, then the gait's buttons and the status line."""
        if getattr(self, "_box", None) is None:
            self.status.layout = W.Layout(flex="1 1 auto")
            actions = W.HBox([self.draw, self.clear, self.objective, self.button, self.status],
                             layout=W.Layout(align_items="center", grid_gap="0 8px", max_width="900px"))
            self._box = W.VBox([super().widget, actions])
        return self._box
