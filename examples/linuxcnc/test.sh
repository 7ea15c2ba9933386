#!/usr/bin/env bash
# Integration test of linkagehexkins in a real LinuxCNC (2.9, uspace, simulated, headless).
#
# Installs linuxcnc-uspace and linuxcnc-uspace-dev if missing, builds the module against the
# installed headers, and runs LinuxCNC itself (motion controller, task, drive.py as the
# display) on a simulated hexapod along each path in paths/, once with linkagehexkins and
# once with genhexkins. The motion controller calls the module's kinematicsInverse for
# coordinated moves and its kinematicsForward on the joint feedback every servo cycle;
# linuxcnc_report checks every sampled Cartesian feedback against linkage's inverse
# kinematics and prints the two modules side by side. The last line starts with `linuxcnc:`.
# Nothing is skipped: if a step cannot run, the script says why and fails.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"

die() {
    echo "linuxcnc: FAILED — $*"
    exit 1
}

# 1. LinuxCNC, installed where it is missing.
bash "$here/install.sh" || exit 1
rtlib="$(dirname "$(dpkg -L linuxcnc-uspace | grep '/modules/genhexkins.so$' | head -1)")"
[ -d "$rtlib" ] || die "LinuxCNC's module directory not found (no genhexkins.so)"

# 2. The module, against the installed headers; rtapi_app loads modules from its own directory.
echo "== building linkagehexkins"
t0=$SECONDS
make -s -C "$here" >/dev/null || die "building linkagehexkins failed"
[ -w "$rtlib" ] || die "cannot install linkagehexkins.so into $rtlib (not writable: run as root)"
install -m 644 "$here/linkagehexkins.so" "$rtlib/" || die "installing linkagehexkins.so failed"
(cd "$root" && cargo build -q -p linkage-ffi --example linuxcnc_report) || die "building linuxcnc_report failed"
report="$root/target/debug/examples/linuxcnc_report"
echo "built in $((SECONDS - t0)) s"

# 3. Runs. As root, rtapi_app drops to RTAPI_UID and needs its socket where that uid can write.
work="$(mktemp -d /tmp/linkage-linuxcnc.XXXXXX)"
chmod 755 "$work"
if [ "$(id -u)" -eq 0 ]; then
    export RTAPI_UID="$(id -u nobody)"
fi
if pgrep -x rtapi_app >/dev/null; then
    die "another LinuxCNC or halrun session is running (rtapi_app): its HAL would clash with this one"
fi
run() { # run KINS PATH_NAME -> $work/NAME-KINS.csv
    local kins=$1 name=$2 dir="$work/$2-$1"
    mkdir -p "$dir"
    sed -e "s|@KINS@|$kins|" -e "s|@DRIVER@|$here/drive.py|" "$here/sim/hexapod.ini" > "$dir/hexapod.ini"
    cp "$here/sim/hexapod.hal" "$here/sim/hexapod.tbl" "$dir/"
    sed "s/PREFIX/$kins/" "$here/sim/geometry.hal" > "$dir/geometry.hal"
    # A path may come with pins of its own (paths/NAME.hal for both modules,
    # paths/NAME.KINS.hal for one), set after the geometry's.
    for extra in "$here/paths/$name.hal" "$here/paths/$name.$kins.hal"; do
        if [ -f "$extra" ]; then
            sed "s/PREFIX/$kins/" "$extra" >> "$dir/geometry.hal"
        fi
    done
    [ -n "${RTAPI_UID:-}" ] && chown "$RTAPI_UID" "$dir"
    local t0=$SECONDS rc=0
    (cd "$dir" && RTAPI_FIFO_PATH="$dir/rtapi_fifo" LINKAGE_PATH="$here/paths/$name.path" \
        LINKAGE_OUT="$work/$name-$kins.csv" LINKAGE_KINS="$kins" \
        timeout 300 linuxcnc hexapod.ini > "$dir/linuxcnc.out" 2>&1) || rc=$?
    if [ "$rc" -ne 0 ] || ! grep -q "drive.py: done" "$work/$name-$kins.csv.log" 2>/dev/null; then
        echo "--- linuxcnc output ($dir/linuxcnc.out)"; tail -20 "$dir/linuxcnc.out" || true
        echo "--- drive.py log"; cat "$work/$name-$kins.csv.log" 2>/dev/null || true
        die "LinuxCNC with $kins on path $name exited with status $rc"
    fi
    echo "$name with $kins: $(($(wc -l < "$work/$name-$kins.csv") - 1)) samples in $((SECONDS - t0)) s"
}
args=("$here/sim/geometry.hal")
for name in workspace singular screws; do
    run linkagehexkins "$name"
    run genhexkins "$name"
    args+=("$name" "$here/paths/$name.path" "$work/$name-linkagehexkins.csv" "$work/$name-genhexkins.csv")
done

# 4. The check and the side-by-side table; its exit status is the test's.
echo "== report (samples in $work)"
"$report" "${args[@]}"
