#!/bin/sh
# The render region's pass rate (docs/performance.md, "Render region"): `tyndall render` of the
# default scene at 512x512, --gpu off, whole and with --region 192 192 128 128 (1/16 of the
# pixels), alternated twice so a change in the machine's load hits both; prints each run's
# passes/s and the ratio region / whole of their sums. The photon paths per pass stay (the
# region's pixels equal the whole image's), so the ratio is bounded by the photon stage's share.
# Prints the load average too: other work on the machine shows in every figure.
# Usage: bench/render_region_bench.sh [BUILD_DIR] [PASSES] [SCENE]
set -eu
build=${1:-build}
passes=${2:-8}
scene=${3:-}
out=$(mktemp -d)
rate() {
  "$build/app/tyndall" render $scene --size 512x512 --gpu off --passes "$passes" -q -o "$out/r.exr" "$@" |
    sed -n 's/.*(\([0-9.]*\) passes\/s.*/\1/p'
}
uptime
w1=$(rate); r1=$(rate --region 192 192 128 128)
w2=$(rate); r2=$(rate --region 192 192 128 128)
uptime
python3 -c "
w=[$w1,$w2]; r=[$r1,$r2]
print('whole 512x512: %s passes/s; region 128x128: %s passes/s; ratio region/whole %.2f' % (
 ', '.join('%.2f' % x for x in w), ', '.join('%.2f' % x for x in r), sum(r) / sum(w)))"
rm -rf "$out"
