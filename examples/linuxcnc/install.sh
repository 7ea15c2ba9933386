#!/usr/bin/env bash
# Installs LinuxCNC 2.9 (linuxcnc-uspace, linuxcnc-uspace-dev) from Debian where it is missing,
# without recommended packages (those pull in a real-time kernel and docs), and checks that
# its tools and Python modules are there. Nothing to do where it is installed. Run by test.sh,
# and by .ci/run ahead of time, beside the build, so that CI does not wait for the download.
set -euo pipefail

die() {
    echo "linuxcnc: FAILED — $*"
    exit 1
}

packages=(linuxcnc-uspace linuxcnc-uspace-dev)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
    [ "$(id -u)" -eq 0 ] || die "${missing[*]} not installed and not root: run apt-get install -y --no-install-recommends ${missing[*]}"
    echo "== installing ${missing[*]}"
    t0=$SECONDS
    export DEBIAN_FRONTEND=noninteractive
    # A stale package list makes the install fail: update it once, then install.
    apt-get update -q >/dev/null || die "apt-get update failed"
    apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null \
        || die "apt-get install ${missing[*]} failed"
    echo "installed in $((SECONDS - t0)) s"
fi
for tool in linuxcnc halcmd rtapi_app; do
    command -v "$tool" >/dev/null || die "$tool not found after installing ${packages[*]}"
done
/usr/bin/python3 -c 'import linuxcnc, hal' 2>/dev/null \
    || die "/usr/bin/python3 cannot import LinuxCNC's linuxcnc and hal modules"
