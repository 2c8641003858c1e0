#!/bin/sh
# Makes docs/images/refraction-methods.png: the ball with a figure inside (data/scenes/ball-figure.json) by
# voxel-multi, voxel-two, image-space and the matched and full references (exact shadows for all, 320x240),
# and below each its |difference| from the matched reference x 4 (white: off by 0.25 or more), the full
# reference's showing what the matched model leaves out (inner reflections). Needs build/ and oiiotool.
set -eu
cd "$(dirname "$0")/.."
o=$(mktemp -d)
trap 'rm -rf "$o"' EXIT
scene=data/scenes/ball-figure.json
for m in voxel-multi voxel-two image-space reference reference-full; do
  build/voxr render "$scene" --size 320x240 --refraction "$m" --shadows reference -o "$o/$m.exr" -q
done
for m in voxel-multi voxel-two image-space reference-full; do
  oiiotool "$o/$m.exr" --ch R,G,B "$o/reference.exr" --ch R,G,B --absdiff --mulc 4 -o "$o/$m.err.exr"
done
oiiotool --pattern constant:color=0,0,0 320x240 3 -o "$o/blank.exr"
oiiotool "$o/voxel-multi.exr" --ch R,G,B "$o/voxel-two.exr" --ch R,G,B "$o/image-space.exr" --ch R,G,B \
  "$o/reference.exr" --ch R,G,B "$o/reference-full.exr" --ch R,G,B "$o/voxel-multi.err.exr" \
  "$o/voxel-two.err.exr" "$o/image-space.err.exr" "$o/blank.exr" "$o/reference-full.err.exr" \
  --mosaic:pad=4 5x2 --colorconvert linear sRGB -d uint8 -o docs/images/refraction-methods.png
echo "wrote docs/images/refraction-methods.png"
