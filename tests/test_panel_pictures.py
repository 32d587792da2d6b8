"""Every registered panel displays with a picture of its state and an alt text (for static pages:
the course website, nbconvert), besides its live widget view (which JupyterLab shows)."""
import base64
import io

import matplotlib
import matplotlib.artist
import pytest

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from gm_core.widgets.base import all_panels  # noqa: E402

PANELS = all_panels()


@pytest.mark.parametrize("name", sorted(PANELS))
def test_panel_bundle_has_widget_view_png_and_alt(name):
    panel = PANELS[name]()
    try:
        data, meta = panel._repr_mimebundle_()
        assert "application/vnd.jupyter.widget-view+json" in data
        png = mpimg.imread(io.BytesIO(base64.b64decode(data["image/png"])), format="png")
        w, h = panel.fig.get_size_inches() * panel.fig.dpi
        assert abs(png.shape[1] - w) <= 2 and abs(png.shape[0] - h) <= 2, "one pixel per figure pixel"
        assert png[..., :3].std() > 0.01, "the picture is not blank"
        alt = meta["image/png"]["alt"]
        assert alt.startswith("Interactive figure: ") and len(alt) > 30
        first = next(iter(panel.controls.values()), None)
        if first is not None and getattr(first, "description", ""):
            assert first.description in alt, "the alt text names the controls' values"
    finally:
        plt.close(panel.fig)


class _CountsDraws(matplotlib.artist.Artist):
    """An invisible-to-the-eye artist that counts how often the figure around it is drawn."""

    def __init__(self):
        super().__init__()
        self.draws = 0

    def draw(self, renderer):
        self.draws += 1


def test_a_frozen_layout_is_saved_as_matplotlib_saves_it_with_one_draw():
    """CourseFigure.savefig leaves out matplotlib's extra layout draw when the layout is frozen:
    one draw, and the same file, byte for byte, as matplotlib's own Figure.savefig,
    and the figure keeps its frozen layout and its axes' places."""
    from matplotlib.figure import Figure
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    from gm_core.drawing.toolkit.style import CourseFigure

    compared = 0
    for name in sorted(PANELS):
        panel = PANELS[name]()
        try:
            fig = panel.fig
            engine = fig.get_layout_engine()
            if not isinstance(fig, CourseFigure) or not isinstance(engine, PlaceHolderLayoutEngine):
                continue
            places = [ax.get_position().bounds for ax in fig.axes]
            spy = fig.add_artist(_CountsDraws())
            ours, theirs = io.BytesIO(), io.BytesIO()
            fig.savefig(ours, format="png", dpi="figure")
            assert spy.draws == 1, (name, spy.draws)
            Figure.savefig(fig, theirs, format="png", dpi="figure")
            assert ours.getvalue() == theirs.getvalue(), name
            assert fig.get_layout_engine() is engine, name
            assert [ax.get_position().bounds for ax in fig.axes] == places, name
            compared += 1
        finally:
            plt.close(panel.fig)
        if compared == 6:
            break
    assert compared == 6, "six panels with a frozen layout were compared"
