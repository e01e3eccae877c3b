#!/usr/bin/env bash
# Hostile-but-fair runs against every command (Linux only).
#
#   scripts/hostile.sh [--short] [BINARY]   (default: target/release/classic-gpgpu)
#   HOSTILE_ONLY=crowd,mass-dump scripts/hostile.sh    (only those writers)
#
# First the option classes, over every command, walked from the binary's own list of options
# (`classic-gpgpu options`), so that a new option is covered without an edit here:
#   bounds    every number far above its range: refused at once, naming the option and value;
#   negative  every number negative (and every real number -1e309): the same;
#   ignored   options a run would ignore or that change nothing: refused with the reason, or
#             honoured (--json parses);
#   shared    two outputs of one run on one path, an output on an input: refused;
#   links     every output given as a link to nothing, and as a loop of links: refused, named,
#             the link kept, nothing made where it points;
#   markers   locks and markers: a user's file named like a lock kept, a file at the lock's
#             name refused and kept, another command's folder refused even with --force;
#   mount     a mount point as an output folder: refused before any work;
#   issue     the cases of issue 52, each with its outcome (printed as a table).
# `--short` (CI) runs these classes only: about a minute.
#
# For each writer, five kinds of case:
#   full      its output folder on a tmpfs that is full, the old output file in it;
#   readonly  its output folder on a read-only mount, the old output file in it;
#   sigint    SIGINT at a random moment (two tries; the child is started with SIGINT at its
#             default, as a non-interactive bash starts background jobs with it ignored);
#   kill9     kill -9 at a random moment (two tries);
#   twice     two runs into the same output at once.
# And for each writer of a folder, four more (the rule of page::folder::Staged):
#   foreign   a file of the user's in the folder: refused without --force, the file as it was;
#   force     the same with --force: written, the user's file untouched beside it;
#   stale     a file the marker lists as the earlier run's and this run does not write: gone;
#   symlink   the folder given as a link to a folder: written there, the link kept; a link to
#             nothing: refused, nothing made where it points.
# A case passes when nothing is lost (the old output is either untouched or replaced by a
# whole, valid new one; a file of the user's beside a folder output survives), a failure
# exits non-zero with a message naming what failed, and no temporary file (.NAME.tmp-PID)
# is left once a run has completed in that folder (a killed run cannot clean up after
# itself; the next write there removes what it left).
#
# The tmpfs mounts need a mount namespace: the script re-runs itself under
# `unshare --user --map-root-user --mount` (no root needed where unprivileged user
# namespaces are allowed). Where that fails it falls back to `ulimit -f` for the full-disk
# case (the write is then cut short by SIGXFSZ, a kill in the middle of a write) and skips
# the read-only case, saying so.
set -u

SHORT=
if [[ ${1:-} == --short ]]; then
    SHORT=1
    shift
fi
BIN=${1:-target/release/classic-gpgpu}
BIN=$(realpath "$BIN")
if [[ -z "${HOSTILE_IN_NS:-}" ]] && command -v unshare >/dev/null &&
    unshare --user --map-root-user --mount true 2>/dev/null; then
    HOSTILE_IN_NS=1 HOSTILE_ONLY="${HOSTILE_ONLY:-}" exec unshare --user --map-root-user --mount "$0" ${SHORT:+--short} "$BIN"
fi
MOUNTS=${HOSTILE_IN_NS:+yes}
export CLASSIC_GPGPU_RENDERER=${CLASSIC_GPGPU_RENDERER:-egl-surfaceless}

WORK=$(mktemp -d /tmp/hostile.XXXXXX)
trap 'umount "$WORK"/m* 2>/dev/null; rm -rf "$WORK"' EXIT
INPUTS=$WORK/inputs
mkdir -p "$INPUTS"
RUN=0 PASS=0 FAIL=0 SKIP=0 SIGNALLED=0
FAILED=()
declare -A COUNT PASSED

# ---- inputs (small) ----
"$BIN" mesh generate cube --out "$INPUTS/cube.obj" >/dev/null 2>&1
"$BIN" mesh generate sphere --out "$INPUTS/sphere.obj" >/dev/null 2>&1
echo '[{"translation": [0, 0, 0], "rotation": [1, 0, 0, 0]},
       {"translation": [0.5, 0, 0], "rotation": [1, 0, 0, 0]}]' >"$INPUTS/path.json"
"$BIN" lecture3 height-map --size 32 --out "$INPUTS/text.png" >/dev/null 2>&1

