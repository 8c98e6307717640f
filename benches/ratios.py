#!/usr/bin/env python3
"""Medians from criterion's last run, and ratios to the f64 row of the same run.

Usage: python3 benches/ratios.py [GROUP-PREFIX]   (after `cargo bench --bench NAME`)
"""
import json, pathlib, sys

root = pathlib.Path(__file__).resolve().parent.parent / "target" / "criterion"
prefix = sys.argv[1] if len(sys.argv) > 1 else ""
rows = {}
for est in root.glob("**/new/estimates.json"):
    bench = json.loads((est.parent / "benchmark.json").read_text())
    group, param = bench["group_id"], bench.get("value_str") or bench.get("function_id") or ""
    if not group.startswith(prefix):
        continue
    rows[(group, param)] = json.loads(est.read_text())["median"]["point_estimate"]

def fmt(ns):
    return f"{ns/1e6:.3f} ms" if ns >= 1e6 else f"{ns/1e3:.2f} us"

params = sorted({p for _, p in rows})
groups = sorted({g for g, _ in rows})
for p in params:
    base = next((rows[(g, p)] for g in groups if g.endswith("/f64") and (g, p) in rows), None)
    for g in groups:
        if (g, p) in rows:
            ratio = f"  x{rows[(g, p)]/base:.2f} of f64" if base else ""
            print(f"{g:32s} {p:14s} median {fmt(rows[(g, p)]):>12s}{ratio}")
