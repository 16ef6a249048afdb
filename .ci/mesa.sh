#!/usr/bin/env bash
# Installs lavapipe (Mesa's CPU Vulkan driver) at version 25 or later, which has hardware-
# style ray queries (VK_KHR_ray_query, VK_KHR_acceleration_structure) on the CPU. On Debian
# bookworm (Mesa 22) it takes mesa-vulkan-drivers from bookworm-backports, together with that
# suite's libdrm2 and libdrm-amdgpu1, which the driver needs. The backports suite is added
# from the machine's own apt source (same mirror, same keyring), so no mirror is named here.
# Elsewhere it installs the distribution's mesa-vulkan-drivers. Idempotent.
set -euo pipefail

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive

mesa_major() {
    dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null | sed 's/^[0-9]*://; s/\..*//'
}

if [ "$(mesa_major)" -ge 25 ] 2>/dev/null && ls /usr/share/vulkan/icd.d/lvp_icd*.json >/dev/null 2>&1; then
    exit 0
fi

codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
if [ "$codename" = bookworm ]; then
    suite="$codename-backports"
    if ! grep -rqs -- "$suite" /etc/apt/sources.list /etc/apt/sources.list.d/; then
        echo "enabling $suite from the machine's apt source"
        list=$(mktemp)
        # deb822 sources: each stanza that carries the release's own suite, with the suite
        # replaced by backports (comments dropped).
        for f in /etc/apt/sources.list.d/*.sources; do
            [ -e "$f" ] || continue
            awk -v suite="$codename" '
                BEGIN { RS = ""; FS = "\n" }
                {
                    keep = 0; out = ""
                    for (i = 1; i <= NF; i++) {
                        line = $i
                        if (line ~ /^#/) continue
                        if (line ~ /^Suites:/) {
                            n = split(substr(line, 8), s, " ")
                            for (j = 1; j <= n; j++) if (s[j] == suite) keep = 1
                            line = "Suites: " suite "-backports"
                        }
                        out = out line "\n"
                    }
                    if (keep) printf "%s\n", out
                }' "$f" >>"$list"
        done
        if [ -s "$list" ]; then
            $SUDO cp "$list" "/etc/apt/sources.list.d/$suite.sources"
        else
            # One-line sources: the release's own `deb` lines, suite replaced.
            grep -hE "^deb[[:space:]].*[[:space:]]$codename[[:space:]]" \
                /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
                sed -E "s/[[:space:]]$codename[[:space:]]/ $suite /" >"$list" || true
            [ -s "$list" ] || { echo "no apt source for $codename to derive $suite from" >&2; exit 1; }
            $SUDO cp "$list" "/etc/apt/sources.list.d/$suite.list"
        fi
        $SUDO chmod 644 /etc/apt/sources.list.d/"$suite".*
        rm -f "$list"
    fi
    $SUDO apt-get update -qq
    echo "installing mesa-vulkan-drivers (Mesa 25 lavapipe) from $suite"
    $SUDO apt-get install -y -qq -t "$suite" mesa-vulkan-drivers libdrm2 libdrm-amdgpu1
else
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq mesa-vulkan-drivers
fi
echo "lavapipe: Mesa $(dpkg-query -W -f='${Version}' mesa-vulkan-drivers)"
