#!/bin/sh
# The cost of emission (docs/performance.md, "Emissive media"): a pass of scenes/campfire.json at
# 512x512 against a pass of the same scene with the medium's "emission" removed (the same fire
# grid as plain smoke, lit by the scene's moonlight alone), same photon paths per pass, --gpu off,
# through scripts/bench-ab.sh (the variants alternated, the order flipped every round, so the
# machine's load falls on both alike). Prints the medians of seconds per pass and their ratio.
# Usage: bench/fire_emission_bench.sh [BUILD_DIR] [ROUNDS] [PASSES]
set -eu
build=${1:-build}
rounds=${2:-4}
passes=${3:-6}
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -v '"emission": {"grid": "temperature"' "$here/scenes/campfire.json" | sed 's/"seed": 3},$/"seed": 3}}/' \
  > "$tmp/campfire-smoke.json"
"$build/app/tyndall" render "$tmp/campfire-smoke.json" --size 16x16 --passes 1 -q -o "$tmp/check.exr" >/dev/null
uptime
"$here/scripts/bench-ab.sh" "$rounds" "$passes" \
  "smoke=$build/app/tyndall render $tmp/campfire-smoke.json --size 512x512 --photons 20000" \
  "fire=$build/app/tyndall render $here/scenes/campfire.json --size 512x512 --photons 20000"
uptime
