#!/usr/bin/env bash
# Hostile-but-fair runs against every command that writes files (Linux only).
#
#   scripts/hostile.sh [BINARY]      (default: target/release/classic-gpgpu)
#   HOSTILE_ONLY=crowd,mass-dump scripts/hostile.sh    (only those writers)
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

BIN=${1:-target/release/classic-gpgpu}
BIN=$(realpath "$BIN")
if [[ -z "${HOSTILE_IN_NS:-}" ]] && command -v unshare >/dev/null &&
    unshare --user --map-root-user --mount true 2>/dev/null; then
    HOSTILE_IN_NS=1 HOSTILE_ONLY="${HOSTILE_ONLY:-}" exec unshare --user --map-root-user --mount "$0" "$BIN"
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
    "view-screenshot|file|v.png|view --headless --frames 1 --size 64x48 --screenshot OUT --force mass cube"
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
temporaries() { find "$1" \( -name '.*.tmp-*' -o -name '.*.staging-*' -o -name '.*.lock' \) 2>/dev/null; }

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
    [[ -z "$(temporaries "$d")" ]] || why+="temporary left after the next run "
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

echo "binary: $BIN; renderer: $CLASSIC_GPGPU_RENDERER; mounts: ${MOUNTS:-no (ulimit -f, read-only skipped)}"
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
for spec in "${WRITERS[@]}"; do
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
