#!/usr/bin/env bash
# Installs those of the Debian packages named that are not installed yet (apt-get, as root or through sudo), so a
# rerun on a set-up machine installs nothing. Used by tools/setup.sh and tools/fuzz.sh.
#   bash tools/install_missing.sh LABEL PACKAGE...     (LABEL starts the one line it prints when it installs)
set -euo pipefail
label="$1"
shift
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]})) || exit 0
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "$label: installing ${missing[*]}"
$sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
