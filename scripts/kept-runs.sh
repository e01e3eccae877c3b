#!/usr/bin/env bash
# Makes the kept runs of assets/results/ on this machine, each named <machine>-<commit>.json
# by `classic-gpgpu compare` (a --quick run's machine ends in -quick), replaces the earlier
# kept run of the same machine, and puts the README's table (`compare --markdown`) between its
# markers. Run it on a quiet machine: a timing taken under load is recorded "not judged".
#
#   scripts/kept-runs.sh                      # all four: llvmpipe llvmpipe-quick softpipe-quick zink
#   scripts/kept-runs.sh llvmpipe zink        # some of them
#   scripts/kept-runs.sh --out DIR --only blocks llvmpipe-quick   # a try: into DIR, one section
#
# The runs (2-core machine, quiet): llvmpipe, every section at the papers' sizes, about 3 min;
# llvmpipe-quick, every section at --quick sizes, about 1 min; softpipe-quick, the three
# sections CI runs on softpipe (blocks, paper1, paper2) at --quick sizes, a few minutes; zink
# (on lavapipe, mesa-vulkan-drivers), every section at the papers' sizes, about 7 min.
# A GPU's run (e.g. `reproduce` with --renderer egl-device) is kept the same way: copy its
# results.json to the name `compare` gives it (the file name check in tests/compare.rs says).
set -euo pipefail
cd "$(dirname "$0")/.."

out=assets/results
only=()
readme=1
machines=()
while (($#)); do
  case "$1" in
    --out) out=$2; readme=0; shift 2 ;;
    --only) only=(--only "$2"); shift 2 ;;
    --no-readme) readme=0; shift ;;
    -h | --help) sed -n '2,17p' "$0"; exit 0 ;;
    llvmpipe | llvmpipe-quick | softpipe-quick | zink) machines+=("$1"); shift ;;
    *) echo "kept-runs.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
((${#machines[@]})) || machines=(llvmpipe llvmpipe-quick softpipe-quick zink)

if [ -n "$(git status --porcelain --untracked-files=no)" ] && [ "$out" = assets/results ]; then
  echo "kept-runs.sh: the tree has changes not committed; a kept run names its commit, so" \
    "commit first (or try with --out DIR)" >&2
  exit 1
fi

unset CLASSIC_GPGPU_RENDERER GALLIUM_DRIVER LIBGL_ALWAYS_SOFTWARE
cargo build --release --locked --quiet
bin=target/release/classic-gpgpu
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One kept run: the renderer's environment, then reproduce's arguments.
keep() {
  local machine=$1
  shift
  local -a env_vars=()
  while [[ $# -gt 0 && $1 == *=* ]]; do env_vars+=("$1"); shift; done
  echo "== $machine: reproduce $* ${only[*]} =="
  local start=$SECONDS
  env "${env_vars[@]}" "$bin" reproduce "$@" "${only[@]}" --out "$work/$machine" >"$work/$machine.log" 2>&1 || {
    tail -20 "$work/$machine.log" >&2
    echo "kept-runs.sh: $machine failed (log above)" >&2
    exit 1
  }
  # The name compare gives the run (Run::kept_name): <machine>-<commit>.json, the machine
  # being the renderer the run reports (a renderer that did not start is not kept under
  # another's name).
  local driver=${machine%-quick}
  if ! grep -q "\"renderer\": \"$driver" "$work/$machine/results.json"; then
    echo "kept-runs.sh: $machine: the run's renderer is not $driver:" \
      "$(grep -m1 '"renderer": "' "$work/$machine/results.json")" >&2
    exit 1
  fi
  local name
  name="$machine-$(git rev-parse HEAD | cut -c1-7).json"
  for old in "$out"/"${name%-*}"-*.json; do
    [[ -e $old && $(basename "$old") =~ ^${name%-*}-[0-9a-f]{7}(-dirty)?\.json$ ]] || continue
    [ "$(basename "$old")" = "$name" ] && continue
    echo "replacing $old"
    if git ls-files --error-unmatch "$old" >/dev/null 2>&1; then git rm -q "$old"; else rm "$old"; fi
  done
  cp "$work/$machine/results.json" "$out/$name"
  echo "$out/$name ($((SECONDS - start)) s)"
}

for machine in "${machines[@]}"; do
  case "$machine" in
    llvmpipe) keep llvmpipe GALLIUM_DRIVER=llvmpipe ;;
    llvmpipe-quick) keep llvmpipe-quick GALLIUM_DRIVER=llvmpipe --quick ;;
    softpipe-quick)
      if ((${#only[@]})); then keep softpipe-quick GALLIUM_DRIVER=softpipe --quick
      else keep softpipe-quick GALLIUM_DRIVER=softpipe --quick --only blocks,paper1,paper2; fi ;;
    zink) keep zink GALLIUM_DRIVER=zink LIBGL_ALWAYS_SOFTWARE=1 ;;
  esac
done

if ((readme)); then
  table=$(mktemp)
  "$bin" compare --markdown "$out"/*.json >"$table"
  python3 - "$table" <<'PY'
import sys
table = open(sys.argv[1]).read()
text = open("README.md").read()
begin, end = "<!-- compare:begin -->", "<!-- compare:end -->"
a = text.index(begin) + len(begin) + 1
b = text.index(end, a)
open("README.md", "w").write(text[:a] + table + text[b:])
PY
  rm "$table"
  echo "README.md: the table between its markers is the one compare prints from $out/*.json"
fi
