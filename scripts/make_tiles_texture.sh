#!/bin/sh
# Regenerates scenes/textures/tiles.png (64x64 sRGB: 8x8-texel tiles alternating cream and
# terracotta) with ImageMagick, for scenes/frosted-lantern.json.
set -e
cd "$(dirname "$0")/.."
convert \( xc:'#e8d9b5' xc:'#a0522d' +append \) \( xc:'#a0522d' xc:'#e8d9b5' +append \) -append \
  -filter point -scale 800% -write mpr:t +delete -size 64x64 tile:mpr:t \
  -type TrueColor -define png:color-type=2 -strip scenes/textures/tiles.png
