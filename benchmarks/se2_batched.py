#!/usr/bin/env python
"""Batched SE(2) maps: gm_core versus a plain-numpy reference (and peers, when installed).

Prints nanoseconds per element for ``exp``, ``log``, ``compose``, ``inverse`` and ``Ad`` at
N = 1e3 and 1e6 elements, for

* ``gm_core``   -- ``gm_core.SE2`` (validated public API),
* ``reference`` -- the same closed forms written inline in plain numpy, no validation and no
  function-call layers (defined in this file; it is the yardstick for gm_core's overhead),
* ``jaxlie`` and ``geomstats`` -- peer libraries, measured in a subprocess with another Python
  (their own virtual environment), so nothing is installed into the project's .venv.

Usage::

    .venv/bin/python benchmarks/se2_batched.py                       # gm_core vs reference
    .venv/bin/python benchmarks/se2_batched.py --peers /tmp/peers-venv/bin/python
    GM_BENCH_PEERS=/tmp/peers-venv/bin/python .venv/bin/python benchmarks/se2_batched.py

Timing: ``time.perf_counter`` around a loop of calls sized to take at least ~50 ms, repeated
with gm_core and the reference interleaved; the whole measurement alternates local and peer runs
``--rounds`` times (default 2) and the table shows each cell's best (medians are in ``--json``).
The gm_core/reference ratio is the median over adjacent (interleaved) repeat pairs, which is far
less sensitive to other processes' load than a ratio of independent bests. jax runs with float64
enabled and XLA limited to one thread (numpy's elementwise maps are single-threaded too); jitted
functions are compiled before timing and synchronised with ``block_until_ready``. geomstats runs
on its numpy backend. Peers return their own representations (jaxlie: (cos, sin, x, y);
geomstats: (theta, x, y)); the worker checks their results against the reference formulas
before timing them and reports ``mismatch`` if they disagree.

The script itself needs only numpy (the worker mode imports nothing from gm_core).
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time

import numpy as np

OPS = ("exp", "log", "compose", "inverse", "Ad")
SIZES = (1_000, 1_000_000)
PEERS = ("jaxlie", "geomstats")
MIN_REPEAT_SECONDS = 0.05
#: The timer: time.perf_counter (wall clock, the default) or time.process_time (CPU time of this
#: process, which leaves out time spent waiting for a core on a busy shared machine).
CLOCKS = {"perf_counter": time.perf_counter, "process_time": time.process_time}
clock = time.perf_counter


# ----------------------------------------------------------------------------- plain reference
# The formulas of gm_core.groups._SE2 written inline: no validation, no wrappers.
def ref_exp(xi):
    w = xi[:, 2]
    h = 0.5 * w
    c = np.cos(h)
    s = np.sin(h)
    k = np.divide(s, h, out=np.ones_like(h), where=h != 0)
    vx = xi[:, 0]
    vy = xi[:, 1]
    out = np.empty_like(xi)
    out[:, 0] = k * (c * vx - s * vy)
    out[:, 1] = k * (s * vx + c * vy)
    out[:, 2] = w
    return out


def ref_log(g):
    t = g[:, 2]
    t = t - 2 * np.pi * np.ceil((t - np.pi) / (2 * np.pi))
    h = 0.5 * t
    c = np.cos(h)
    s = np.sin(h)
    k = np.divide(s, h, out=np.ones_like(h), where=h != 0)
    x = g[:, 0]
    y = g[:, 1]
    out = np.empty_like(g)
    out[:, 0] = (c * x + s * y) / k
    out[:, 1] = (c * y - s * x) / k
    out[:, 2] = t
    return out


def ref_compose(g, h):
    t = g[:, 2]
    c = np.cos(t)
    s = np.sin(t)
    u = h[:, 0]
    v = h[:, 1]
    out = np.empty_like(g)
    out[:, 0] = g[:, 0] + c * u - s * v
    out[:, 1] = g[:, 1] + s * u + c * v
    out[:, 2] = t + h[:, 2]
    return out


def ref_inverse(g):
    t = g[:, 2]
    c = np.cos(t)
    s = np.sin(t)
    x = g[:, 0]
    y = g[:, 1]
    out = np.empty_like(g)
    out[:, 0] = -c * x - s * y
    out[:, 1] = s * x - c * y
    out[:, 2] = -t
    return out


def ref_Ad(g):
    t = g[:, 2]
    c = np.cos(t)
    s = np.sin(t)
    M = np.zeros((g.shape[0], 3, 3))
    M[:, 0, 0] = c
    M[:, 0, 1] = -s
    M[:, 0, 2] = g[:, 1]
    M[:, 1, 0] = s
    M[:, 1, 1] = c
    M[:, 1, 2] = -g[:, 0]
    M[:, 2, 2] = 1.0
    return M


REFERENCE = {"exp": ref_exp, "log": ref_log, "compose": ref_compose, "inverse": ref_inverse,
             "Ad": ref_Ad}


def make_inputs(n, seed=0):
    """Algebra vectors xi and elements g, h (angles in (-pi, pi)), float64, shape (n, 3)."""
    rng = np.random.default_rng(seed)
    xi = rng.uniform(-3.0, 3.0, (n, 3))
    g = rng.uniform(-3.0, 3.0, (n, 3))
    h = rng.uniform(-3.0, 3.0, (n, 3))
    xi[:, 2] = rng.uniform(-np.pi, np.pi, n)
    g[:, 2] = rng.uniform(-np.pi, np.pi, n)
    h[:, 2] = rng.uniform(-np.pi, np.pi, n)
    return {"xi": xi, "g": g, "h": h}


ARGS = {"exp": ("xi",), "log": ("g",), "compose": ("g", "h"), "inverse": ("g",), "Ad": ("g",)}


# ----------------------------------------------------------------------------- timing
def measure(cases, repeats):
    """Time several cases with interleaved repeats, so that load from other processes on a shared
    machine hits them alike. ``cases``: name -> (fn, args, sync or None). Returns
    name -> (best, median) seconds per call; each repeat loops >= MIN_REPEAT_SECONDS of calls.
    """
    runners, loops = {}, {}
    for name, (fn, args, sync) in cases.items():
        def once(fn=fn, args=args, sync=sync):
            r = fn(*args)
            if sync is not None:
                sync(r)
        once()                                            # warm up (and compile, for jax)
        t0 = clock()
        once()
        single = clock() - t0
        runners[name] = once
        loops[name] = max(1, int(MIN_REPEAT_SECONDS / max(single, 1e-9)))
    times = {name: [] for name in cases}
    start = clock()
    for i in range(repeats):
        for name, once in runners.items():
            t0 = clock()
            for _ in range(loops[name]):
                once()
            times[name].append((clock() - t0) / loops[name])
        if i >= 2 and clock() - start > 20.0:  # very slow peers: three repeats suffice
            break
    return {name: (float(np.min(t)), float(np.median(t)), t) for name, t in times.items()}


def _per_element(res, n):
    return {"best": res[0] / n * 1e9, "median": res[1] / n * 1e9}


def machine():
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        load = "%.1f" % os.getloadavg()[0]
    except (AttributeError, OSError):
        load = "?"
    return {"cpu": cpu, "cores": os.cpu_count(), "python": platform.python_version(),
            "numpy": np.__version__, "load": load}


# ----------------------------------------------------------------------------- gm_core + reference
def run_local(sizes, repeats):
    from gm_core import SE2

    gm = {"exp": SE2.exp, "log": SE2.log, "compose": SE2.compose, "inverse": SE2.inverse,
          "Ad": SE2.Ad}
    out = {"gm_core": {}, "reference": {}, "pair_ratios": {}}
    for n in sizes:
        data = make_inputs(n)
        for op in OPS:
            args = [data[a] for a in ARGS[op]]
            a, b = gm[op](*args), REFERENCE[op](*args)
            if not np.allclose(a, b, rtol=1e-12, atol=1e-12):
                raise SystemExit(f"gm_core.SE2.{op} disagrees with the reference formula")
            res = measure({"gm_core": (gm[op], args, None),
                           "reference": (REFERENCE[op], args, None)}, repeats)
            for name, r in res.items():
                out[name].setdefault(op, {})[str(n)] = _per_element(r, n)
            # each gm_core repeat ran right next to a reference repeat: their ratio sees the same load
            pairs = np.array(res["gm_core"][2]) / np.array(res["reference"][2])
            out["pair_ratios"].setdefault(op, {})[str(n)] = [float(x) for x in pairs]
    return out


# ----------------------------------------------------------------------------- peers (worker mode)
def _check(name, op, got, want, notes):
    if not np.allclose(got, want, rtol=1e-9, atol=1e-9):
        notes.append(f"{name}.{op}: results differ from the reference formulas")
        return False
    return True


def _jaxlie_suite(notes):
    import jax
    jax.config.update("jax_enable_x64", True)
    import jax.numpy as jnp
    import jaxlie

    SE2 = jaxlie.SE2

    def params(g):          # our (x, y, theta) -> jaxlie (cos, sin, x, y), outside the timing
        return jnp.asarray(np.stack([np.cos(g[:, 2]), np.sin(g[:, 2]), g[:, 0], g[:, 1]], -1))

    def to_xyt(p):
        p = np.asarray(p)
        return np.stack([p[:, 2], p[:, 3], np.arctan2(p[:, 1], p[:, 0])], -1)

    fns = {
        "exp": jax.jit(lambda xi: SE2.exp(xi).parameters()),
        "log": jax.jit(lambda p: SE2(p).log()),
        "compose": jax.jit(lambda p, q: (SE2(p) @ SE2(q)).parameters()),
        "inverse": jax.jit(lambda p: SE2(p).inverse().parameters()),
        "Ad": jax.jit(lambda p: SE2(p).adjoint()),
    }

    def prepare(op, data):
        if op == "exp":
            return [jnp.asarray(data["xi"])]
        if op == "compose":
            return [params(data["g"]), params(data["h"])]
        return [params(data["g"])]

    def verify(op, data, res):
        small = {k: v[:200] for k, v in data.items()}
        want = REFERENCE[op](*[small[a] for a in ARGS[op]])
        got = np.asarray(fns[op](*prepare(op, small)))
        if op in ("exp", "compose", "inverse"):
            got = to_xyt(got)
            got[:, 2] = want[:, 2] + np.angle(np.exp(1j * (got[:, 2] - want[:, 2])))
        return _check("jaxlie", op, got, want, notes)

    return fns, prepare, verify, (lambda r: r.block_until_ready())


def _geomstats_suite(notes):
    os.environ.setdefault("GEOMSTATS_BACKEND", "numpy")
    from geomstats.geometry.special_euclidean import SpecialEuclidean

    G = SpecialEuclidean(n=2, point_type="vector")     # vectors (theta, x, y)
    perm = [2, 0, 1]
    back = [1, 2, 0]
    fns = {"exp": G.exp, "log": G.log, "compose": G.compose, "inverse": G.inverse}

    def prepare(op, data):
        return [np.ascontiguousarray(data[a][:, perm]) for a in ARGS[op]]

    def verify(op, data, res):
        small = {k: v[:200] for k, v in data.items()}
        want = REFERENCE[op](*[small[a] for a in ARGS[op]])
        got = np.asarray(fns[op](*prepare(op, small)))[:, back]
        if op != "log":
            got[:, 2] = want[:, 2] + np.angle(np.exp(1j * (got[:, 2] - want[:, 2])))
        return _check("geomstats", op, got, want, notes)

    return fns, prepare, verify, None


def run_peers(sizes, repeats):
    """Worker: time the peers importable in *this* interpreter; JSON on stdout."""
    os.environ.setdefault("XLA_FLAGS", "--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1")
    os.environ.setdefault("JAX_PLATFORMS", "cpu")
    result = {"machine": machine(), "versions": {}, "timings": {}, "notes": []}
    for peer, suite in (("jaxlie", _jaxlie_suite), ("geomstats", _geomstats_suite)):
        try:
            mod = __import__(peer)
            fns, prepare, verify, sync = suite(result["notes"])
        except Exception as exc:          # not installed or broken: report, keep going
            result["notes"].append(f"{peer}: not available ({type(exc).__name__}: {exc})"[:200])
            continue
        try:
            from importlib.metadata import version
            result["versions"][peer] = version(peer)
        except Exception:
            result["versions"][peer] = getattr(mod, "__version__", "?")
        timings = result["timings"].setdefault(peer, {})
        for n in sizes:
            data = make_inputs(n)
            for op in OPS:
                if op not in fns:
                    timings.setdefault(op, {})[str(n)] = "n/a"
                    continue
                try:
                    args = prepare(op, data)
                    if not verify(op, data, None):
                        timings.setdefault(op, {})[str(n)] = "mismatch"
                        continue
                    pair = measure({peer: (fns[op], args, sync)}, repeats)[peer]
                    timings.setdefault(op, {})[str(n)] = _per_element(pair, n)
                except Exception as exc:
                    result["notes"].append(f"{peer}.{op} at N={n}: {type(exc).__name__}: {exc}"[:200])
                    timings.setdefault(op, {})[str(n)] = "error"
    json.dump(result, sys.stdout)


def peers_from(python, sizes, repeats):
    cmd = [python, os.path.abspath(__file__), "--worker", "--repeats", str(repeats),
           "--clock", next(k for k, v in CLOCKS.items() if v is clock),
           "--sizes", *[str(n) for n in sizes]]
    env = dict(os.environ, GEOMSTATS_BACKEND="numpy", JAX_PLATFORMS="cpu",
               XLA_FLAGS="--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1")
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=1800)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return {"timings": {}, "versions": {}, "notes": [f"peers: could not run {python}: {exc}"]}
    try:
        return json.loads(proc.stdout)
    except json.JSONDecodeError:
        tail = (proc.stderr or "").strip().splitlines()[-3:]
        return {"timings": {}, "versions": {}, "notes": [f"peers: worker failed: {' | '.join(tail)}"]}


# ----------------------------------------------------------------------------- report
def _cell(entry):
    if isinstance(entry, dict):
        return f"{entry['best']:.1f}"
    return "not installed" if entry is None else str(entry)


def _fmt_n(n):
    return f"1e{int(round(np.log10(n)))}" if n >= 10 and 10 ** round(np.log10(n)) == n else str(n)


def report(local, peers, sizes):
    info = machine()
    lines = [
        f"Machine: {info['cpu']}, {info['cores']} cores (1-min load average {info['load']} at the end); "
        f"Python {info['python']}, numpy {info['numpy']}",
    ]
    versions = peers.get("versions", {}) if peers else {}
    if peers and "machine" in peers:
        lines.append(f"Peers: numpy {peers['machine']['numpy']} in their venv; "
                     + ", ".join(f"{k} {v}" for k, v in versions.items()))
    lines.append(f"timer: {next(k for k, v in CLOCKS.items() if v is clock)}")
    lines.append("ns per element (best of repeats); ratio = gm_core / plain-numpy reference, the median "
                 "over interleaved repeat pairs")
    head = ["op", "N", "gm_core", "reference", "ratio", *PEERS]
    rows = []
    checks = []
    for op in OPS:
        for n in sizes:
            g = local["gm_core"][op][str(n)]
            r = local["reference"][op][str(n)]
            ratio = float(np.median(local["pair_ratios"][op][str(n)]))
            row = [op, _fmt_n(n), _cell(g), _cell(r), f"{ratio:.2f}"]
            for p in PEERS:
                entry = (peers or {}).get("timings", {}).get(p, {}).get(op, {}).get(str(n))
                if entry is None and peers and p in versions:
                    entry = "n/a"
                row.append(_cell(entry))
                if isinstance(entry, dict) and op in ("exp", "log") and n == max(sizes):
                    checks.append((f"gm_core ahead of {p} on {op} at N={_fmt_n(n)}",
                                   g["best"] < entry["best"], f"{entry['best'] / g['best']:.1f}x"))
            rows.append(row)
            if n == max(sizes):
                checks.append((f"gm_core <= 1.2x reference on {op} at N={_fmt_n(n)}", ratio <= 1.2,
                               f"{ratio:.2f}"))
    widths = [max(len(str(x)) for x in col) for col in zip(head, *rows)]
    fmt = "| " + " | ".join(f"{{:{'<' if i < 2 else '>'}{w}}}" for i, w in enumerate(widths)) + " |"
    lines.append(fmt.format(*head))
    lines.append("|" + "|".join(("-" * (w + 1) + ":") if i >= 2 else ("-" * (w + 2))
                                for i, w in enumerate(widths)) + "|")
    lines += [fmt.format(*row) for row in rows]
    lines.append("")
    for text, ok, value in checks:
        lines.append(f"[{'ok' if ok else 'MISSED'}] {text} ({value})")
    for note in (peers or {}).get("notes", []):
        lines.append(f"note: {note}")
    if not peers:
        lines.append("peers: not measured (pass --peers PYTHON or set GM_BENCH_PEERS)")
    return "\n".join(lines)


def _merge(old, new):
    """Cell-wise best of two timing trees ({lib: {op: {N: {"best", "median"} or str}}} or a peers
    result with "timings"); non-numeric cells ("n/a", "mismatch") of the new tree win."""
    if old is None:
        return new
    if "timings" in new or "timings" in old:
        merged = dict(new)
        merged["timings"] = _merge(old.get("timings", {}), new.get("timings", {}))
        merged["notes"] = list(dict.fromkeys(old.get("notes", []) + new.get("notes", [])))
        return merged
    out = {}
    for lib in set(old) | set(new):
        out[lib] = {}
        for op in set(old.get(lib, {})) | set(new.get(lib, {})):
            a, b = old.get(lib, {}).get(op, {}), new.get(lib, {}).get(op, {})
            cells = {}
            for n in set(a) | set(b):
                x, y = a.get(n), b.get(n)
                if isinstance(x, list) and isinstance(y, list):
                    cells[n] = x + y
                elif isinstance(x, dict) and isinstance(y, dict):
                    cells[n] = {"best": min(x["best"], y["best"]), "median": min(x["median"], y["median"])}
                else:
                    cells[n] = y if y is not None else x
            out[lib][op] = cells
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", nargs="+", type=float, default=list(SIZES),
                   help="batch sizes N (default 1e3 1e6)")
    p.add_argument("--repeats", type=int, default=7, help="timed repeats per case (best is shown)")
    p.add_argument("--peers", default=os.environ.get("GM_BENCH_PEERS"),
                   help="python of a venv with jaxlie/geomstats (or env GM_BENCH_PEERS)")
    p.add_argument("--rounds", type=int, default=2,
                   help="alternate local and peer measurements this many times; keep the best")
    p.add_argument("--clock", choices=sorted(CLOCKS), default="perf_counter",
                   help="timer: wall clock (default) or this process's CPU time (busy machines)")
    p.add_argument("--json", action="store_true", help="print raw timings as JSON as well")
    p.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    global clock
    clock = CLOCKS[args.clock]
    sizes = [int(n) for n in args.sizes]
    if args.worker:
        run_peers(sizes, args.repeats)
        return
    # Several rounds alternating local and peer measurements, keeping each cell's best: load from
    # other processes on a shared machine then affects both sides alike.
    local, peers = None, None
    for _ in range(args.rounds):
        local = _merge(local, run_local(sizes, args.repeats))
        if args.peers:
            peers = _merge(peers, peers_from(args.peers, sizes, args.repeats))
    if peers is not None:
        for peer in PEERS:
            if peer not in peers.get("timings", {}):
                peers.setdefault("timings", {})[peer] = {}
    print(report(local, peers, sizes))
    if args.json:
        print(json.dumps({"local": local, "peers": peers}, indent=1))


if __name__ == "__main__":
    main()
