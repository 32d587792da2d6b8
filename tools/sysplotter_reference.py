"""Regenerate the sysplotter reference values: sysplotter's own code, run in GNU Octave, on its system files.

For every system file ``sysf_<name>.m`` of sysplotter (OSU-LRAM/GeometricSystemPlotter) this
initialises the system with sysplotter's own code and evaluates what the file defines at a few
shapes: ``s.A`` (or ``s.A_num ./ s.A_den`` for the files that give a numerator and denominator)
and ``s.metric`` when the file has one. The values are written to
``gm_core/systems/sysplotter_reference.json`` with the commit of sysplotter they came from and
Octave's version; :func:`gm_core.systems.catalog.parity` and ``tests/test_catalog.py`` compare the
catalog with them, so neither the tests nor a student need Octave, only this script does::

    git clone https://github.com/OSU-LRAM/GeometricSystemPlotter /tmp/sysplotter
    .venv/bin/python tools/sysplotter_reference.py /tmp/sysplotter                 # every file
    .venv/bin/python tools/sysplotter_reference.py /tmp/sysplotter three_link_lowRe # some files
    .venv/bin/python tools/sysplotter_reference.py /tmp/sysplotter --passive        # the passive swimmer

``--passive`` runs instead sysplotter's passive-joint simulation (``simulate2DPassiveSwimmer.m``) on
``three_link_passive`` with joint 2 driven by a sine (:data:`PASSIVE_DRIVE`) and writes
``gm_core/systems/sysplotter_passive.json``, which ``tests/test_passive.py`` compares with
:mod:`gm_core.systems.passive`. sysplotter feeds that function tables of its metric and their gradients;
here it gets the file's own ``s.A`` and ``s.metric`` and central differences (step 1e-5) of ``s.metric``,
so that the only approximation left is its ode45 at default tolerances. It takes about four minutes.

Shapes: for each file, ``SHAPES_PER_FILE`` points drawn from a generator seeded by the file's name,
uniform in the middle 70 % of the file's own ``s.grid_range`` and at least 20 % of the half-range
from its centre (the modal continuous bodies are singular at zero amplitude). A file that Octave
cannot evaluate is stored with its error message, never left out: the parity table shows it.
The repository is read, never copied into this course.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import zlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "gm_core" / "systems" / "sysplotter_reference.json"
PASSIVE_OUT = ROOT / "gm_core" / "systems" / "sysplotter_passive.json"
#: The drive of the passive reference: joint 2 = amplitude sin(2 pi t / period).
PASSIVE_DRIVE = {"file": "three_link_passive", "amplitude": 0.8, "period": 1.0, "samples": 101}
SHAPES_PER_FILE = 4
TIMEOUT = 900           # seconds per file (the continuous bodies integrate with ode45)

# Both drivers start here: sysplotter's paths (as its GUI sets them) and the file's name.
_PATHS = r"""sp = fullfile('{root}', 'ProgramFiles');
pathnames.sysplotterpath = [sp filesep];
pathnames.syspath = fullfile('{root}', 'UserFiles', 'GenericUser', 'Systems');
addpath(pathnames.syspath);
addpath(genpath(fullfile(sp, 'Utilities')));
warning('off', 'all');
name = 'sysf_{name}';
"""

# One Octave process per file, so that no file's path or globals reach another. The unit
# offsets ``u`` (one row per shape) are scaled by the file's grid_range in Octave.
_DRIVER = _PATHS + r"""
out = struct('name', '{name}', 'error', '', 'display_name', '', 'shapes', [], 'A', [], 'metric', []);
try
  d = feval(name, 'dependency', pathnames);
  for k = 1:numel(d.dependency), addpath(genpath(d.dependency{{k}})); end
  addpath(genpath(fullfile(sp, 'sys_calcpath_fcns', 'DERIVESTsuite')));   % jacobianest (general curvature)
  addpath('{shims}');      % last added, so first on the path
  out.display_name = feval(name, 'name', pathnames);
  s = feval(name, 'initialize', pathnames);
  u = {u};
  n = size(u, 2);
  gr = reshape(s.grid_range, 2, [])';
  if size(gr, 1) == 1, gr = repmat(gr, n, 1); end
  c = mean(gr, 2)'; h = (gr(:, 2) - gr(:, 1))' / 2;
  shapes = c + u .* h;
  As = {{}}; Ms = {{}};
  for i = 1:size(shapes, 1)
    a = num2cell(shapes(i, :));
    if isfield(s, 'A')
      A = s.A(a{{:}});
    else
      A = s.A_num(a{{:}});
      if isfield(s, 'A_den'), A = A ./ s.A_den(a{{:}}); end
    end
    if iscell(A), A = cell2mat(A); end
    As{{i}} = A;
    if isfield(s, 'metric')
      M = s.metric(a{{:}});
      if iscell(M), M = cell2mat(M); end
      Ms{{i}} = M;
    end
  end
  out.shapes = shapes;
  out.A = As;
  if isfield(s, 'metric'), out.metric = Ms; else out.metric = 'none'; end
