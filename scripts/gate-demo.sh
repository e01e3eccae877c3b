#!/usr/bin/env bash
# Shows what issue 50 asks to see, from a fresh run and the kept runs:
#   scripts/gate-demo.sh NEW.json [OLD.json]
# NEW.json: a fresh `classic-gpgpu reproduce` (report/results.json); OLD.json: a kept run of an
# older commit of the same machine and sizes (default: the kept llvmpipe run at the papers'
# sizes). It prints:
#  1. the page comparing NEW with every kept run (groups, claims compared, changed definitions);
#  2. the gate, NEW against OLD: each changed claim and `compared N claims: ...`, and its exit;
#  3. the gate, NEW against itself: exit 0;
#  4. the gate, NEW with one verdict decided by counts flipped, against NEW: exit 1.
set -uo pipefail
cd "$(dirname "$0")/.."
new=${1:?usage: scripts/gate-demo.sh NEW.json [OLD.json]}
old=${2:-$(ls assets/results/llvmpipe-[0-9a-f]*.json | tail -1)}
bin=${CLASSIC_GPGPU:-target/release/classic-gpgpu}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "== 1. the page: $new beside every kept run =="
"$bin" compare "$new" assets/results/*.json --out "$work/page"
echo "(page: $work/page/index.html, kept only while this script runs)"

echo
echo "== 2. the gate: $new against $old =="
"$bin" compare --baseline "$old" "$new"
echo "exit status: $?"

echo
echo "== 3. the gate: $new against itself =="
"$bin" compare --baseline "$new" "$new" | tail -1
echo "exit status: ${PIPESTATUS[0]}"

echo
echo "== 4. the gate: one verdict decided by counts flipped =="
python3 - "$new" "$work/flipped.json" <<'PY'
import json, sys
run = json.load(open(sys.argv[1]))
claims = [c for s in run["sections"] for c in s["claims"] if c["holds"] is not None]
# A claim decided by counts; one decided by an error only when the run has none (--only blocks).
for basis in ("count", "error"):
    for claim in claims:
        if claim.get("decided_by") == basis:
            claim["holds"] = not claim["holds"]
            print(f"flipped {claim['id']} ({basis}): holds = {claim['holds']}")
            json.dump(run, open(sys.argv[2], "w"))
            sys.exit(0)
sys.exit("no claim decided by counts to flip")
PY
"$bin" compare --baseline "$new" "$work/flipped.json"
echo "exit status: $?"
