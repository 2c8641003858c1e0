#!/usr/bin/env bash
# Issue 18's and 19's frame targets, measured side by side in one run: warm frames (median of --frames N, the
# first frame of each process excluded by the median) of the default methods (`voxr render` with no method
# flags: voxel-exact shadows and refraction since issue 19; voxel + voxel-multi before) and of
# the exact Embree reference (--refraction reference: matched refraction, exact shadows), per scene and
# size, plus fresh `voxr render` processes of the built-in scene. Prints a Markdown table.
# usage: bench/frame_targets.sh [VOXR [BASELINE_VOXR]] [--frames N] [--fresh N]
#   BASELINE_VOXR: an older build's voxr, measured interleaved with VOXR (a before/after column)
set -euo pipefail
cd "$(dirname "$0")/.."
voxr=build/voxr baseline="" frames=5 fresh=5
args=()
while [ $# -gt 0 ]; do
  case $1 in
    --frames) frames=$2; shift 2 ;;
    --fresh) fresh=$2; shift 2 ;;
    -h|--help) sed -n 2,7p "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) args+=("$1"); shift ;;
  esac
done
[ ${#args[@]} -ge 1 ] && voxr=${args[0]}
[ ${#args[@]} -ge 2 ] && baseline=${args[1]}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median_of() { python3 -c "import json,sys; print(round(json.load(open(sys.argv[1]))['ms']['frame_median'],1))" "$1"; }
# The last frame's host time (ms, CPU time of the calling thread outside waits) and host synchronisations.
# A deforming scene adds its posing (pose_scene + set_scene, host) in brackets.
host_of() {
  python3 -c "
import json, sys
r = json.load(open(sys.argv[1]))
pose = r['frames'][-1].get('pose_ms', 0.0) if r.get('frames') else 0.0
extra = f' (+ pose {pose:.1f})' if pose > 0 else ''
print(f\"{r['ms']['host']:.2f}{extra} | {r['host_syncs']}\")" "$1"
}
frame() {  # BIN SCENE SIZE EXTRA... -> median warm frame ms
  local bin=$1 scene=$2 size=$3; shift 3
  "$bin" render "$scene" --size "$size" --frames "$frames" -q -o "$tmp/f.png" --report "$tmp/r.json" "$@"
  median_of "$tmp/r.json"
  [ -n "${host_out:-}" ] && host_of "$tmp/r.json" >"$host_out"
  return 0
}
echo "device: $("$voxr" devices 2>/dev/null | grep -m1 -E '^ *0:0' || true)"
echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'); frames per case: $frames (median)"
echo
echo "| scene | size | default ms | reference ms | default / reference | default host ms | host syncs |$([ -n "$baseline" ] && echo ' before ms |')"
echo "|---|---|---:|---:|---:|---:|---:|$([ -n "$baseline" ] && echo '---:|')"
for size in 640x480 1920x1080; do
  for scene in data/scenes/shadow-tree.json data/scenes/glass-sphere.json data/scenes/bunny-glass-130.json \
               data/scenes/glass-vase.json data/scenes/thin-vase-floor.json data/scenes/tree-1m.json; do
    d=$(host_out=$tmp/host frame "$voxr" "$scene" "$size")
    r=$(frame "$voxr" "$scene" "$size" --refraction reference)
    b=""
    [ -n "$baseline" ] && b=" $(frame "$baseline" "$scene" "$size") |"
    echo "| $(basename "$scene" .json) | $size | $d | $r | $(python3 -c "print(f'{$d/$r:.2f}')") | $(cat "$tmp/host") |$b"
  done
done
# A deforming scene: posed on the host and set_scene every frame, so nothing is kept between frames.
for scene in data/scenes/swaying-tree.json; do
  d=$(host_out=$tmp/host frame "$voxr" "$scene" 640x480)
  r=$(frame "$voxr" "$scene" 640x480 --refraction reference)
  b=""
  [ -n "$baseline" ] && b=" $(frame "$baseline" "$scene" 640x480) |"
  echo "| $(basename "$scene" .json) (deforming) | 640x480 | $d | $r | $(python3 -c "print(f'{$d/$r:.2f}')") | $(cat "$tmp/host") |$b"
done
echo
fresh_ms() {  # BIN -> wall ms of one fresh default render
  local s e
  s=$(date +%s%N); "$1" render -q -o "$tmp/p.png"; e=$(date +%s%N)
  echo $(((e - s) / 1000000))
}
"$voxr" render -q -o "$tmp/p.png"  # the kernel cache warm
[ -n "$baseline" ] && "$baseline" render -q -o "$tmp/p.png"
new=() old=()
for ((i = 0; i < fresh; i++)); do
  new+=("$(fresh_ms "$voxr")")
  [ -n "$baseline" ] && old+=("$(fresh_ms "$baseline")")
done
stats() { python3 -c "import statistics,sys; v=[float(x) for x in sys.argv[1:]]; print(f'{statistics.median(v):.0f} ms (min {min(v):.0f}, max {max(v):.0f})')" "$@"; }
echo "fresh \`voxr render\` of the built-in scene, warm kernel cache, $fresh processes: $(stats "${new[@]}")"
[ -n "$baseline" ] && echo "the same with the baseline, interleaved: $(stats "${old[@]}")"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
