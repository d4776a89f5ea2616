#!/usr/bin/env bash
# Configures and builds lifelong in Release into build/ (warnings are errors).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DLIFELONG_WERROR=ON "$@"
cmake --build build -j"$(nproc)"