catch err
  out.error = err.message;
  for k = 1:numel(err.stack), out.error = sprintf('%s | %s:%d', out.error, err.stack(k).name, err.stack(k).line); end
end
fid = fopen('{result}', 'w');
fprintf(fid, '%s', jsonencode(out));
fclose(fid);
"""


# Where Octave differs from MATLAB, or a file needs MATLAB's Symbolic toolbox, a shim on the path
# in front of sysplotter's own functions. Each is a line or two; none changes sysplotter's physics.
_SHIMS = {
    # MATLAB's deval (evaluate an ode45 solution structure) does not exist in Octave: a cubic
    # spline through Octave's refined output points (sysplotter's ode45 tolerances dominate).
    "deval.m": """function y = deval(sol, t)
  [x, i] = sort(sol.x(:));
  y = interp1(x, sol.y(:, i).', t(:).', 'spline', 'extrap').';
end
""",
    # The generated curvature files are made by make_curvdef with the Symbolic toolbox at every
    # initialisation; here the shipped generated file is used instead (see _curvature_files).
    "make_curvdef.m": """function f = make_curvdef(curv, params, name, varargin)
  f = str2func(['curv_' name]);
end
""",
    "syms.m": """function syms(varargin)
  for k = 1:nargin, assignin('caller', varargin{k}, 0); end
end
""",
    # Octave cannot parse the enumeration in Utilities/LieGroups.m; twin_rotor only names LieGroups.SO3.
    "LieGroups.m": """function g = LieGroups()
  g = struct('SE2', 'SE2', 'SO3', 'SO3');
end
""",
    "subs.m": """function out = subs(expr, varargin)
  out = expr;
end
""",
    # wrapToPi is in MATLAB's Mapping toolbox (Octave's mapping package, not installed here).
    "wrapToPi.m": """function a = wrapToPi(a)
  a = mod(a + pi, 2 * pi) - pi;
end
""",
}

# The passive swimmer: sysplotter's own simulate2DPassiveSwimmer on the file's own functions.
_PASSIVE_DRIVER = _PATHS + r"""
d = feval(name, 'dependency', pathnames);
for k = 1:numel(d.dependency), addpath(genpath(d.dependency{{k}})); end
addpath(fullfile(sp, 'GaitOptimization', 'optimalgaitgenerator_fcns'));
addpath('{shims}');
s = feval(name, 'initialize', pathnames);
h = 1e-5;
funs.A_fun = s.A;
funs.metric_fun = s.metric;
funs.dmdr1_fun = @(a1, a2) (s.metric(a1 + h, a2) - s.metric(a1 - h, a2)) / (2 * h);
funs.dmdr2_fun = @(a1, a2) (s.metric(a1, a2 + h) - s.metric(a1, a2 - h)) / (2 * h);
T = {period}; amp = {amplitude}; w = 2 * pi / T;
p.rc = @(t) amp * sin(w * t);
p.drc = @(t) amp * w * cos(w * t);
p.ddrc = @(t) -amp * w^2 * sin(w * t);
[displ, cost, angles, final_loop] = simulate2DPassiveSwimmer(p, T, funs, s.physics.k, s.physics.b);
out = struct('k', s.physics.k, 'b', s.physics.b, 'g', final_loop(1:3, end)', 'displ', displ, 'cost', cost, ...
             'times', linspace(0, T, size(angles, 2)), 'passive', angles(1, :), 'driven', angles(2, :));
