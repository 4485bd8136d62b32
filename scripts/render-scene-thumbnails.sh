#!/usr/bin/env bash
# Renders the scene library's thumbnails (docs/scenes/<name>.png, 256x256) with each scene's own
# "render" block (pass and photon counts chosen per scene). caustic-box.json's render block must
# stay that of `tyndall render` without a scene (loading/default_scene.h), so its counts are given here.
# Usage: scripts/render-scene-thumbnails.sh [scene names...]   (default: all of scenes/*.json)
set -euo pipefail
cd "$(dirname "$0")/.."
tyndall=./build/app/tyndall
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for f in scenes/*.json; do names+=("$(basename "$f" .json)"); done
fi
mkdir -p docs/scenes
for n in "${names[@]}"; do
  extra=()
  if [ "$n" = caustic-box ]; then extra=(--photons 12000 --passes 64); fi
  "$tyndall" render "scenes/$n.json" --size 256x256 "${extra[@]}" -o "docs/scenes/$n.png"
done
