"""OpenCASCADE's exact HLR on a STEP file, timed, beside `limn hlr` (the peers' script reads IGES).

Run with the peers' Python (../shared/peers/setup_peers.sh):
    "$PY" tools/occt_step_hlr.py PART.stp --dir=-1,-2,-3 --repeat 5

Prints one JSON line: the faces OCCT read, its visible and hidden polyline counts and the median
time of its HLR (`time_s`, as `occt_hlr.py` measures it). OCCT's --dir points toward the viewer:
the same view is `limn hlr --dir 1,2,3`.
"""

import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "shared", "peers"))
import occt_hlr  # noqa: E402
from OCP.BRepLib import BRepLib  # noqa: E402
from OCP.IFSelect import IFSelect_ReturnStatus  # noqa: E402
from OCP.STEPControl import STEPControl_Reader  # noqa: E402
from OCP.TopAbs import TopAbs_FACE  # noqa: E402


def load_step(path):
    t0 = time.perf_counter()
    rd = STEPControl_Reader()
    with occt_hlr.stdout_to_stderr():
        if rd.ReadFile(path) != IFSelect_ReturnStatus.IFSelect_RetDone:
            raise SystemExit(f"{path}: STEP read failed")
        rd.TransferRoots()
        shape = rd.OneShape()
    info = {"source": "step", "faces": occt_hlr.count(shape, TopAbs_FACE)}
    info["bbox_diag"] = occt_hlr.bbox_diag(shape)
    BRepLib.EncodeRegularity_s(shape, 1e-10)
    info["build_s"] = time.perf_counter() - t0
    return shape, info


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model")
    ap.add_argument("--dir", required=True)
    ap.add_argument("--repeat", type=int, default=5)
    a = ap.parse_args()
    shape, info = load_step(a.model)
    d = occt_hlr.parse_vec(a.dir, "--dir")
    out = occt_hlr.hlr(shape, info, d, repeat=a.repeat, want3d=False)
    vis = sum(len(v) for v in out["visible"].values())
    hid = sum(len(v) for v in out["hidden"].values())
    print(json.dumps({"model": os.path.basename(a.model), "faces": info["faces"],
                      "visible_polylines": vis, "hidden_polylines": hid,
                      "time_s": out["time_s"]}))


if __name__ == "__main__":
    main()
