#!/bin/sh
# The cost of emission (docs/performance.md, "Emissive media"): a pass of scenes/campfire.json at
# 512x512 against a pass of the same scene with the medium's "emission" removed (the same fire
# grid as plain smoke, lit by the scene's moonlight alone), 20000 photon paths per pass, --gpu off;
# the variants alternate and the order flips every round, so the machine's load falls on both
# alike. Prints each round, the medians and their ratio.
#
#   cpu   CPU seconds per pass, THREADS threads (default 1: worker threads that wait for each other
#         spin, and on a loaded machine the spinning counts as CPU time). Each round renders each
#         variant twice, 1 pass and 1 + N passes, and takes the difference of the process CPU
#         times (user + sys) over N: loading, start-up and writing the image taken out. CPU time,
#         not wall time, so that other work on a shared machine slows neither variant's figure much.
#   wall  wall seconds per pass of N-pass renders through scripts/bench-ab.sh (its 2 threads).
#
# Usage: bench/fire_emission_bench.sh cpu|wall [BUILD_DIR] [ROUNDS] [N] [THREADS]
set -eu
mode=${1:-}
case "$mode" in
    cpu | wall) ;;
    *) echo "usage: $0 cpu|wall [BUILD_DIR] [ROUNDS] [N] [THREADS]" >&2; exit 2 ;;
esac
build=${2:-build}
rounds=${3:-4}
n=${4:-6}
threads=${5:-1}
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fire="$here/scenes/campfire.json"
smoke="$tmp/campfire-smoke.json"
grep -v '"emission": {"grid": "temperature"' "$fire" | sed 's/"seed": 3},$/"seed": 3}}/' >"$smoke"

if [ "$mode" = wall ]; then
    "$build/app/tyndall" render "$smoke" --size 16x16 --passes 1 -q -o "$tmp/check.exr" >/dev/null
    uptime
    "$here/scripts/bench-ab.sh" "$rounds" "$n" \
        "smoke=$build/app/tyndall render $smoke --size 512x512 --photons 20000" \
        "fire=$build/app/tyndall render $fire --size 512x512 --photons 20000"
    uptime
    exit 0
fi

cpu() {  # cpu SCENE PASSES: CPU seconds of one render
    /usr/bin/time -f "%U %S" -o "$tmp/t" "$build/app/tyndall" render "$1" --size 512x512 --photons 20000 \
        --passes "$2" --threads "$threads" --gpu off -q -o "$tmp/x.exr" >/dev/null
    awk '{print $1 + $2}' "$tmp/t"
}
r=0
while [ "$r" -lt "$rounds" ]; do
    if [ $((r % 2)) -eq 0 ]; then order="smoke fire"; else order="fire smoke"; fi
    for v in $order; do
        if [ "$v" = smoke ]; then scene="$smoke"; else scene="$fire"; fi
        one=$(cpu "$scene" 1)
        many=$(cpu "$scene" $((1 + n)))
        per=$(awk -v a="$one" -v b="$many" -v n="$n" 'BEGIN {printf "%.3f", (b - a) / n}')
        echo "$v $per" >>"$tmp/results"
        echo "round $((r + 1)) $v: 1 pass $one s, $((1 + n)) passes $many s CPU -> $per CPU s/pass (load $(cut -d' ' -f1 /proc/loadavg))"
    done
    r=$((r + 1))
done
python3 - "$tmp/results" <<'PY'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
s = [float(p) for v, p in rows if v == "smoke"]
f = [float(p) for v, p in rows if v == "fire"]
print(f"smoke {statistics.median(s):.3f}  fire {statistics.median(f):.3f} CPU s/pass (medians of {len(s)} rounds)")
print("fire / smoke: %.2fx (rounds: %s)" % (statistics.median(f) / statistics.median(s),
      ", ".join("%.2fx" % (b / a) for a, b in zip(s, f))))
PY