# ---- the writers: name, kind (file: OUT is a file; dir: OUT is a folder), the output's
# name, and the command (OUT stands for the output path) ----
WRITERS=(
    "mlp-detect|file|det.png|mlp detect $INPUTS/text.png --out OUT --force"
    "mlp-train|file|net.json|mlp train --images 8 --epochs 1 --windows-per-class 8 --out OUT --force"
    "height-map|file|h.png|lecture3 height-map --size 16 --out OUT --force"
    "displace|dir|frames|lecture3 displace --size 32 --out OUT --force"
    "crowd|file|crowd.png|crowd --characters 2 --frames 1 --size 64x48 --png OUT --force"
    "mass-dump|dir|peels|mass cube --resolution 8 --dump OUT --force"
    "collide-dump|dir|dump|collide $INPUTS/cube.obj $INPUTS/sphere.obj --dump OUT --force"
    "buoyancy-png|dir|frames|buoyancy --bodies 2 --steps 4 --resolution 8 --png-every 2 OUT --force"
    "octree-npy|dir|octree|lecture3 octree --resolution 8 --points 200 --size 16 --npy OUT --force"
    "light-npy|dir|light|lecture3 light --vpls 8 --size 16 --npy OUT --force"
    "displace-npy|dir|npy|lecture3 displace --size 32 --no-check --npy OUT --force"
    "guide|dir|guide|learn --guide OUT --force"
    "mlp-bench|dir|bench|mlp-bench --quick --runs 1 --out OUT --force"
    "distance-field|file|d.npy|lecture1 distance-field $INPUTS/cube.obj --resolution 8 --npy OUT --force"
    "swept-volume|file|s.obj|lecture1 swept-volume $INPUTS/cube.obj --path $INPUTS/path.json --resolution 16 --poses 3 --out OUT --force"
    "view-screenshot|file|v.png|view --headless --frames 1 --size 256x192 --screenshot OUT --force mass cube"
    "learn-png|dir|lesson|learn texture-is-array --png OUT --force"
    "mesh-generate|file|t.obj|mesh generate torus --out OUT --force"
    "reproduce|dir|report|reproduce --quick --only blocks --out OUT --force"
)

# Is FILE a whole output of its kind?
valid() {
    python3 - "$1" <<'EOF'
import json, struct, sys, pathlib
p = pathlib.Path(sys.argv[1])
b = p.read_bytes()
ext = p.suffix.lower()
if ext == ".png":
    ok = b.startswith(b"\x89PNG\r\n\x1a\n") and b[-12:-4] == b"\x00\x00\x00\x00IEND"
elif ext == ".json":
    json.loads(b); ok = True
elif ext == ".npy":
    n = struct.unpack("<H", b[8:10])[0]
    header = b[10:10 + n].decode()
    shape = eval(header)["shape"]
    count = 1
    for s in shape: count *= s
    ok = b.startswith(b"\x93NUMPY") and len(b) == 10 + n + 4 * count
elif ext == ".obj":
    text = b.decode()
    ok = text.endswith("\n") and any(l.startswith("f ") for l in text.splitlines())
else:
    ok = len(b) > 0
sys.exit(0 if ok else 1)
EOF
}

OLD=$WORK/old.txt
echo "the user's old file, not to be lost" >"$OLD"

# The old output in folder DIR: for a file writer, OUT itself; for a folder writer, a
# file of the user's inside OUT.
plant_old() { # dir kind name
    if [[ $2 == file ]]; then
        cp "$OLD" "$1/$3"
    else
        mkdir -p "$1/$3" && cp "$OLD" "$1/$3/notes.txt"
    fi
}

# Nothing lost: the old file untouched or replaced by a whole one; every file of a folder
# output whole.
nothing_lost() { # dir kind name
    if [[ $2 == file ]]; then
        local f=$1/$3
        [[ -f $f ]] || return 1
        cmp -s "$f" "$OLD" && return 0
        valid "$f"
    else
        cmp -s "$1/$3/notes.txt" "$OLD" || return 1
        local f
        for f in "$1/$3"/*; do
            [[ $f == */notes.txt ]] && continue
            [[ -f $f ]] && { valid "$f" || return 1; }
        done
        return 0
    fi
}

old_untouched() { # dir kind name
    if [[ $2 == file ]]; then
        cmp -s "$1/$3" "$OLD"
    else
        cmp -s "$1/$3/notes.txt" "$OLD"
    fi
}

# Temporary files, staging folders and locks a run leaves (none once one has completed).
temporaries() { find "$1" \( -name '.*.tmp-*' -o -name '.*.staging-*' -o -name '.*.classic-gpgpu-lock' \) 2>/dev/null; }

