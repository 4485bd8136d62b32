#!/bin/sh
# The viewer's interactive figures (docs/performance.md): preview images per second during an orbit
# drag, UI frame time p50/p95, and the latency from a mouse event to the first image of the new view,
# at a 512x512 window on the default scene, under Xvfb with llvmpipe. Runs the drag three times in
# one go: previews at 1/2 resolution and 1/4 of the photons ("half"), at 1/4 and 1/16 ("quarter"),
# and at full cost ("full", the baseline), so the ratios are measured on the same machine at the
# same time. Prints the load average too: other work on the machine shows in every figure.
# Usage: bench/viewer_bench.sh [BUILD_DIR] [extra tyndall view options]
set -eu
build=${1:-build}
[ $# -gt 0 ] && shift
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
run() {
  name=$1; shift
  xvfb-run -a -s '-screen 0 1280x1024x24' "$build/app/tyndall" view --size 512x512 --gpu off \
    --script "$here/viewer_drag.txt" --stats "$out/$name.json" "$@" >/dev/null
}
run half --preview-scale 2 --preview-photons 4 "$@"
run quarter --preview-scale 4 --preview-photons 16 "$@"
run full --preview-scale 1 --preview-photons 1 "$@"
for k in half quarter full; do
  printf '%s: ' "$k"
  python3 -c "
import json,sys; j=json.load(open('$out/$k.json'))
print('preview images/s %.1f (%d in %.1f s; per image: setup %.0f ms, setup+pass %.0f ms), refine passes/s %.2f, frame ms p50 %.1f p95 %.1f max %.1f, drag event->preview image ms p50 %.0f p95 %.0f (%d events), release->first refined image ms %s' % (
 j['preview_images_per_s'], j['preview_images'], j['preview_seconds'], j['preview_setup_ms_p50'], j['preview_job_ms_p50'], j['refine_passes_per_s'],
 j['frame_ms_p50'], j['frame_ms_p95'], j['frame_ms_max'], j['latency_ms_p50'], j['latency_ms_p95'], j['latency_events'], '/'.join('%.0f' % x for x in j['refine_latency_ms'])))"
done
uptime
rm -rf "$out"
