#!/usr/bin/env bash
# The color channel's cost (issue 21): fresh `voxr voxelize` processes on a 1.1 M-triangle bunny at --res 512,
# count,normal against count,normal,color, interleaved run by run (after one untimed pair); prints each run's report ms.wall and the
# median (min-max) per case. Usage: bench/color_bench.sh [runs=5] [res=512]
set -euo pipefail
runs=${1:-5}
res=${2:-512}
here=$(cd "$(dirname "$0")/.." && pwd)
voxr=${VOXR:-$here/build/voxr}
work=${TMPDIR:-/tmp}/voxr-color-bench
mkdir -p "$work"
mesh=$work/bunnyx16-color.ply
[ -f "$mesh" ] || python3 "$here/bench/color_mesh.py" "$here/data/meshes/bunny.obj" 2 "$mesh"
# One untimed pair first: the programs come from the cache after it.
for channels in occ,count,normal occ,count,normal,color; do
  "$voxr" voxelize "$mesh" --res "$res" --channels "$channels" -q 2>/dev/null
done
declare -A walls cpus
for r in $(seq 1 "$runs"); do
  for channels in occ,count,normal occ,count,normal,color; do
    # CPU time (user + system) of the whole process as well: less sensitive than wall time to other load.
    t0=$(awk '{print $14+$15+$16+$17}' /proc/$$/stat)
    ( "$voxr" voxelize "$mesh" --res "$res" --channels "$channels" -q --report "$work/r.json" 2>/dev/null )
    t1=$(awk '{print $14+$15+$16+$17}' /proc/$$/stat)
    cpu=$(( (t1 - t0) * 1000 / $(getconf CLK_TCK) ))
    w=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['ms']['wall'])" "$work/r.json")
    echo "run $r $channels ms.wall $w cpu_ms $cpu"
    walls[$channels]+="$w "
    cpus[$channels]+="$cpu "
  done
done
for channels in occ,count,normal occ,count,normal,color; do
  for what in wall cpu; do
    if [ $what = wall ]; then values=${walls[$channels]}; else values=${cpus[$channels]}; fi
    python3 - "$channels" "$what" $values <<'PY'
import statistics, sys
v = [float(x) for x in sys.argv[3:]]
print(f"{sys.argv[1]:<24} {sys.argv[2]:<5} median {statistics.median(v):.1f} ms ({min(v):.1f}-{max(v):.1f}), {len(v)} runs")
PY
  done
done
echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u)"