# Runs its arguments with SIGINT at its default disposition: a non-interactive bash starts
# background jobs with SIGINT ignored, and an ignored signal stays ignored across exec.
SIGINT_DEFAULT=(python3 -c 'import os, signal, sys
signal.signal(signal.SIGINT, signal.SIG_DFL)
os.execvp(sys.argv[1], sys.argv[1:])')

run_writer() { # command-template out-path stdout-file
    local cmd=${1//OUT/$2}
    # shellcheck disable=SC2086
    "$BIN" $cmd >"$3.out" 2>"$3.err"
}

record() { # name case ok why [note]
    RUN=$((RUN + 1))
    COUNT[$2]=$((${COUNT[$2]:-0} + 1))
    if [[ $3 == 1 ]]; then
        PASS=$((PASS + 1))
        PASSED[$2]=$((${PASSED[$2]:-0} + 1))
    else
        FAIL=$((FAIL + 1))
        FAILED+=("$1/$2: $4")
    fi
    printf '%-16s %-9s %s %s\n' "$1" "$2" "$([[ $3 == 1 ]] && echo pass || echo "FAIL: $4")" "${5:-}"
}

# A failed run: non-zero exit, a message, nothing lost, no temporaries.
failed_cleanly() { # name case dir kind out rc log
    local why=""
    [[ $6 != 0 ]] || why="exit 0 "
    [[ -s $7.err ]] || why+="no message "
    grep -qi "panick" "$7.err" && why+="panic "
    old_untouched "$3" "$4" "$(basename "$5")" || why+="old output changed "
    [[ -z "$(temporaries "$3")" ]] || why+="temporary left "
    record "$1" "$2" "$([[ -z $why ]] && echo 1 || echo 0)" "$why$(head -c 200 "$7.err" | tr '\n' ' ')"
}

mount_tmpfs() { # dir size [ro]
    mkdir -p "$1" && mount -t tmpfs -o "size=$2" tmpfs "$1"
}

case_full() { # name kind outname template
    local d=$WORK/mfull_$1 log=$WORK/log_full_$1
    if [[ -n $MOUNTS ]]; then
        mount_tmpfs "$d" 256k || { SKIP=$((SKIP + 1)); return; }
        plant_old "$d" "$2" "$3"
        dd if=/dev/zero of="$d/filler" bs=4k 2>/dev/null
        run_writer "$4" "$d/$3" "$log"
        local rc=$?
        rm -f "$d/filler"
        failed_cleanly "$1" full "$d" "$2" "$d/$3" "$rc" "$log"
        umount "$d"
    else
        mkdir -p "$d" && plant_old "$d" "$2" "$3"
        (ulimit -f 1; run_writer "$4" "$d/$3" "$log")
        local rc=$?
        nothing_lost "$d" "$2" "$3" && [[ $rc != 0 ]] &&
            record "$1" full-ulimit 1 "" || record "$1" full-ulimit 0 "rc $rc, output lost"
    fi
}

case_readonly() { # name kind outname template
    local d=$WORK/mro_$1 log=$WORK/log_ro_$1
    [[ -n $MOUNTS ]] || { SKIP=$((SKIP + 1)); return; }
    mount_tmpfs "$d" 1m || { SKIP=$((SKIP + 1)); return; }
    plant_old "$d" "$2" "$3"
    mount -o remount,ro "$d"
    run_writer "$4" "$d/$3" "$log"
    failed_cleanly "$1" readonly "$d" "$2" "$d/$3" "$?" "$log"
    umount "$d"
}

# A run stopped by SIGNAL after a random delay (up to the clean run's time); then a clean
# run into the same folder, which must complete and leave no temporaries.
# The temporaries left in DIR after a killed run and the next one, less a finished output a
# run killed just before its swap left in its staging folder: kept on purpose, and named by
# the next run (page::folder::recover).
left_over() { # dir next-run-stderr
    local t
    while IFS= read -r t; do
        [[ -n $t ]] || continue
        [[ -f $t/.classic-gpgpu-report ]] && grep -qF "note: $t holds the finished" "$2" && continue
        echo "$t"
    done < <(temporaries "$1")
}

case_signal() { # name kind outname template signal seconds
    local d=$WORK/sig_$1_$5_$RANDOM log=$WORK/log_sig_$1
    mkdir -p "$d" && plant_old "$d" "$2" "$3"
    local cmd=${4//OUT/$d/$3}
    # shellcheck disable=SC2086
    "${SIGINT_DEFAULT[@]}" "$BIN" $cmd >"$log.out" 2>"$log.err" &
    local pid=$!
    sleep "$(python3 -c "import random; print(round(random.uniform(0, $6), 2))")"
    kill "-$5" "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    local rc=$?
    # What the signal did: 130 / 137 is the run stopped by it, 0 a run that had finished.
    local how=finished
    [[ $rc == 130 && $5 == INT ]] && how=stopped SIGNALLED=$((SIGNALLED + 1))
    [[ $rc == 137 && $5 == KILL ]] && how=stopped SIGNALLED=$((SIGNALLED + 1))
    [[ $how == finished && $rc != 0 ]] && how="exit $rc"
    local why=""
    nothing_lost "$d" "$2" "$3" || why+="output lost or partial "
    run_writer "$4" "$d/$3" "$log.again" || why+="the next run failed: $(head -c 200 "$log.again.err") "
    nothing_lost "$d" "$2" "$3" || why+="the next run's output is not whole "
    [[ -z "$(left_over "$d" "$log.again.err")" ]] || why+="temporary left after the next run "
    record "$1" "$(tr A-Z a-z <<<"$5")" "$([[ -z $why ]] && echo 1 || echo 0)" "$why" "($how)"
}

# The marker a folder writer keeps in its folder (page::folder::MARKER).
MARKER=.classic-gpgpu-report

# A folder writer's own rule: a file of the user's refused without --force and kept with
# it, a stale file of its own earlier run removed, a linked folder followed.
case_folder_rule() { # name outname template
    local d=$WORK/rule_$1 log=$WORK/log_rule_$1 out
    local bare=${3// --force/}
    mkdir -p "$d"
    # foreign
    out=$d/foreign_$2
    mkdir -p "$out" && cp "$OLD" "$out/notes.txt"
    run_writer "$bare" "$out" "$log.foreign"
    local rc=$? why=""
    [[ $rc != 0 ]] || why+="exit 0 "
    grep -q "notes.txt" "$log.foreign.err" && grep -q -- "--force" "$log.foreign.err" ||
        why+="the message names neither the file nor --force "
    grep -qi "panick" "$log.foreign.err" && why+="panic "
    cmp -s "$out/notes.txt" "$OLD" || why+="the user's file changed "
    [[ $(find "$out" -type f | wc -l) == 1 ]] || why+="files written while refused "
    record "$1" foreign "$([[ -z $why ]] && echo 1 || echo 0)" "$why$(head -c 200 "$log.foreign.err" | tr '\n' ' ')"
    # force
    why=""
    run_writer "$3" "$out" "$log.force" || why+="failed: $(head -c 200 "$log.force.err") "
    cmp -s "$out/notes.txt" "$OLD" || why+="the user's file changed "
    [[ -f $out/$MARKER ]] || why+="no marker "
    nothing_lost "$d" dir "foreign_$2" || why+="an output is not whole "
    [[ -z "$(temporaries "$d")" ]] || why+="temporary left "
    record "$1" force "$([[ -z $why ]] && echo 1 || echo 0)" "$why"
    # stale: a file the marker says the earlier run wrote, which this run does not write
    why=""
    out=$d/stale_$2
    if run_writer "$bare" "$out" "$log.stale1"; then
        echo stale >"$out/stale-own.png"
        printf -- '-\tstale-own.png\n' >>"$out/$MARKER"
        run_writer "$bare" "$out" "$log.stale2" || why+="the rerun failed: $(head -c 200 "$log.stale2.err") "
        [[ ! -e $out/stale-own.png ]] || why+="the earlier run's file survived "
        grep -q "stale-own.png" "$out/$MARKER" && why+="the marker still lists it "
    else
        why+="the first run failed: $(head -c 200 "$log.stale1.err") "
    fi
    record "$1" stale "$([[ -z $why ]] && echo 1 || echo 0)" "$why"
    # symlink: followed to a folder, refused when dangling
    why=""
    mkdir -p "$d/real_$2"
    ln -s "$d/real_$2" "$d/link_$2"
    run_writer "$bare" "$d/link_$2" "$log.link" || why+="through a link: $(head -c 200 "$log.link.err") "
    [[ -L $d/link_$2 ]] || why+="the link was replaced "
    [[ -f $d/real_$2/$MARKER ]] || why+="the linked folder was not written "
    ln -s "$d/nowhere_$2" "$d/dangling_$2"
    run_writer "$3" "$d/dangling_$2" "$log.dangling" && why+="a dangling link was written through "
    grep -q "does not exist" "$log.dangling.err" || why+="the dangling link's message: $(head -c 150 "$log.dangling.err") "
    [[ -e $d/nowhere_$2 ]] && why+="made the dangling link's target "
    [[ -L $d/dangling_$2 ]] || why+="the dangling link was replaced "
    [[ -z "$(temporaries "$d")" ]] || why+="temporary left "
    record "$1" symlink "$([[ -z $why ]] && echo 1 || echo 0)" "$why"
}

case_twice() { # name kind outname template
    local d=$WORK/twice_$1 log=$WORK/log_twice_$1
    mkdir -p "$d" && plant_old "$d" "$2" "$3"
    run_writer "$4" "$d/$3" "$log.1" &
    local p1=$!
    run_writer "$4" "$d/$3" "$log.2" &
    local p2=$!
    wait "$p1"; local r1=$?
    wait "$p2"; local r2=$?
    local why=""
    for k in 1 2; do
        local rc=$([[ $k == 1 ]] && echo $r1 || echo $r2)
        [[ $rc == 0 || -s $log.$k.err ]] || why+="run $k failed silently "
        grep -qi "panick" "$log.$k.err" && why+="run $k panicked "
    done
    [[ $r1 == 0 || $r2 == 0 ]] || why+="both failed ($(head -c 150 "$log.1.err")) "
    nothing_lost "$d" "$2" "$3" || why+="output lost or partial "
    [[ -z "$(temporaries "$d")" ]] || why+="temporary left "
    record "$1" twice "$([[ -z $why ]] && echo 1 || echo 0)" "$why"
}


# ---- the option classes ----

OPTIONS=$WORK/options.json
"$BIN" options >"$OPTIONS"

# Runs the binary with its arguments (OUT and IN_* already substituted); log in $LOG.out/.err.
run_case() {
    "$BIN" "$@" >"$LOG.out" 2>"$LOG.err"
}

# A refusal: non-zero exit (1, or clap's 2), no panic, a message holding every needle, within
# TIME seconds (a refusal takes milliseconds; a run that was not refused does work first).
refused() { # class name seconds needles... -- args...
    local class=$1 name=$2 limit=$3
    shift 3
    local needles=()
    while [[ $1 != -- ]]; do needles+=("$1"); shift; done
    shift
    LOG=$WORK/log_case
    local start=$SECONDS
    timeout 120 "$BIN" "$@" >"$LOG.out" 2>"$LOG.err"
    local rc=$? took=$((SECONDS - start)) why=""
    [[ $rc == 1 || $rc == 2 ]] || why+="exit $rc "
    grep -qi "panicked" "$LOG.err" && why+="panic "
    ((took <= limit)) || why+="took ${took}s "
    for n in "${needles[@]}"; do grep -qF -- "$n" "$LOG.err" || why+="no '$n' in the message "; done
    record "$name" "$class" "$([[ -z $why ]] && echo 1 || echo 0)" "$why$(head -c 160 "$LOG.err" | tr '\n' ' ')"
    CASE_TEXT=$(grep -m1 "^error" "$LOG.err" | head -c 230)
}

# Every numeric option from the binary's list: "command words|--long|kind".
numbers() {
    python3 - "$OPTIONS" <<'PY'
import json, sys
for c in json.load(open(sys.argv[1]))["commands"]:
    for o in c["options"]:
        if o["kind"] in ("count", "real", "pair") and o["long"]:
            print(f'{c["command"]}|--{o["long"]}|{o["kind"]}')
PY
}

class_bounds() { # class huge-count huge-real huge-pair
    local class=$1 line words long kind value
    while IFS= read -r line; do
        IFS='|' read -r words long kind <<<"$line"
        case $kind in count) value=$2 ;; real) value=$3 ;; *) value=$4 ;; esac
        # shellcheck disable=SC2086
        refused "$class" "$words $long" 10 "$long" "${value%%[x,]*}" -- $words "$long" "$value"
    done < <(numbers)
}

# Every output option and a command line for it (OUT the path; inputs need not exist: an
# output is refused before any input is read). An output the binary lists and this table
# lacks fails the links class.
OUTPUT_LINES=(
    " --trace|--trace=OUT info"
    "collide --dump|collide a.obj b.obj --dump OUT"
    "collide-bench --out|collide-bench --out OUT"
    "mass --dump|mass cube --dump OUT"
    "buoyancy --png-every|buoyancy --png-every 2 OUT"
    "mass-bench --out|mass-bench --out OUT"
    "mesh generate --out|mesh generate cube --out OUT"
    "reproduce --out|reproduce --out OUT"
    "crowd --png|crowd --png OUT"
    "crowd-bench --out|crowd-bench --out OUT"
    "mlp detect --out|mlp detect image.png --out OUT"
    "mlp train --out|mlp train --out OUT"
    "mlp-bench --out|mlp-bench --out OUT"
    "lecture1 voronoi --png|lecture1 voronoi sites.json --png OUT"
    "lecture1 voronoi --npy|lecture1 voronoi sites.json --png v.png --npy OUT"
    "lecture1 distance-field --npy|lecture1 distance-field m.obj --npy OUT"
    "lecture1 swept-volume --out|lecture1 swept-volume m.obj --path p.json --out OUT"
    "lecture1 penetration --png|lecture1 penetration a.obj b.obj --png OUT"
    "lecture1 penetration --npy|lecture1 penetration a.obj b.obj --npy OUT"
    "lecture3 octree --npy|lecture3 octree --npy OUT"
    "lecture3 octree --png|lecture3 octree --png OUT"
    "lecture3 pyramid --npy|lecture3 pyramid --npy OUT"
    "lecture3 pyramid --png|lecture3 pyramid --png OUT"
    "lecture3 displace --out|lecture3 displace --out OUT"
    "lecture3 displace --npy|lecture3 displace --npy OUT"
    "lecture3 displace --png|lecture3 displace --png OUT"
    "lecture3 light --npy|lecture3 light --npy OUT"
    "lecture3 light --png|lecture3 light --png OUT"
    "lecture3 random --npy|lecture3 random --npy OUT"
    "lecture3 random --png|lecture3 random --png OUT"
    "lecture3 depth-mask --png|lecture3 depth-mask --png OUT"
    "lecture3 height-map --out|lecture3 height-map --out OUT"
    "lecture3-bench --out|lecture3-bench --out OUT"
    "selftest --junit|selftest --junit OUT"
    "view --screenshot|view --headless --frames 1 --screenshot OUT mass cube"
    "glsl export <DIR>|glsl export OUT"
    "learn --png|learn 1 --png OUT"
    "learn --guide|learn --guide OUT"
    "learn --out|learn reduction --bench --out OUT"
    "compare --out|compare r.json --out OUT"
    "compare --junit|compare --baseline old.json new.json --junit OUT"
    "assets export <DIR>|assets export OUT"
    "claims --out|claims --stamp old.json --like new.json --out OUT"
)

class_links() {
    local listed
    listed=$(printf '%s\n' "${OUTPUT_LINES[@]}" | cut -d'|' -f1 | sort)
    local missing
    missing=$(python3 - "$OPTIONS" <<'PY' | sort | comm -23 - <(echo "$listed")
import json, sys
for c in json.load(open(sys.argv[1]))["commands"]:
    for o in c["options"]:
        if o.get("role") == "output":
            name = f'--{o["long"]}' if o["long"] else f'<{o["id"].upper()}>'
            print(f'{c["command"]} {name}')
PY
)
    record "every output" links "$([[ -z $missing ]] && echo 1 || echo 0)" "outputs without a line here: $missing"
    local d=$WORK/links i=0 spec name line
    mkdir -p "$d"
    for spec in "${OUTPUT_LINES[@]}"; do
        IFS='|' read -r name line <<<"$spec"
        i=$((i + 1))
        ln -s "$d/nowhere$i" "$d/dangling$i"
        # shellcheck disable=SC2086
        refused links "$name (link to nothing)" 10 "$d/dangling$i" "does not exist" -- ${line//OUT/$d/dangling$i}
        [[ -L $d/dangling$i && ! -e $d/nowhere$i ]] ||
            record "$name" links 0 "the link was replaced or written through"
        ln -s "$d/loop${i}b" "$d/loop${i}a"
        ln -s "$d/loop${i}a" "$d/loop${i}b"
        # shellcheck disable=SC2086
        refused links "$name (loop of links)" 10 "loop" -- ${line//OUT/$d/loop${i}a}
    done
}

class_ignored() {
    local d=$WORK/ignored
    mkdir -p "$d"
    "$BIN" mesh generate cube --out "$d/cube.obj" >/dev/null 2>&1
    refused ignored "compare --markdown X --out D" 10 "--out" "--markdown" -- compare --markdown r.json --out "$d/page"
    refused ignored "--json with compare --markdown" 10 "--json" "nothing to print as JSON" -- --json compare --markdown r.json
    refused ignored "--json with view" 10 "--json" -- --json view --headless --frames 1 --screenshot "$d/v.png" mass cube
    refused ignored "lecture1 pairwise --tile 4 --formulation compute" 60 "--tile 4" "--formulation compute" -- lecture1 pairwise "$d/cube.obj" --tile 4 --formulation compute
    refused ignored "selftest --only ''" 60 "--only" "empty" -- selftest --only ''
    local cmd
    for cmd in "mesh generate cube --out $d/c2.obj" "glsl list" "compare r.json" "mlp train --out $d/n.json" "learn --list" "learn 1 --hint 1" "learn 1 --solution"; do
        # shellcheck disable=SC2086
        refused ignored "--trace with $cmd" 10 "--trace" "no GL call" -- --trace=$d/t.txt $cmd
    done
    [[ ! -e $d/t.txt ]] || record "--trace" ignored 0 "a trace file was written"
    local json
    for json in "learn 1 --hint 2" "learn 1 --solution" "info" "glsl list" "learn --list"; do
        # shellcheck disable=SC2086
        "$BIN" $json --json >"$d/j.out" 2>"$d/j.err"
        python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$d/j.out" 2>/dev/null
        record "$json --json" ignored "$([[ $? == 0 ]] && echo 1 || echo 0)" "not JSON: $(head -c 120 "$d/j.out")"
    done
    refused ignored "lecture1 compare --triangles 300,310" 60 "--triangles 300 and 310" -- lecture1 compare --triangles 300,310
    "$BIN" lecture1 compare --triangles 300,600 >"$d/c.out" 2>"$d/c.err"
    grep -q "so it has 336 triangles" "$d/c.err"
    record "lecture1 compare --triangles 300,600" ignored "$([[ $? == 0 ]] && echo 1 || echo 0)" "the rounding is not said: $(head -c 120 "$d/c.err")"
}

class_shared() {
    local d=$WORK/shared
    mkdir -p "$d"
    refused shared "--trace F selftest --junit F" 10 "one path for two outputs" -- --trace="$d/F" selftest --junit "$d/F"
    refused shared "--trace F.png crowd --png F.png" 10 "one path for two outputs" -- --trace="$d/F.png" crowd --png "$d/F.png"
    refused shared "lecture3 displace --out D --npy D/." 10 "one path for two outputs" -- lecture3 displace --out "$d/D" --npy "$d/D/."
    "$BIN" mesh generate cube --out "$d/in.obj" >/dev/null 2>&1
    refused shared "collide IN b.obj --dump IN" 10 "is the input" -- collide "$d/in.obj" b.obj --dump "$d/in.obj"
    [[ ! -e $d/F && ! -e $d/F.png ]] || record shared shared 0 "a shared output was written"
}

class_markers() {
    local d=$WORK/markers
    mkdir -p "$d"
    # A file of the user's named as the old lock was (`.dump.lock`) is never touched.
    echo mine >"$d/.dump.lock"
    "$BIN" mass cube --resolution 8 --dump "$d/dump" >/dev/null 2>"$d/e1"
    cmp -s <(echo mine) "$d/.dump.lock"
    record "mass --dump D/dump beside D/.dump.lock" markers "$([[ $? == 0 ]] && echo 1 || echo 0)" "the user's .dump.lock changed: $(head -c 120 "$d/e1")"
    # A file at the lock's own name that is not a lock: refused, kept.
    echo mine >"$d/.dump2.classic-gpgpu-lock"
    refused markers "a user's file at the lock's name" 60 "is in the way" -- mass cube --resolution 8 --dump "$d/dump2"
    cmp -s <(echo mine) "$d/.dump2.classic-gpgpu-lock" || record "the lock-named file" markers 0 "changed"
    # Another command's folder, even with --force: a report, a compare page, a lesson's pictures.
    "$BIN" reproduce --quick --only blocks --out "$d/report" >/dev/null 2>"$d/e2" ||
        record "reproduce --quick --only blocks" markers 0 "$(head -c 200 "$d/e2")"
    local marker_before
    marker_before=$(cat "$d/report/.classic-gpgpu-report" 2>/dev/null)
    refused markers "mass cube --dump REPORT --force" 60 "is \`classic-gpgpu reproduce\`'s" -- mass cube --resolution 8 --dump "$d/report" --force
    [[ $(cat "$d/report/.classic-gpgpu-report") == "$marker_before" ]] ||
        record "reproduce's marker" markers 0 "changed by mass --dump --force"
    "$BIN" compare "$d/report/results.json" --out "$d/page" >/dev/null 2>"$d/e3" ||
        record "compare" markers 0 "$(head -c 200 "$d/e3")"
    refused markers "reproduce --out C (a compare page) --force" 60 "is \`classic-gpgpu compare\`'s" -- reproduce --quick --only blocks --out "$d/page" --force
    [[ -f $d/page/comparison.json ]] || record "the compare page" markers 0 "comparison.json removed"
    "$BIN" learn 1 --png "$d/pictures" >/dev/null 2>&1
    refused markers "learn 2 --png D (lesson 1's) --force" 60 "'s (its .classic-gpgpu-report marker" -- learn 2 --png "$d/pictures" --force
    # The folder rule of lecture3 pyramid --npy: the user's file refused, kept with --force.
    mkdir -p "$d/npy" && echo mine >"$d/npy/max_0.npy"
    refused markers "lecture3 pyramid --npy DIR (a user's max_0.npy)" 60 "max_0.npy" "--force" -- lecture3 pyramid --npy "$d/npy"
    "$BIN" lecture3 pyramid --npy "$d/npy" --force >/dev/null 2>"$d/e4"
    cmp -s <(echo mine) "$d/npy/max_0.npy"
    record "lecture3 pyramid --npy DIR --force (a user's max_0.npy)" markers "$([[ $? == 0 ]] && echo 1 || echo 0)" "the user's max_0.npy was replaced"
    # No message contradicts itself (the marker named as a file of someone else's).
    ! grep -rqs "e.g. .classic-gpgpu-report" "$WORK"/log_case.err
    record "no self-contradicting refusal" markers "$([[ $? == 0 ]] && echo 1 || echo 0)" "$(cat "$WORK/log_case.err")"
}

class_mount() {
    local d=$WORK/mnt_out
    if [[ -z $MOUNTS ]]; then
        refused mount "reproduce --out /proc (a mount point)" 10 "a mount point" -- reproduce --out /proc
        return
    fi
    mount_tmpfs "$d" 1m || { SKIP=$((SKIP + 1)); return; }
    refused mount "reproduce --out MOUNT" 10 "a mount point" -- reproduce --quick --only blocks --out "$d"
    refused mount "mass cube --dump MOUNT --force" 10 "a mount point" -- mass cube --dump "$d" --force
    refused mount "crowd --png MOUNT" 10 "a mount point" -- crowd --png "$d"
    "$BIN" reproduce --quick --only blocks --out "$d/report" >/dev/null 2>"$WORK/log_mount.err"
    record "reproduce --out MOUNT/report" mount "$([[ $? == 0 ]] && echo 1 || echo 0)" "$(head -c 200 "$WORK/log_mount.err")"
    umount "$d"
}

# The cases of issue 52 with their outcomes, one row each: what the run did now.
ISSUE_ROWS=()
issue_case() { # name expect(refused|ok) args...
    local name=$1 expect=$2
    shift 2
    LOG=$WORK/log_issue
    local start=$SECONDS
    timeout 300 "$BIN" "$@" >"$LOG.out" 2>"$LOG.err"
    local rc=$? took=$((SECONDS - start))
    # The refusal's line (and the note on a bare --trace), else the run's first words.
    local text
    text=$(grep -E "^error|^note: a bare --trace" "$LOG.err" | head -c 400 | tr '\n' ' ')
    [[ -n $text ]] || text=$(head -c 200 "$LOG.out" | tr '\n' ' ')
    local ok=0
    if [[ $expect == refused ]]; then
        [[ ($rc == 1 || $rc == 2) && $took -le 30 ]] && ! grep -qi panicked "$LOG.err" && ok=1
    else
        [[ $rc == 0 ]] && ok=1
    fi
    record "$name" issue "$ok" "exit $rc after ${took}s: $text"
    ISSUE_ROWS+=("| \`$name\` | exit $rc, ${took} s | ${text//|/\\|} |")
}

class_issue() {
    local d=$WORK/issue
    mkdir -p "$d"
    issue_case "lecture3-bench --runs 100000000000 --out D" refused lecture3-bench --runs 100000000000 --out "$d/b1"
    issue_case "reproduce --quick --only paper4 --runs 1e11" refused reproduce --quick --only paper4 --runs 1e11 --out "$d/r1"
    issue_case "crowd-bench --runs 1e11" refused crowd-bench --runs 1e11 --out "$d/b2"
    issue_case "mlp-bench --runs 1e11" refused mlp-bench --runs 1e11 --out "$d/b3"
    issue_case "mass-bench --runs 18446744073709551615" refused mass-bench --runs 18446744073709551615 --out "$d/b4"
    issue_case "collide-bench --runs 1e11" refused collide-bench --runs 1e11 --out "$d/b5"
    issue_case "view --frames 18446744073709551615" refused view --headless --frames 18446744073709551615 --screenshot "$d/v.png" mass cube
    issue_case "lecture1 avatar-ccd --tolerance 1e308" refused lecture1 avatar-ccd --tolerance 1e308
    issue_case "lecture1 avatar-ccd --tolerance 1e100" refused lecture1 avatar-ccd --tolerance 1e100
    issue_case "lecture1 compare --triangles 100,200" refused lecture1 compare --triangles 100,200
    issue_case "reproduce --quick --only blocks --runs 3" ok reproduce --quick --only blocks --runs 3 --out "$d/r2"
    grep -q "best of 3" "$d/r2/index.html" 2>/dev/null
    record "the blocks table says best of 3" issue "$([[ $? == 0 ]] && echo 1 || echo 0)" "no 'best of 3' in $d/r2/index.html"
    "$BIN" mesh generate cube --out "$d/cube.obj" >/dev/null 2>&1
    issue_case "compare --markdown X --out D" refused compare --markdown "$d/r2/results.json" --out "$d/page"
    issue_case "--json compare --markdown X" refused --json compare --markdown "$d/r2/results.json"
    issue_case "learn 1 --solution --json" ok --json learn 1 --solution
    issue_case "learn 1 --hint 1 --json" ok --json learn 1 --hint 1
    issue_case "lecture1 pairwise --tile 4 --formulation compute" refused lecture1 pairwise "$d/cube.obj" --tile 4 --formulation compute
    issue_case "selftest --only ''" refused selftest --only ''
    issue_case "--trace F mesh (no GL call)" refused --trace="$d/t1" mesh generate cube --out "$d/c2.obj"
    issue_case "--trace F selftest --junit F" refused --trace="$d/F" selftest --junit "$d/F"
    issue_case "--trace F.png crowd --png F.png" refused --trace="$d/F.png" crowd --png "$d/F.png"
    mkdir -p "$d/npy" && echo mine >"$d/npy/max_0.npy"
    issue_case "lecture3 pyramid --npy DIR (user's max_0.npy)" refused lecture3 pyramid --npy "$d/npy"
    issue_case "lecture3 pyramid --npy DIR --force (user's max_0.npy)" refused lecture3 pyramid --npy "$d/npy" --force
    issue_case "mass cube --dump REPORT --force" refused mass cube --dump "$d/r2" --force
    ln -s "$d/nowhere.xml" "$d/L.xml"
    issue_case "selftest --junit L.xml (dangling)" refused selftest --junit "$d/L.xml"
    ln -s "$d/nowhere.json" "$d/L.json"
    issue_case "learn reduction --bench --out L.json (dangling)" refused learn reduction --bench --out "$d/L.json"
    ln -s "$d/nowhere.txt" "$d/L"
    issue_case "--trace L (dangling)" refused --trace="$d/L" info
    mkdir -p "$d/glsl/glsl/learn"
    ln -s "$d/nowhere.frag" "$d/glsl/glsl/learn/jacobi.frag"
    issue_case "glsl export DIR (a shader path dangling)" refused glsl export "$d/glsl" --force
    mkdir -p "$d/D" && echo mine >"$d/D/.dump.lock"
    issue_case "mass cube --dump D/dump (user's D/.dump.lock)" ok mass cube --resolution 8 --dump "$d/D/dump"
    cmp -s <(echo mine) "$d/D/.dump.lock"
    record "D/.dump.lock kept" issue "$([[ $? == 0 ]] && echo 1 || echo 0)" "the user's file changed"
    "$BIN" compare "$d/r2/results.json" --out "$d/C" >/dev/null 2>&1
    issue_case "reproduce --out C (a compare page)" refused reproduce --quick --only blocks --out "$d/C"
    [[ -f $d/C/comparison.json ]]
    record "C/comparison.json kept" issue "$([[ $? == 0 ]] && echo 1 || echo 0)" "removed"
    issue_case "--size -5" refused lecture3 random --size -5
    issue_case "--seed -1" refused lecture3 random --seed -1
    issue_case "--tolerance -1" refused lecture1 avatar-ccd --tolerance -1
    issue_case "--fraction -0.1" refused lecture3 depth-mask --fraction -0.1
    issue_case "--runs -1" refused mass-bench --runs -1
    issue_case "--trace info" ok --trace info
    issue_case "learn --trace 1" ok learn --trace 1
    issue_case "--trace t.txt info" refused --trace t.txt info
    ln -s "$d/loop2" "$d/loop1" && ln -s "$d/loop1" "$d/loop2"
    issue_case "reproduce --out LOOP" refused reproduce --quick --only blocks --out "$d/loop1"
    mkdir -p "$d/other" && echo x >"$d/other/notes.txt"
    "$BIN" mass cube --resolution 8 --dump "$d/m" >/dev/null 2>&1
    issue_case "learn 1 --png D (mass's --dump folder)" refused learn 1 --png "$d/m"
    issue_case "mass --dump D (a folder of the user's)" refused mass cube --resolution 8 --dump "$d/other"
    if [[ -n $MOUNTS ]] && mount_tmpfs "$d/mnt" 1m; then
        issue_case "reproduce --out MOUNT" refused reproduce --quick --only blocks --out "$d/mnt"
        issue_case "reproduce --out MOUNT --force" refused reproduce --quick --only blocks --out "$d/mnt" --force
        umount "$d/mnt"
    fi
}

run_classes() {
    echo "== option classes (every command, from 'classic-gpgpu options') =="
    class_bounds bounds 1e30 1e309 99999999999x99999999999,1
    class_bounds negative -5 -1e309 -5x-5,-5
    class_ignored
    class_shared
    class_links
    class_markers
    class_mount
    class_issue
    echo
    echo "issue 52's cases, rerun:"
    echo "| case | outcome | message |"
    echo "|---|---|---|"
    printf '%s\n' "${ISSUE_ROWS[@]}"
}

echo "binary: $BIN; renderer: $CLASSIC_GPGPU_RENDERER; mounts: ${MOUNTS:-no (ulimit -f, read-only skipped)}"
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
[[ -n ${HOSTILE_ONLY:-} ]] || run_classes
for spec in "${WRITERS[@]}"; do
    [[ -z $SHORT ]] || break
    IFS='|' read -r name kind out template <<<"$spec"
    [[ -z "${HOSTILE_ONLY:-}" || ",$HOSTILE_ONLY," == *",$name,"* ]] || continue
    # A clean run first: it must work, and its time bounds the random kill delays.
    d=$WORK/clean_$name
    mkdir -p "$d"
    start=$(date +%s.%N)
    if ! run_writer "$template" "$d/$out" "$WORK/log_clean_$name"; then
        record "$name" clean 0 "$(head -c 300 "$WORK/log_clean_$name.err")"
        continue
    fi
    seconds=$(python3 -c "print(max(0.2, $(date +%s.%N) - $start))")
    case_full "$name" "$kind" "$out" "$template"
    case_readonly "$name" "$kind" "$out" "$template"
    for signal in INT INT KILL KILL; do
        case_signal "$name" "$kind" "$out" "$template" "$signal" "$seconds"
    done
    case_twice "$name" "$kind" "$out" "$template"
    [[ $kind == dir ]] && case_folder_rule "$name" "$out" "$template"
done
echo
echo "cases: $RUN run, $PASS passed, $FAIL failed, $SKIP skipped"
for c in "${!COUNT[@]}"; do echo "  $c: ${PASSED[$c]:-0} of ${COUNT[$c]} passed"; done | sort
echo "signal cases where the signal stopped the run (not finished first): $SIGNALLED"
for f in "${FAILED[@]}"; do echo "  failed: $f"; done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
[[ $FAIL == 0 ]]
