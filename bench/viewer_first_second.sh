#!/bin/sh
# The viewer's first seconds after a release (docs/performance.md, "The first seconds"): the
# default scene at 256x256, --gpu off, under Xvfb with llvmpipe. The window refines 1 pass, an
# orbit drag is released, and the image it shows is saved 0.5, 1, 2 and 5 s later (a preview
# image, stretched as the window shows it, until the first refined pass arrives); each is
# compared by relative RMS error with `tyndall render` of the last saved view at REF_PASSES
# passes (the converged image of that view). Once per preview setting: the default (1/4
# resolution, 1/16 photons), half (1/2, 1/4) and none (full resolution and photons). Prints one
# row per setting: seconds and error; writes DIR/first-second.dat for gnuplot.
# Prints the load average too: other work on the machine shows in every figure.
# Usage: bench/viewer_first_second.sh [BUILD_DIR] [REF_PASSES] [DIR]
set -eu
build=${1:-build}
refPasses=${2:-256}
out=${3:-$(mktemp -d)}
mkdir -p "$out"
view() {  # $1: name, then the preview options
  name=$1; shift
  printf 'wait-passes 1\ndrag left 128 128 168 136 8\nsleep 500\nsave %s\nsleep 500\nsave %s\nsleep 1000\nsave %s\nsleep 3000\nsave %s\nquit\n' \
    "$out/$name-0.5" "$out/$name-1" "$out/$name-2" "$out/$name-5" >"$out/$name.txt"
  xvfb-run -a -s '-screen 0 1280x1024x24' "$build/app/tyndall" view --size 256x256 --gpu off "$@" \
    --script "$out/$name.txt" >/dev/null
}
uptime
view default
view half --preview-scale 2 --preview-photons 4
view none --preview-scale 1 --preview-photons 1
uptime
"$build/app/tyndall" render "$out/default-5.json" --passes "$refPasses" --gpu off -q -o "$out/reference.exr" >/dev/null
uptime
printf '# seconds default half none\n' >"$out/first-second.dat"
for t in 0.5 1 2 5; do
  row=$t
  for name in default half none; do
    row="$row $("$build/bench/image_error" "$out/reference.exr" "$out/$name-$t.exr" | cut -d' ' -f2)"
  done
  echo "$row" >>"$out/first-second.dat"
done
cat "$out/first-second.dat"
