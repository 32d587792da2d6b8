"""Regenerate the author's numbers for the arc chains and continuum bodies: his own code, run at a few shapes.

The author's Python (rlhatton/GeometryOfMotionCodebase, package ``geomotion``) builds the chain of
his example E702 (revolute joints, an arc joint, an arc link) and the continuum bodies of E720
(constant curvature) and E727 (stretch). This script runs his classes at a few configurations and
writes the poses to ``tests/data/author_reference.json`` with the commit they came from;
``tests/test_chain_arcs.py`` and ``tests/test_continuum.py`` compare the course's models with them, so
neither the tests nor a student need his code, only this script does::

    git clone https://github.com/rlhatton/GeometryOfMotionCodebase /tmp/gomc
    python -m pip install --target /tmp/gomc_deps numdifftools     # his only extra dependency
    .venv/bin/python tools/author_reference.py /tmp/gomc --deps /tmp/gomc_deps

His continuum body integrates its backbone with ``scipy.integrate.solve_ivp`` at scipy's default
tolerances (rtol 1e-3); here the same call runs with rtol = atol = 1e-12 (the only change, made by
wrapping the ``solve_ivp`` his module imported), so that the numbers test the model, not the
tolerance. The repository is read, never copied into this course.
"""
from __future__ import annotations

import argparse
import functools
import importlib
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any, cast

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "data" / "author_reference.json"
TOL = 1e-12

# E702: R, R, arc joint, R; links straight 1, straight 1, an arc of length 1, straight 1.
CHAIN_CASES = [  # (arc joint curvature, arc link curvature, joint values)
    (1.0, 1.0, [1.0, -0.5, 0.25, 1.0]),     # E702 itself
    (1.0, 1.0, [-0.3, 0.9, -0.6, 0.2]),
    (2.0, -0.5, [0.4, 0.7, 0.35, -1.1]),
]
S_POINTS = np.linspace(0.0, 1.0, 11).tolist()
# Continuum bodies on s in [0, 1]: curvature kappa(s; r) and stretch sigma(s; r) as in E720/E727.
CONTINUUM_CASES = [
    ("E720 constant curvature", "constant", [1.0]),
    ("E727 stretch", "e727", [1.0]),
    ("serpenoid curvature and E727 stretch", "serpenoid+e727", [2.0, -1.0, 0.4]),
]


def _shape_function(kind, G):
    def h(shape, s, t):
        if kind == "constant":
            return G.Lie_alg_vector([0, 0, shape[0]])
        if kind == "e727":
            return G.Lie_alg_vector([-shape[0] * np.cos(s * 4 * np.pi), 0, 0])
        k = shape[0] * np.cos(2 * np.pi * s) + shape[1] * np.sin(2 * np.pi * s)
        return G.Lie_alg_vector([-shape[2] * np.cos(s * 4 * np.pi), 0, k])
    return h


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("repo", type=Path, help="a checkout of rlhatton/GeometryOfMotionCodebase")
    ap.add_argument("--deps", type=Path, help="a folder holding numdifftools, put on sys.path first")
    ap.add_argument("--commit", help="the commit of the checkout (default: git rev-parse HEAD in it)")
    args = ap.parse_args(argv)
    os.environ.setdefault("MPLBACKEND", "Agg")
    if args.deps:
        sys.path.insert(0, str(args.deps))
    sys.path.insert(0, str(args.repo))
    # his package is found on the path given, not installed (so no course dependency names it)
    cb, dm, kc, rb = (cast(Any, importlib.import_module(f"geomotion.{m}"))
                      for m in ("continuumbody", "diffmanifold", "kinematicchain", "rigidbody"))

    commit = args.commit or subprocess.run(["git", "-C", str(args.repo), "rev-parse", "HEAD"], check=True,
                                           capture_output=True, text=True).stdout.strip()
    G = rb.SE2
    chains = []
    for k_joint, k_link, alpha in CHAIN_CASES:
        rot, arc = G.Lie_alg_vector([0, 0, 1]), G.Lie_alg_vector([1, 0, k_joint])
        straight, bent = G.element([1, 0, 0]), G.Lie_alg_vector([1, 0, k_link]).exp_R
        joints = [kc.Joint(rot), kc.Joint(rot), kc.Joint(arc), kc.Joint(rot)]
        links = [kc.Link(straight), kc.Link(straight), kc.Link(bent), kc.Link(straight)]
        chain = kc.KinematicChainSequential(links, joints)
        chain.set_configuration(alpha)
        chains.append({"arc_joint_curvature": k_joint, "arc_link_curvature": k_link, "alpha": alpha,
                       "f": [np.ravel(lk.proximal_position.value).tolist() for lk in links],
                       "g": [np.ravel(lk.medial_position.value).tolist() for lk in links],
                       "h": [np.ravel(lk.distal_position.value).tolist() for lk in links]})

    dm.solve_ivp = functools.partial(dm.solve_ivp, rtol=TOL, atol=TOL)
    bodies = []
    for name, kind, shape in CONTINUUM_CASES:
        body = cb.ContinuumBody(_shape_function(kind, G), [0, 1])
        body.set_configuration(shape)
        poses = np.asarray(body.shape_locus.sol(np.array(S_POINTS))).T
        bodies.append({"name": name, "kind": kind, "shape": shape, "s": S_POINTS, "poses": poses.tolist()})

    OUT.parent.mkdir(parents=True, exist_ok=True)
    data = {"source": "rlhatton/GeometryOfMotionCodebase", "commit": commit,
            "regenerate": "tools/author_reference.py", "solve_ivp_tolerance": TOL,
            "chains": chains, "continuum": bodies}
    OUT.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {OUT.relative_to(ROOT)}: {len(chains)} chains, {len(bodies)} continuum bodies")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
