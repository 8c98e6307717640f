"""Write the STEP fixtures of fixtures/step/occt-written/ with OpenCASCADE (cadquery-ocp).

Run with the peers' Python (../shared/peers/setup_peers.sh):
    "$PY" tools/make_step_fixtures.py fixtures/step/occt-written

Each file is OCCT 8.0.1's STEP (AP214) translation of a shape built here or read from one of the
IGES fixtures, so limn's STEP and IGES readers can be compared on the same geometry.
"""

import os
import sys

from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
from OCP.Interface import Interface_Static


def write(shape, path):
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    w = STEPControl_Writer()
    if w.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone:
        raise SystemExit(f"transfer failed: {path}")
    if w.Write(path) != IFSelect_RetDone:
        raise SystemExit(f"write failed: {path}")
    print("wrote", path)


def from_iges(path):
    r = IGESControl_Reader()
    if r.ReadFile(path) != IFSelect_RetDone:
        raise SystemExit(f"cannot read {path}")
    r.TransferRoots()
    return r.OneShape()


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "fixtures/step/occt-written"
    os.makedirs(out, exist_ok=True)
    write(BRepPrimAPI_MakeBox(2.0, 3.0, 4.0).Shape(), os.path.join(out, "box.stp"))
    for name in ["OCC8842_cylinder_Ideas", "OCC8842_cone_Ideas", "bug24012_face"]:
        shape = from_iges(os.path.join("fixtures/iges/occt", name + ".igs"))
        write(shape, os.path.join(out, name + ".stp"))


if __name__ == "__main__":
    main()
