#!/bin/sh
# The viewer at rest (docs/performance.md): the default scene at 512x512, --gpu off, under Xvfb with
# llvmpipe, left alone for 30 s after its first refined pass; prints the frames the window drew,
# the images it showed, its refined passes/s, and the passes/s of `tyndall render --time 30` of the
# same scene, size and settings run right after (the ratio is what the window costs the renderer).
# Prints the load average too: other work on the machine shows in every figure.
# Usage: bench/viewer_rest_bench.sh [BUILD_DIR] [SECONDS]
set -eu
build=${1:-build}
secs=${2:-30}
out=$(mktemp -d)
printf 'wait-passes 1\nsleep %s\nquit\n' "$((secs * 1000))" >"$out/rest.txt"
uptime
xvfb-run -a -s '-screen 0 1280x1024x24' "$build/app/tyndall" view --size 512x512 --gpu off \
  --script "$out/rest.txt" --stats "$out/rest.json" >/dev/null
uptime
render=$("$build/app/tyndall" render --size 512x512 --gpu off --time "$secs" -o "$out/render.exr" |
  sed -n 's/.*(\([0-9.]*\) passes\/s.*/\1/p')
uptime
python3 -c "
import json; j=json.load(open('$out/rest.json')); r=float('$render')
print('at rest %d s: %d frames drawn, %d images shown (%.2f frames per image), viewer %.2f refined passes/s (%d passes), tyndall render %.2f passes/s, ratio %.2f' % (
 $secs, j['frames'], j['images_shown'], j['frames'] / max(j['images_shown'], 1), j['refine_passes_per_s'], j['refine_passes'], r, j['refine_passes_per_s'] / r))"
rm -rf "$out"
