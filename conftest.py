"""Root pytest configuration: test-mode flag for notebooks and a headless matplotlib backend."""
import os

# Notebooks and drawing code shorten animations when this is set (gm_core.drawing.testing()).
os.environ["GM_COURSE_TESTING"] = "1"
# Unit tests draw off-screen; notebooks choose their own backend with %matplotlib widget.
os.environ.setdefault("MPLBACKEND", "Agg")
