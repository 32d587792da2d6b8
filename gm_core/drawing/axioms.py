"""Group or not? (book section 1.2, the group box (1.ii)-(1.v)): the four axioms tried on real
groups and on famous failures, (Z, x), (R+, +), (R, -), with the counterexample that breaks each
failing axiom.

The verdicts and counterexamples are mathematics in :mod:`gm_core.groups.axioms` (``check_axioms``,
``try_elements``); here they are laid out as a table of badges and short lines.
"""
from __future__ import annotations

from typing import ClassVar

from matplotlib.patches import Rectangle
from typing_extensions import override

from gm_core.drawing.toolkit.style import PALETTE, PathText, Scene, text_panel
from gm_core.groups.axioms import GROUP_AXIOMS, STRUCTURES, AxiomReport, Structure, check_axioms, try_elements
from gm_core.groups.axioms import structure as find_structure

__all__ = ["GroupOrNotScene", "integer_structure"]

_LAW = {"closure": "closure (1.ii)", "associativity": "associativity (1.iii)",
        "identity": "identity (1.iv)", "inverse": "inverse (1.v)"}
_HOLDS, _FAILS = PALETTE["green"], PALETTE["vermillion"]


class GroupOrNotScene(Scene):
    """A verdict per axiom for one candidate structure, with a counterexample when it fails.

    Values ``structure`` (a key of :data:`gm_core.groups.axioms.STRUCTURES`) and ``a, b, c`` (numbers
    the reader tries; for SE(2) they pick elements exp(s xi_k)). Each row: a badge (green ✓ /
    vermillion ✗), the axiom, the verdict of the counterexample search over the structure's
    sample elements, and the axiom written out at the reader's a, b, c.
    """

    ROW: ClassVar[float] = 0.2            # height of one axiom row, axes units
    TOP: ClassVar[float] = 0.84

    FIGSIZE = (8.6, 3.9)
    MARGINS = dict(left=0.01, right=0.99, bottom=0.01, top=0.99)

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        text_panel(ax)
        PathText(ax, 0.085, self.TOP + 0.02, "axiom", size=8, weight="bold", color="0.35")
        PathText(ax, 0.33, self.TOP + 0.02, "search over sample elements   ·   at your a, b, c (blue)", size=8,
                 weight="bold", color="0.35")
        self._cache: dict[str, dict[str, AxiomReport]] = {}

    @override
    def create(self) -> None:
        (ax,) = self.axes
        self.badges: list[Rectangle] = []
        self.marks: list[PathText] = []
        self.names: list[PathText] = []
        self.whys: list[PathText] = []
        self.tries: list[PathText] = []
        for k, axiom in enumerate(GROUP_AXIOMS):
            y = self.TOP - (k + 0.5) * self.ROW
            box = Rectangle((0.012, y - 0.06), 0.055, 0.12, facecolor=_HOLDS, edgecolor="none", zorder=2)
            ax.add_patch(box)
            self.badges.append(box)
            self.marks.append(PathText(ax, 0.0395, y, "", size=13, ha="center", va="center", color="w",
                                       weight="bold", zorder=3))
            self.names.append(PathText(ax, 0.085, y, _LAW[axiom], size=9, va="center"))
            self.whys.append(PathText(ax, 0.33, y + 0.07, "", size=8.5, va="top"))
            self.tries.append(PathText(ax, 0.33, y - 0.075, "", size=8, va="baseline",
                                       color=PALETTE["blue"], family="monospace"))
        self.title = PathText(ax, 0.012, 0.955, "", size=10.5, weight="bold", va="top")

    @override
    def set(self, structure: str | Structure = "(ℤ, ×)", a: float = 2.0, b: float = 3.0, c: float = -1.0) -> None:
        S = find_structure(structure)
        if S.name not in self._cache:
            self._cache[S.name] = check_axioms(S)
        self.verdicts = self._cache[S.name]
        self.tried = try_elements(S, a, b, c)
        failing = [ax for ax in GROUP_AXIOMS if not self.verdicts[ax].holds]
        self.is_group = not failing
        for k, axiom in enumerate(GROUP_AXIOMS):
            v = self.verdicts[axiom]
            self.badges[k].set_facecolor(_HOLDS if v.holds else _FAILS)
            self.marks[k].set_text("✓" if v.holds else "✗")
            self.whys[k].set_text(v.why if not v.holds else "holds: " + v.why)
            self.whys[k].set_color("k" if v.holds else _FAILS)
            self.tries[k].set_text(self.tried[axiom])
        if self.is_group:
            self.title.set_text(f"{S.name} is a group: all four axioms hold")
            self.title.set_color(_HOLDS)
        else:
            self.title.set_text(f"{S.name} is NOT a group: {', '.join(failing)} fail"
                                + ("s" if len(failing) == 1 else ""))
            self.title.set_color(_FAILS)


def integer_structure(name: str | Structure) -> bool:
    """True if every member of the structure ``name`` is an integer (its controls take whole numbers)."""
    return find_structure(name).integer


#: the candidate structures, in the order the panel offers them
CHOICES = list(STRUCTURES)
