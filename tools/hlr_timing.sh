#!/usr/bin/env bash
# Hidden-line timings of two limn binaries, interleaved, and OpenCASCADE on the same views.
# Usage: tools/hlr_timing.sh BEFORE_BIN AFTER_BIN [RUNS]   (from the repository's root)
# Prints one line per run: model, limn view, binary, tol|notol, user seconds; then OCCT's
# medians (occt_hlr.py --repeat 5; OCCT's direction is the opposite of limn's). Needs the
# peers' venv (bash ../shared/peers/setup_peers.sh).
set -eu
before=$1; after=$2; runs=${3:-3}
py="${PEERS_VENV:-$HOME/.cache/limn-peers/venv}/bin/python"
for _ in $(seq "$runs"); do
  for d in -1,-2,-3 2,3,-2 1,-1,2; do
    for b in "$before" "$after"; do
      /usr/bin/time -f "teapot $d $b notol %U" "$b" hlr fixtures/bezier/teapot.bpt --dir "$d" --threads 1 > /dev/null
      /usr/bin/time -f "teapot $d $b tol %U" "$b" hlr fixtures/bezier/teapot.bpt --dir "$d" --threads 1 --tol 1e-9 > /dev/null
    done
  done
  for m in occ22470 BUC50025; do
    for b in "$before" "$after"; do
      /usr/bin/time -f "$m 1,2,3 $b notol %U" "$b" hlr "fixtures/iges/occt/$m.igs" --dir 1,2,3 --threads 1 > /dev/null
    done
  done
done
out=$(mktemp)
for d in 1,2,3 -2,-3,2 -1,1,-2; do
  "$py" ../shared/peers/occt_hlr.py fixtures/bezier/teapot.bpt --dir="$d" --repeat 5 --no-3d --out "$out" > /dev/null
  python3 -c "import json,sys; print('occt teapot', sys.argv[1], json.load(open(sys.argv[2]))['time_s'])" "$d" "$out"
done
for m in occ22470 BUC50025; do
  "$py" ../shared/peers/occt_hlr.py "fixtures/iges/occt/$m.igs" --dir=-1,-2,-3 --repeat 5 --no-3d --out "$out" > /dev/null
  python3 -c "import json,sys; print('occt', sys.argv[1], json.load(open(sys.argv[2]))['time_s'])" "$m" "$out"
done
rm -f "$out"
