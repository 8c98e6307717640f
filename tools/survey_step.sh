#!/usr/bin/env bash
# Reads every STEP file of OCCT's test data under 400 kB with `limn info` and tallies the outcomes.
#
#   tools/survey_step.sh GIT_DIR REF OUT_DIR
#
# GIT_DIR is a clone (or bare mirror) of Open-Cascade-SAS/OCCT, REF a commit holding data/step
# (e.g. refs/pull/946/head). Writes OUT_DIR/files/ (the STEP files), OUT_DIR/report.txt (a line
# per file: exit code|file|faces line of `limn info`|first line of stderr) and prints the tally.
set -euo pipefail
git_dir=$1 ref=$2 out=$3
limn=${LIMN:-target/release/limn}
mkdir -p "$out/files"
git --git-dir="$git_dir" ls-tree -r -l "$ref" -- data/step |
  awk '$4 < 400000 && tolower($5) ~ /\.(stp|step)$/ {print $3, $5}' |
  while read -r blob path; do
    git --git-dir="$git_dir" cat-file blob "$blob" > "$out/files/$(basename "$path")"
  done
: > "$out/report.txt"
for f in "$out"/files/*; do
  rc=0
  timeout 120 "$limn" info "$f" > "$out/stdout" 2> "$out/stderr" || rc=$?
  faces=$(grep -m1 '^faces:' "$out/stdout" | cut -d' ' -f2 || true)
  echo "$rc|$(basename "$f")|${faces:-}|$(grep -m1 -v '^limn: warning' "$out/stderr" || true)" >> "$out/report.txt"
done
echo "exit codes (count code):"
cut -d'|' -f1 "$out/report.txt" | sort | uniq -c
echo "refusals by reason (count reason, instance numbers and lines elided):"
grep '^2|' "$out/report.txt" | cut -d'|' -f4 | sed -E 's/^limn: [^:]*: //; s/#[0-9]+/#N/g; s/line [0-9]+/line N/g' |
  cut -c1-100 | sort | uniq -c | sort -rn
