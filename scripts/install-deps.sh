#!/usr/bin/env bash
# Installs the Debian 12 packages lifelong builds against; does nothing when all are present.
set -euo pipefail
packages=(build-essential cmake pkg-config libbox2d-dev libeigen3-dev libyaml-cpp-dev
  libcli11-dev nlohmann-json3-dev libsuitesparse-dev libnanoflann-dev zlib1g-dev libpng-dev libopencv-dev gnuplot-nox
  libgtest-dev libgmock-dev libbenchmark-dev libosmesa6-dev libegl-dev libgl-dev libegl-mesa0)
# An optimized serial BLAS for CHOLMOD's supernodal factorization (the reference BLAS is
# several times slower on large pose graphs).
packages+=(libopenblas0-serial python3)
# The report test (tests/eval/report_browser_test.py) opens report.html in a real browser.
packages+=(chromium)
# The Slurm test (tests/apps/sweep_slurm_test.sh) starts its own munged, slurmctld and slurmd.
packages+=(slurm-wlm munge)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
