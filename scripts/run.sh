#!/usr/bin/env bash
# The main job: install what is missing, build, run the default scenario into runs/default.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/apps/lifelong run -o runs/default "$@"
