#!/bin/sh
# Regenerates scenes/textures/tiles.png (64x64, 8x8 tiles of two terracotta shades, sRGB) with
# ImageMagick, for scenes/frosted-lantern.json.
set -e
cd "$(dirname "$0")/.."
convert -size 64x64 xc:'#b5651d' \( -size 8x8 pattern:checkerboard -scale 800% -fill '#e8d9b5' -opaque white \
  -fill '#6b3e1f' -opaque black \) -compose over -composite -colorspace sRGB -type TrueColor \
  -define png:color-type=2 -strip scenes/textures/tiles.png
