#!/usr/bin/env python3
"""The golden comparison: every CLI command on every fixture and generated shape.

    python3 tools/golden.py run OUT [--bin target/release/limn] [--jobs 2] [--only SUBSTR]
    python3 tools/golden.py compare BEFORE AFTER

`run` writes one file per job into OUT (the command's stdout, and for JSON its value with
every `stats` object and every `time_ms` field removed, keys sorted), plus `OUT/index.json`
(job name -> command line, exit code, wall seconds). `compare` reports every job whose
normalised output or exit code differs, and exits 1 if any does.

Run it before a change that must not change results (the layout, a faster spine), keep
the folder, run it after, compare. The generated shapes come from
`cargo run --example golden_shapes -- target/golden-models` (exact rationals), made once, so
both runs read the same files by the same names.
"""

import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIX = ROOT / "fixtures"

BEZIER = [
    FIX / "bezier/teapot.bpt",
    FIX / "bezier/newell_teaset/teacup",
    FIX / "bezier/newell_teaset/teaspoon",
    FIX / "bezier/newell_teaset/teapot",
]
IGES = sorted((FIX / "iges").rglob("*.igs"))
MESHES = sorted((FIX / "meshes").rglob("*.obj"))
SHAPES = ["sphere", "torus", "torus_rotated", "two_spheres", "cylinder_quarter", "double_well"]

# IGES parts whose hidden lines and silhouettes take seconds, not minutes.
IGES_HLR = ["occ22470.igs", "BUC50025.igs", "OCC8842_cylinder_Ideas.igs", "OCC8842_cone_Ideas.igs",
            "bug24012_face.igs", "128-000.igs"]


def jobs(models):
    """(name, argv, kind) for every job; kind is 'json' or 'text'."""
    out = []

    def add(name, argv, kind="json"):
        out.append((name, [str(a) for a in argv], kind))

    def short(p):
        p = Path(p)
        if p.parent.name == "newell_teaset":
            return f"teaset_{p.name}"
        return p.stem if p.suffix else p.name

    shapes = [models / f"{s}.json" for s in SHAPES]
    every = BEZIER + IGES + MESHES + shapes
    for m in every:
        add(f"info-{short(m)}", ["info", m, "--format", "json"])
        add(f"info-{short(m)}.txt", ["info", m], "text")
    patch_models = BEZIER + IGES + shapes
    for m in patch_models:
        n = short(m)
        add(f"sil-{n}", ["silhouette", m, "--dir", "1,2,3", "--format", "json"])
        add(f"sil-{n}-tol", ["silhouette", m, "--dir", "1,2,3", "--tol", "1e-5", "--format", "json"])
        add(f"sil-{n}-eye", ["silhouette", m, "--eye", "7,-5,9", "--format", "json"])
        add(f"sil-{n}-mesh", ["silhouette", m, "--dir", "1,2,3", "--method", "mesh", "--format", "json"])
        add(f"sil-{n}-srfnode", ["silhouette", m, "--dir", "1,2,3", "--method", "srf-node", "--format", "json"])
    for m in BEZIER + shapes:
        n = short(m)
        add(f"sil-{n}.txt", ["silhouette", m, "--dir", "-1,-2,-3"], "text")
        add(f"sil-{n}.svg", ["silhouette", m, "--dir", "1,2,3", "--format", "svg"], "text")
        add(f"sil-{n}.obj", ["silhouette", m, "--dir", "1,2,3", "--format", "obj"], "text")
        add(f"par-{n}", ["curves", m, "--kind", "parabolic", "--format", "json"])
        add(f"par-{n}-tol", ["curves", m, "--kind", "parabolic", "--tol", "1e-5", "--format", "json"])
        add(f"par-{n}.svg", ["curves", m, "--kind", "parabolic", "--format", "svg"], "text")
    for m in [FIX / "bezier/teapot.bpt"] + shapes:
        n = short(m)
        add(f"hlr-{n}", ["hlr", m, "--dir", "-1,-2,-3", "--format", "json"])
        add(f"hlr-{n}-tol", ["hlr", m, "--dir", "2,3,-2", "--tol", "1e-6", "--format", "json"])
        add(f"hlr-{n}.svg", ["hlr", m, "--dir", "2,3,-2", "--format", "svg"], "text")
        add(f"hlr-{n}.txt", ["hlr", m, "--dir", "2,3,-2"], "text")
        add(f"vis-{n}", ["visible", m, "--dir", "1,2,3", "--format", "json"])
        add(f"vis-{n}-tol", ["visible", m, "--dir", "-1,-2,-3", "--tol", "1e-5", "--cell-depth", "6", "--cells", "--format", "json"])
        add(f"vis-{n}.svg", ["visible", m, "--dir", "1,2,3", "--format", "svg"], "text")
    for m in IGES:
        if m.name in IGES_HLR:
            add(f"hlr-{short(m)}", ["hlr", m, "--dir", "1,2,3", "--format", "json"])
    for m in shapes:
        n = short(m)
        add(f"hlr-{n}-eye", ["hlr", m, "--eye", "9,-7,11", "--format", "json"])
        add(f"vis-{n}-eye", ["visible", m, "--eye", "9,-7,11", "--format", "json"])
        add(f"flec-{n}", ["curves", m, "--kind", "flecnodal", "--format", "json"])
        add(f"flec-{n}-tol", ["curves", m, "--kind", "flecnodal", "--tol", "1e-4", "--format", "json"])
        add(f"bit-{n}", ["curves", m, "--kind", "bitangent", "--format", "json"])
        add(f"ev-{n}", ["events", m, "--format", "json"])
        add(f"ev-{n}.svg", ["events", m, "--kinds", "parabolic,flecnodal", "--format", "svg"], "text")
    tp = FIX / "bezier/teapot.bpt"
    add("flec-teapot", ["curves", tp, "--kind", "flecnodal", "--format", "json"])
    add("flec-teapot.txt", ["curves", tp, "--kind", "flecnodal"], "text")
    add("ev-teapot-par", ["events", tp, "--kinds", "parabolic", "--format", "json"])
    add("bit-teapot-shallow", ["curves", tp, "--kind", "bitangent", "--max-depth", "8", "--format", "json"])
    add("demo", ["demo"], "text")
    add("demo-json", ["demo", "--format", "json"])
    # Errors: the exit code and the one line.
    add("err-missing", ["info", "/nonexistent/model.json"], "text")
    add("err-dir", ["silhouette", tp, "--dir", "0,0,0"], "text")
    add("err-args", ["hlr", tp], "text")
    return out


