#!/bin/sh
# Regenerates scenes/textures/sky-sun.exr (128x64 half-float lat-long, linear radiance) with
# OpenImageIO's oiiotool, for scenes/sunlit-fog.json: a sky from deep blue overhead to pale at the
# horizon, a dark brown ground, and a small warm sun (2x2 texels, radiance 300, about 1000 times
# the sky's) about 35 degrees above the horizon, a quarter turn from the image's centre (toward +X).
set -e
cd "$(dirname "$0")/.."
# The gradient runs over the whole height (pale at the horizon, the middle row) before the ground
# covers the lower half.
oiiotool --pattern fill:top=0.15,0.3,0.75:bottom=1.35,1.3,1.05 128x64 3 \
  --fill:color=0.1,0.08,0.06 128x32+0+32 \
  --fill:color=300,270,220 2x2+32+19 \
  -d half --compression zip -o scenes/textures/sky-sun.exr