fid = fopen('{result}', 'w');
fprintf(fid, '%s', jsonencode(out));
fclose(fid);
"""


# One-line changes to copies of sysplotter's files (file name -> (text, replacement)), each for an
# Octave difference, never for the physics.
_PATCHES = {
    # Octave's ode45 takes an empty options argument as an extra argument of the ODE function.
    "ode_multistart.m": ("options = [];", "options = odeset();"),
    # Octave does not capture r in @(s) when a nested @(k,r) names a parameter r too.
    "backbone_from_curvature_bases.m": ("@(k,r) theta_fun_helper(k,r,s)", "@(k,rk) theta_fun_helper(k,rk,s)"),
    # Octave's ode45 wants a column as its initial value (MATLAB takes a matrix in column order;
    # the ODE functions already return their derivative as a column).
    "LowRE_connection_continuous.m": ("zeros(3,3+length(shapeparams)))", "zeros(3*(3+length(shapeparams)),1))"),
    "LowRE_metric_continuous.m": ("zeros(length(shapeparams)));", "zeros(length(shapeparams)^2,1));"),
}


def write_shims(root: Path, folder: Path) -> None:
    """The shims above, plus the copies of sysplotter's files that need a one-line change in Octave."""
    folder.mkdir()
    for name, text in _SHIMS.items():
        (folder / name).write_text(text)
    for name, (old, new) in _PATCHES.items():
        text = next((root / "ProgramFiles").rglob(name)).read_text()
        if old not in text:
            raise SystemExit(f"{name}: the line to patch for Octave is not there any more: {old!r}")
        (folder / name).write_text(text.replace(old, new, 1))
    # Shipped generated curvature files that close their function twice (make_curvdef appends an
    # 'end' to matlabFunction's output, which already has one): Octave refuses them.
    for f in (root / "UserFiles" / "GenericUser" / "Systems").glob("curv_*.m"):
        lines = [line for line in f.read_text().splitlines() if line.strip()]
        if len(lines) >= 2 and lines[-1].strip() == "end" and lines[-2].strip() == "end":
            (folder / f.name).write_text("\n".join(lines[:-1]) + "\n")


def unit_offsets(name: str, n_shape: int) -> np.ndarray:
    """``SHAPES_PER_FILE`` offsets in [-0.7, 0.7]^n with norm >= 0.2, seeded by the file's name."""
    rng = np.random.default_rng(zlib.crc32(name.encode()))
    rows = []
    while len(rows) < SHAPES_PER_FILE:
        u = rng.uniform(-0.7, 0.7, n_shape)
        if np.linalg.norm(u) >= 0.2:
            rows.append(u)
    return np.array(rows)


def octave_matrix(a: np.ndarray) -> str:
    return "[" + "; ".join(" ".join(f"{x:.17g}" for x in row) for row in a) + "]"


def shape_count(root: Path, name: str) -> int:
    """The number of shape variables of ``sysf_<name>.m``: the arguments of its s.A (or s.A_num)."""
    text = (root / "UserFiles" / "GenericUser" / "Systems" / f"sysf_{name}.m").read_text(errors="replace")
    for key in ("s.A = @(", "s.A_num = @("):
        for line in text.splitlines():
            if line.strip().startswith("%"):
                continue
            i = line.find(key)
            if i >= 0:
                args = line[i + len(key):].split(")", 1)[0]
                return len([a for a in args.split(",") if a.strip()])
    return 2     # files that give s.A_num as a named function of two shapes (diffdrive)


def run_file(root: Path, name: str) -> dict:
    n = shape_count(root, name)
    u = unit_offsets(name, n)
    with tempfile.TemporaryDirectory() as tmp:
        result = Path(tmp) / "out.json"
        script = Path(tmp) / "driver.m"
        write_shims(root, Path(tmp) / "shims")
        script.write_text(_DRIVER.format(root=root, name=name, u=octave_matrix(u), result=result, shims=Path(tmp) / "shims"))
        proc = subprocess.run(["octave", "--no-gui", "--no-window-system", "--quiet", str(script)],
                              capture_output=True, text=True, timeout=TIMEOUT, cwd=tmp)
        if not result.exists():
            return {"name": name, "error": f"octave exited with {proc.returncode}: {proc.stderr[-500:]}"}
        out = json.loads(result.read_text())
    if out.get("metric") == "none":
        out["metric"] = None
    for key in ("shapes", "A", "metric"):          # jsonencode turns a single matrix into a list of rows
        if out.get(key) is not None and not isinstance(out[key], list):
            out[key] = [out[key]]
    return out


