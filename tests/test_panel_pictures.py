"""Every registered panel displays with a picture of its state and an alt text (for static pages:
the course website, nbconvert), besides its live widget view (which JupyterLab shows)."""
import base64
import io

import matplotlib
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
