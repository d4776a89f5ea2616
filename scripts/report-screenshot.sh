#!/usr/bin/env bash
# Screenshots a report.html with headless Chromium (Debian package `chromium`), e.g.
#   scripts/report-screenshot.sh runs/latest/report.html docs/report.png
# made docs/report.png from `lifelong run scenarios/office_5min.yaml
# --modes standard,pruned,pruned-exact`. The page is laid out 1400 CSS px wide and drawn
# at SCALE (default 0.6); HEIGHT (default 2240) CSS px of it from the top are kept.
set -euo pipefail
html="$1" out="$2" scale="${3:-0.6}" height="${4:-2240}"
profile="$(mktemp -d)"  # a new, empty profile: nothing of the user's is read or kept
trap 'rm -rf "$profile"' EXIT
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync --disable-dev-shm-usage \
  --user-data-dir="$profile" --hide-scrollbars --force-device-scale-factor="$scale" \
  --window-size="1400,$height" --screenshot="$(realpath -m "$out")" \
  "file://$(realpath "$html")" >/dev/null 2>&1
echo "wrote $out"
