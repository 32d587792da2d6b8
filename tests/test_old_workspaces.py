"""A student's workspace of an earlier course version keeps running: its old imports still work,
warn once with the new home (gm_core.renamed), and give the very same functions."""
import importlib
import subprocess
import sys

import numpy as np
import pytest

from gm_core import renamed
from gm_core.chains import three_link_frames
from gm_core.checks.ex4 import swimmer
from gm_core.geometry import drift_and_turn
from gm_core.systems.gaits import circle_gait


def _fresh(name):
    sys.modules.pop(name, None)
    return importlib.import_module(name)


@pytest.mark.parametrize("old", sorted(renamed.MOVED_MODULES))
def test_an_old_module_path_warns_and_hands_out_the_new_modules_names(old):
    new = importlib.import_module(renamed.MOVED_MODULES[old])
    with pytest.warns(FutureWarning, match=renamed.MOVED_MODULES[old].replace(".", r"\.")):
        module = _fresh(old)
    public = [n for n in getattr(new, "__all__", dir(new)) if not n.startswith("_")]
    assert public, new
    for name in public:
        assert getattr(module, name) is getattr(new, name), (old, name)
    with pytest.raises(AttributeError):
        module.no_such_name  # noqa: B018


def test_the_previous_versions_imports_run_in_a_fresh_interpreter():
    """The import lines of the earlier exercise notebooks (2.3, 4.1, 4.2), as a student reran them."""
    code = ("import warnings; warnings.simplefilter('error', FutureWarning)\n"
            "try:\n    from gm_core.three_link_chain import three_link_jacobians\nexcept FutureWarning as w:\n"
            "    assert 'gm_core.chains.three_link' in str(w), w\nelse:\n    raise SystemExit('no warning')\n"
            "warnings.simplefilter('ignore', FutureWarning)\n"
            "from gm_core.three_link_chain import com_frame_jacobians, three_link_frames\n"
            "from gm_core.gaits import circle_gait\nfrom gm_core.locomotion import net_displacement, circle_gait as c2\n"
            "from gm_core.checks.ch4 import drift_and_turn\nfrom gm_core.chains import Chain, three_link_frames as t2\n"
            "assert c2 is circle_gait and t2 is three_link_frames\n")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_old_names_that_moved_module_warn_and_still_compute():
    old_loco = _fresh_quiet("gm_core.locomotion")
    with pytest.warns(FutureWarning, match="gm_core.systems.gaits"):
        assert old_loco.circle_gait is circle_gait
    old_ch4 = _fresh_quiet("gm_core.checks.ch4")
    g = circle_gait(0.5, (1.5, 1.5))
    with pytest.warns(FutureWarning, match="drift_and_turn"):
        old = old_ch4.drift_and_turn
    np.testing.assert_array_equal(old(g), drift_and_turn(swimmer(), g))
    # exercise 2.3's ``chains.three_link_frames``: the chains package holds it today
    assert importlib.import_module("gm_core.chains").three_link_frames is three_link_frames


def test_new_code_never_imports_through_old_paths():
    """Nothing in the course imports gm_core.renamed's old paths (tests/test_layering.py checks
    the imports; here the finder only ever answers for the listed names)."""
    finder = next(f for f in sys.meta_path if type(f).__name__ == "_MovedFinder")
    assert finder.find_spec("gm_core.systems", None) is None
    assert finder.find_spec("gm_core.locomotion", None) is not None


def _fresh_quiet(name):
    with pytest.warns(FutureWarning):
        return _fresh(name)