def write_passive_reference(root: Path, commit: str, version: str) -> None:
    """sysplotter's passive-swimmer simulation (see the module docstring) as JSON, for tests/test_passive.py."""
    drive = PASSIVE_DRIVE
    with tempfile.TemporaryDirectory() as tmp:
        result, script = Path(tmp) / "out.json", Path(tmp) / "driver.m"
        write_shims(root, Path(tmp) / "shims")
        script.write_text(_PASSIVE_DRIVER.format(root=root, name=drive["file"], shims=Path(tmp) / "shims", result=result,
                                                 period=drive["period"], amplitude=drive["amplitude"]))
        proc = subprocess.run(["octave", "--no-gui", "--no-window-system", "--quiet", str(script)],
                              capture_output=True, text=True, timeout=TIMEOUT, cwd=tmp)
        if not result.exists():
            raise SystemExit(f"octave exited with {proc.returncode}: {proc.stderr[-500:]}")
        out = json.loads(result.read_text())
    record = {"source": "OSU-LRAM/GeometricSystemPlotter (MIT licence), ProgramFiles/GaitOptimization/"
                        "optimalgaitgenerator_fcns/simulate2DPassiveSwimmer.m", "sysplotter_commit": commit,
              "octave": version, "drive": drive, **out}
    PASSIVE_OUT.write_text(json.dumps(record) + "\n")
    print(f"wrote {PASSIVE_OUT.relative_to(ROOT)}")


GRANULAR = ROOT / "gm_core" / "systems" / "sysplotter_granular.json"


def write_granular_table(root: Path, commit: str) -> None:
    """three_link_granular's measured connection (Granular_Local_Connection_Matrix.mat) as JSON, for the catalog."""
    from scipy.io import loadmat

    mat = loadmat(root / "UserFiles" / "GenericUser" / "Systems" / "Granular_Local_Connection_Matrix.mat")
    a1, a2 = mat["alpha1"], mat["alpha2"]          # ndgrid: a1 varies along rows, a2 along columns
    out = {"source": "OSU-LRAM/GeometricSystemPlotter (MIT licence), UserFiles/GenericUser/Systems/"
                     "Granular_Local_Connection_Matrix.mat", "sysplotter_commit": commit,
           "alpha1": a1[:, 0].tolist(), "alpha2": a2[0, :].tolist()}
    for key in ("Ax1", "Ax2", "Ay1", "Ay2", "Atheta1", "Atheta2"):
        out[key] = mat[key].tolist()
    GRANULAR.write_text(json.dumps(out) + "\n")
    print(f"wrote {GRANULAR.relative_to(ROOT)}")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("sysplotter", type=Path, help="a checkout of OSU-LRAM/GeometricSystemPlotter")
    p.add_argument("names", nargs="*", help="file names without sysf_ and .m (default: every file)")
    p.add_argument("--commit", help="sysplotter's commit, for a copy that is not a git checkout")
    p.add_argument("--passive", action="store_true", help="only the passive swimmer's simulation (sysplotter_passive.json)")
    args = p.parse_args(argv)
    root = args.sysplotter.resolve()
    systems = root / "UserFiles" / "GenericUser" / "Systems"
    if not systems.is_dir():
        p.error(f"{root} is not a sysplotter checkout (no UserFiles/GenericUser/Systems)")
    names = args.names or sorted(f.stem[len("sysf_"):] for f in systems.glob("sysf_*.m"))
    data = json.loads(OUT.read_text()) if OUT.exists() else {"files": {}}
    commit = args.commit or subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    version = subprocess.run(["octave", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    data.update({"sysplotter_commit": commit or data.get("sysplotter_commit", "unknown"), "octave": version})
    if args.passive:
        write_passive_reference(root, data["sysplotter_commit"], version)
        return 0
    if "three_link_granular" in names:
        write_granular_table(root, data["sysplotter_commit"])
    for name in names:
        out = run_file(root, name)
        data["files"][name] = out
        print(f"{name:40s} {'error: ' + out['error'][:60] if out.get('error') else 'ok'}", flush=True)
    data["files"] = dict(sorted(data["files"].items()))
    OUT.parent.mkdir(parents=True, exist_ok=True)
    head = {k: v for k, v in data.items() if k != "files"}
    rows = [f" {json.dumps(k)}: {json.dumps(v)}" for k, v in data["files"].items()]    # one line per file
    OUT.write_text(json.dumps(head, indent=1)[:-2] + ',\n "files": {\n' + ",\n".join(rows) + "\n }\n}\n")
    print(f"wrote {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
