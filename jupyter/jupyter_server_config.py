# The course's Jupyter server settings, passed by `make lab` (jupyter lab --config=...).
# A notebook of book/, exercises/ or solutions/ is saved without outputs, in the form git has
# (tools/strip_outputs.py: save_hook), so running and saving one never dirties the checkout and
# a `git pull` of a course update never conflicts. The student's workspace/ is saved as it is.
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
from strip_outputs import save_hook  # noqa: E402

c = get_config()  # noqa: F821 (provided by Jupyter when it loads this file)
c.ContentsManager.pre_save_hook = save_hook