def normalise(value):
    if isinstance(value, dict):
        return {k: normalise(v) for k, v in sorted(value.items()) if k not in ("stats", "time_ms")}
    if isinstance(value, list):
        return [normalise(v) for v in value]
    return value


def run_job(binary, outdir, job, timeout):
    name, argv, kind = job
    t = time.monotonic()
    try:
        p = subprocess.run([binary] + argv, capture_output=True, timeout=timeout, cwd=ROOT)
        code, stdout, stderr = p.returncode, p.stdout.decode("utf-8", "replace"), p.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        code, stdout, stderr = "timeout", "", ""
    secs = time.monotonic() - t
    if kind == "json" and code == 0:
        try:
            body = json.dumps(normalise(json.loads(stdout)), indent=1, sort_keys=True)
        except json.JSONDecodeError as e:
            body = f"not JSON: {e}\n{stdout}"
    else:
        # Text: drop lines that report times.
        body = "\n".join(l for l in stdout.splitlines() if " ms" not in l and "time" not in l)
    body += f"\n--- exit {code}\n--- stderr\n{stderr}"
    (outdir / f"{name}.out").write_text(body)
    return name, {"argv": argv, "exit": code, "seconds": round(secs, 3)}


def cmd_run(args):
    out = Path(args.out).resolve()
    models = ROOT / "target/golden-models"
    out.mkdir(parents=True, exist_ok=True)
    if not models.exists():
        subprocess.run(["cargo", "run", "--release", "--quiet", "--example", "golden_shapes", "--", str(models)],
                       check=True, cwd=ROOT)
    binary = str(Path(args.bin).resolve())
    todo = [j for j in jobs(models) if args.only is None or args.only in j[0]]
    index = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_job, binary, out, j, args.timeout) for j in todo]
        for f in concurrent.futures.as_completed(futures):
            name, info = f.result()
            index[name] = info
            print(f"{info['seconds']:8.2f} s  exit {info['exit']}  {name}", flush=True)
    old = out / "index.json"
    if old.exists() and args.only is not None:
        merged = json.loads(old.read_text())
        merged.update(index)
        index = merged
    old.write_text(json.dumps(index, indent=1, sort_keys=True))
    print(f"{len(todo)} jobs, {sum(i['seconds'] for i in index.values()):.1f} s in all")


def comparable(path):
    """The output with what may differ between runs dropped: the `ms` of `limn events`."""
    text = path.read_text()
    body, sep, rest = text.partition("\n--- exit")
    try:
        value = json.loads(body)
    except json.JSONDecodeError:
        return text
    def drop(v):
        if isinstance(v, dict):
            return {k: drop(x) for k, x in v.items() if k != "ms"}
        if isinstance(v, list):
            return [drop(x) for x in v]
        return v
    return json.dumps(drop(value), sort_keys=True) + sep + rest


def cmd_compare(args):
    a, b = Path(args.before), Path(args.after)
    na, nb = {p.name for p in a.glob("*.out")}, {p.name for p in b.glob("*.out")}
    for n in sorted(na ^ nb):
        print(f"only in {'before' if n in na else 'after'}: {n}")
    names = sorted(na & nb)
    differ = []
    for n in names:
        if comparable(a / n) != comparable(b / n):
            differ.append((n, "differs"))
    ia, ib = (json.loads((d / "index.json").read_text()) for d in (a, b))
    for job in sorted(set(ia) & set(ib)):
        if ia[job]["exit"] != ib[job]["exit"]:
            differ.append((job, f"exit {ia[job]['exit']} -> {ib[job]['exit']}"))
    for n, why in differ:
        print(f"{why}: {n}")
    print(f"{len(names)} outputs and {len(set(ia) & set(ib))} exit codes compared, {len(differ)} differ")
    return 1 if differ else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("out")
    r.add_argument("--bin", default=str(ROOT / "target/release/limn"))
    r.add_argument("--jobs", type=int, default=2)
    r.add_argument("--timeout", type=float, default=600)
    r.add_argument("--only")
    c = sub.add_parser("compare")
    c.add_argument("before")
    c.add_argument("after")
    args = ap.parse_args()
    if args.cmd == "run":
        cmd_run(args)
        return 0
    return cmd_compare(args)


if __name__ == "__main__":
    sys.exit(main())
