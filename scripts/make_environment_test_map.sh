#!/bin/sh
# Regenerates scenes/textures/environment-test-map.exr (64x32 half-float lat-long, linear) with
# OpenImageIO's oiiotool, for docs/scene-format.md's mapping figure: the sky above 45 degrees of
# elevation white, the ground below -45 degrees dark grey, and between them four coloured quarters
# of the horizon centred on the directions they face: +Z red (the image's centre), +X green
# (u = 1/4), -X blue (u = 3/4), -Z yellow (the left and right edges).
set -e
cd "$(dirname "$0")/.."
oiiotool --create 64x32 3 \
  --fill:color=1,1,1 64x8+0+0 \
  --fill:color=0.1,0.1,0.1 64x8+0+24 \
  --fill:color=1,0.85,0.1 8x16+0+8 --fill:color=1,0.85,0.1 8x16+56+8 \
  --fill:color=0.1,0.9,0.1 16x16+8+8 \
  --fill:color=1,0.1,0.1 16x16+24+8 \
  --fill:color=0.15,0.3,1 16x16+40+8 \
  -d half --compression zip -o scenes/textures/environment-test-map.exr
