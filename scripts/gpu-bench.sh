#!/usr/bin/env bash
# One prepared benchmark run of voxr: bundle on the Debian side, run the whole matrix on a bare GPU machine
# in one call, or a tiny version of the same matrix on PoCL (--quick, a ctest test). docs/gpu.md explains.
set -uo pipefail

usage() {
  cat <<'EOF'
usage: scripts/gpu-bench.sh [--quick] [--dry-run] [--voxr PATH] [--device SEL] [--out DIR]
                            [--stages LIST] [--limit STAGE=SECONDS]... [--budget SECONDS]
       scripts/gpu-bench.sh --bundle [DIR] [--from BUILD_DIR]

Runs voxr's benchmark matrix and writes CSV/Markdown per stage, each command's log and a summary index
(index.md, index.csv) into the output folder.

  (no mode)        the whole matrix on the GPU (device NVIDIA), under 8 minutes: stages
                   render      fresh `voxr voxelize` / `voxr render` processes of the built-in scene and
                               tree-1m with --profile --report (the first one also warms the kernel caches)
                   voxelize    `voxr bench voxelize`, bunny x16 at 256, 512, 1024, 2048, occupancy and
                               count+normal: fresh process, in-process job and per frame
                   table1      `voxr bench table1`: every method x the papers' six models x 128, 256, 512
                   shadows     `voxr bench shadows` (its scenes, methods and grids; tree-1m separately)
                   refraction  `voxr bench refraction` per scene (its methods at grids 128, 256, 512)
                   animation   `voxr bench animation` (48 frames of each deforming scene)
                   the frame stages at 640x480 and 1920x1080
  --quick          the same commands on tiny sizes (torus, grids 32/64, 160x120 frames, one repeat, a
                   subset of scenes and methods) on the default OpenCL device (PoCL here), then checks the
                   outputs; seconds, not minutes (the gpu_bench_quick ctest test)
  --dry-run        print the plan (every command with its stage and time limit) and check it: the voxr
                   programs exist, every scene file is there, every flag is one the subcommand accepts.
                   Runs no benchmark and touches no device.
  --bundle [DIR]   (Debian side) build a small Release tree (build-gpu: no viewer, tests, OpenVDB) and
                   pack voxr, voxr-render, the shared libraries they need (not libc, libstdc++ or the
                   OpenCL loader), the benchmark
                   meshes and gpu-env.sh into DIR/voxr-bundle.tar.gz (DIR default .dev, git-ignored);
                   carry DIR to the GPU machine
  --from BUILD     with --bundle: take the programs from an already built tree instead

  --voxr PATH      the voxr to run, or a bundle (default: .dev/voxr-bundle.tar.gz when bundled, else
                   build/voxr); voxr-render must lie beside it. A bundle is unpacked into $TMPDIR (or
                   /tmp), its lib/ goes on LD_LIBRARY_PATH and its meshes/ become VOXR_MESH_DIR unless set
  --device SEL     OpenCL device, P:D or a name substring (default NVIDIA; --quick: VOXR_DEVICE or voxr's
                   default device)
  --out DIR        results folder (default $OUT when set, else out/gpu-bench-DATE)
  --pack           write the results elsewhere and leave only index.md, index.csv and
                   gpu-bench-results.tar.gz (everything) in the results folder: the device tool brings
                   back at most 8 files from $OUT. The default when the folder is $OUT
  --stages LIST    comma-separated subset of render,voxelize,table1,shadows,refraction,animation
  --limit S=SEC    a stage's time limit in seconds (defaults: render 45, voxelize 90, table1 75,
                   shadows 90, refraction 100, animation 50; --quick: 120 each); a step that runs past
                   it is stopped, the stage's later steps are skipped, and the run goes on
  --budget SEC     the whole run's limit (default 455; --quick 300): no step starts or runs past it
  -h, --help       this text

Exit status: 0 when every step finished and its outputs check out (files there, CSV rows with the
header's field count, no NaN or infinite field but a PSNR's inf where an image equals its reference, no
NaN in Markdown or JSON); 1 when a step failed, timed out or was skipped, or an output is bad (index.md
says which); 2 for a usage error.
EOF
}

die() {
  echo "gpu-bench: $*" >&2
  exit 2
}

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root" || exit 2

mode=run
quick=0
dry=0
voxr=""
device=""
device_given=0
out=""
pack=0
stages_arg=""
budget=""
bundle_dir=.dev
from=""
declare -A limit_arg=()
argv_text="scripts/gpu-bench.sh$(printf ' %q' "$@")"

while [ $# -gt 0 ]; do
  case $1 in
    -h | --help) usage; exit 0 ;;
    --quick) quick=1 ;;
    --dry-run) dry=1 ;;
    --bundle)
      mode=bundle
      if [ $# -gt 1 ] && [[ $2 != -* ]]; then bundle_dir=$2; shift; fi ;;
    --from) [ $# -gt 1 ] || die "--from needs a build folder"; from=$2; shift ;;
    --voxr) [ $# -gt 1 ] || die "--voxr needs a path"; voxr=$2; shift ;;
    --device) [ $# -gt 1 ] || die "--device needs a value"; device=$2; device_given=1; shift ;;
    --out) [ $# -gt 1 ] || die "--out needs a folder"; out=$2; shift ;;
    --pack) pack=1 ;;
    --stages) [ $# -gt 1 ] || die "--stages needs a list"; stages_arg=$2; shift ;;
    --limit)
      [ $# -gt 1 ] || die "--limit needs STAGE=SECONDS"
      [[ $2 =~ ^([a-z0-9]+)=([0-9]+)$ ]] || die "--limit $2: expected STAGE=SECONDS"
      limit_arg[${BASH_REMATCH[1]}]=${BASH_REMATCH[2]}
      shift ;;
    --budget)
      if [ $# -lt 2 ] || [[ ! $2 =~ ^[0-9]+$ ]]; then die "--budget needs whole seconds"; fi
      budget=$2; shift ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
  shift
done

# ---------------------------------------------------------------------------------------------------------
# Bundling (Debian side). The logic of ../shared/device/bundle.sh and gpu-env.sh, kept here so that the
# repository does not depend on ../shared: every executable and each shared library it loads, except the C
# and C++ runtime and the OpenCL loader (the GPU machine's driver brings its own).

write_gpu_env() {
  cat >"$1" <<'EOF'
#!/usr/bin/env bash
# Run a bundled program on the GPU machine with both OpenCL platforms visible: PoCL (its CPU, where
# installed) and NVIDIA (the GPU). usage: gpu-env.sh PROGRAM [ARGS...]   (written by scripts/gpu-bench.sh)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
find_lib() {
  local found d
  found=$(ldconfig -p 2>/dev/null | awk -v n="$1" '$1 == n {print $NF; exit}')
  for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu /usr/local/cuda/lib64; do
    [ -n "$found" ] || [ ! -e "$d/$1" ] || found=$d/$1
  done
  echo "$found"
}
if [ ! -e /etc/OpenCL/vendors/nvidia.icd ]; then
  lib=$(find_lib libnvidia-opencl.so.1)
  if [ -n "$lib" ]; then
    if ! { mkdir -p /etc/OpenCL/vendors 2>/dev/null && echo "$lib" >/etc/OpenCL/vendors/nvidia.icd 2>/dev/null; }; then
      mkdir -p "$here/vendors" && echo "$lib" >"$here/vendors/nvidia.icd"
      export OCL_ICD_VENDORS="$here/vendors"
    fi
  fi
fi
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
[ -n "$(find_lib libOpenCL.so.1)" ] || export LD_LIBRARY_PATH="$LD_LIBRARY_PATH:$here/lib-loader"
exec "$@"
EOF
  chmod +x "$1"
}

bundle_meshes=(bunny.obj armadillo.off refined_elephant.off mech-holes-shark.off)

bundle_skip='^(linux-vdso|libc\.so|libm\.so|libstdc\+\+|libgcc_s|ld-linux|libpthread|libdl\.so|librt\.so|libOpenCL\.so)'

do_bundle() {
  local build=$from
  if [ -z "$build" ]; then
    build="build-gpu"
    local launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    echo "gpu-bench: configuring and building $build (Release, no viewer, tests or OpenVDB)"
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DVOXR_BUILD_VIEWER=OFF -DVOXR_BUILD_TESTS=OFF \
      -DVOXR_BUILD_BENCH=OFF -DVOXR_WITH_OPENVDB=OFF "${launcher[@]}" >/dev/null || exit 1
    cmake --build "$build" -j"$(nproc)" --target voxr voxr-render || exit 1
  fi
  local exe
  for exe in voxr voxr-render; do
    [ -x "$build/$exe" ] || { echo "gpu-bench: $build/$exe is not built" >&2; exit 1; }
  done
  local mesh_dir=${VOXR_MESH_DIR:-data/meshes} m
  for m in "${bundle_meshes[@]}"; do
    [ -f "$mesh_dir/$m" ] || { echo "gpu-bench: $mesh_dir/$m is missing (scripts/fetch-meshes.sh)" >&2; exit 1; }
  done
  local stage
  stage=$(mktemp -d "${TMPDIR:-/tmp}/voxr-bundle.XXXXXX") || exit 1
  local b=$stage/voxr-bundle
  mkdir -p "$b/lib" "$b/lib-loader" "$b/meshes"
  # Every library the programs need, through the dependencies of each library kept.
  declare -A where=() done_lib=()
  local name path
  while read -r name path; do where[$name]=$path; done < <(ldd "$build/voxr" "$build/voxr-render" |
    awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}')
  local queue=() n
  for exe in voxr voxr-render; do
    cp -L "$build/$exe" "$b/"
    mapfile -t -O "${#queue[@]}" queue < <(readelf -d "$build/$exe" | awk '/NEEDED/ {gsub(/[][]/, "", $5); print $5}')
  done
  while [ ${#queue[@]} -gt 0 ]; do
    n=${queue[0]}
    queue=("${queue[@]:1}")
    [[ -z ${done_lib[$n]:-} && ! $n =~ $bundle_skip ]] || continue
    done_lib[$n]=1
    [ -n "${where[$n]:-}" ] || { echo "gpu-bench: ldd does not resolve $n" >&2; exit 1; }
    cp -L "${where[$n]}" "$b/lib/$n" || exit 1
    mapfile -t -O "${#queue[@]}" queue < <(readelf -d "${where[$n]}" | awk '/NEEDED/ {gsub(/[][]/, "", $5); print $5}')
  done
  # The OpenCL loader stays the machine's; one travels in lib-loader/ for a machine that has none.
  cp -L "${where[libOpenCL.so.1]}" "$b/lib-loader/" || exit 1
  # Symbols are not needed to run.
  strip --strip-unneeded "$b/voxr" "$b/voxr-render" "$b"/lib/* "$b"/lib-loader/* 2>/dev/null || true
  # Check: with the bundle first on the path, every library resolves inside it (or is the C/C++ runtime).
  local outside
  outside=$(LD_LIBRARY_PATH="$b/lib" ldd "$b/voxr" "$b/voxr-render" |
    awk -v skip="$bundle_skip" -v dir="$b/lib/" '$2 == "=>" && $1 !~ skip && (index($3, dir) != 1) {print $1, $3, $4}')
  if [ -n "$outside" ]; then
    echo "gpu-bench: the bundle does not hold every library:" >&2
    echo "$outside" >&2
    exit 1
  fi
  for m in "${bundle_meshes[@]}"; do cp -L "$mesh_dir/$m" "$b/meshes/"; done
  write_gpu_env "$b/gpu-env.sh"
  {
    echo "bundled: $(date -u '+%Y-%m-%d %H:%M:%S UTC') on $(uname -n) ($(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME"))"
    echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo ' (with uncommitted changes)')"
    echo "from: $build"
    echo "libraries: $(find "$b/lib" -type f | wc -l)"
    echo "command: $argv_text"
  } >"$b/BUNDLE.txt"
  mkdir -p "$bundle_dir" || exit 1
  rm -f "$bundle_dir/voxr-bundle.tar.gz"
  tar -czf "$bundle_dir/voxr-bundle.tar.gz" -C "$stage" voxr-bundle || exit 1
  cp "$b/BUNDLE.txt" "$bundle_dir/"
  echo "gpu-bench: $bundle_dir/voxr-bundle.tar.gz: $(du -sh "$b" | cut -f1) unpacked," \
    "$(du -sh "$bundle_dir/voxr-bundle.tar.gz" | cut -f1) packed; $(sed -n 4p "$b/BUNDLE.txt")"
  rm -rf "$stage"
  echo "gpu-bench: next, on the GPU machine (carry $bundle_dir): scripts/gpu-bench.sh"
}

if [ $mode = bundle ]; then
  if [ $quick = 1 ] || [ $dry = 1 ]; then die "--bundle takes no --quick or --dry-run"; fi
  do_bundle
  exit 0
fi

# ---------------------------------------------------------------------------------------------------------
# The matrix. Every command is the same in both modes; --quick changes only the sizes.

all_stages=(render voxelize table1 shadows refraction animation)
declare -A limit=()
if [ $quick = 1 ]; then
  for s in "${all_stages[@]}"; do limit[$s]=120; done
  budget=${budget:-300}
  sizes=(160x120)
  vox_meshes=torus vox_res=(32 64) vox_cases=occ,count-normal vox_repeat=1 vox_warmup=0 vox_fresh=1
  t1_models=(--models Torus=torus) t1_res=(32) t1_repeat=1 t1_warmup=0
  sh_args=(--scenes default --methods "voxel-center,filter" --res 32)
  sh_big_scene=data/scenes/glass-floor.json sh_big_res=32
  sh_repeat=1 sh_warmup=0 sh_fresh=1
  rf_scenes=(data/scenes/glass-sphere.json) rf_methods=(--methods "voxel-multi-papers-smooth,image-space")
  rf_res=32 rf_shadow_res=32 rf_repeat=1 rf_warmup=0 rf_fresh=1
  an_scenes=(--scenes data/scenes/passing-objects.json) an_frames=2 an_fresh=1
  render_res=32 render_frames=2 render_big=data/scenes/glass-floor.json
  [ $device_given = 1 ] || device=${VOXR_DEVICE:-}
else
  limit=([render]=45 [voxelize]=90 [table1]=75 [shadows]=90 [refraction]=100 [animation]=50)
  budget=${budget:-455}
  sizes=(640x480 1920x1080)
  vox_meshes=bunnyx16 vox_res=(256 512 1024 2048) vox_cases=occ,count-normal vox_repeat=5 vox_warmup=1
  vox_fresh=3
  t1_models=() t1_res=(128 256 512) t1_repeat=3 t1_warmup=1
  sh_args=()
  sh_big_scene=data/scenes/tree-1m.json sh_big_res=256,512
  sh_repeat=5 sh_warmup=1 sh_fresh=1
  rf_scenes=(data/scenes/glass-sphere.json data/scenes/bunny-glass-130.json data/scenes/glass-vase.json
    data/scenes/ball-figure.json data/scenes/gem.json data/scenes/thin-shell.json
    data/scenes/sphere-nearby.json)
  rf_methods=() rf_res=128,256,512 rf_shadow_res=256 rf_repeat=5 rf_warmup=1 rf_fresh=1
  an_scenes=() an_frames=48 an_fresh=1
  render_res=256 render_frames=10 render_big=data/scenes/tree-1m.json
  [ $device_given = 1 ] || device=NVIDIA
fi
for s in "${!limit_arg[@]}"; do
  [[ " ${all_stages[*]} " == *" $s "* ]] || die "--limit: unknown stage '$s' (${all_stages[*]})"
  limit[$s]=${limit_arg[$s]}
done
stages=("${all_stages[@]}")
if [ -n "$stages_arg" ]; then
  IFS=, read -r -a stages <<<"$stages_arg"
  for s in "${stages[@]}"; do
    [[ " ${all_stages[*]} " == *" $s "* ]] || die "--stages: unknown stage '$s' (${all_stages[*]})"
  done
fi

# The programs: a bundle (its libraries and meshes) or a build tree.
if [ -z "$voxr" ]; then
  if [ -f .dev/voxr-bundle.tar.gz ]; then voxr=.dev/voxr-bundle.tar.gz; elif [ -x build/voxr ]; then voxr=build/voxr; fi
  [ -n "$voxr" ] || {
    echo "gpu-bench: no voxr: build it (build/voxr) or bundle it (--bundle), or pass --voxr" >&2
    exit 1
  }
fi
# A bundle travels packed; it is unpacked once per content into the temporary folder.
if [[ $voxr == *.tar.gz ]]; then
  [ -f "$voxr" ] || { echo "gpu-bench: no bundle $voxr" >&2; exit 1; }
  unpacked=${TMPDIR:-/tmp}/voxr-bundle-$(cksum <"$voxr" | cut -d' ' -f1)
  if [ ! -x "$unpacked/voxr-bundle/voxr" ]; then
    rm -rf "$unpacked" && mkdir -p "$unpacked" && tar -xzf "$voxr" -C "$unpacked" ||
      { echo "gpu-bench: cannot unpack $voxr into $unpacked" >&2; exit 1; }
  fi
  voxr=$unpacked/voxr-bundle/voxr
fi
[ -x "$voxr" ] || { echo "gpu-bench: $voxr is not an executable" >&2; exit 1; }
voxr=$(cd "$(dirname "$voxr")" && pwd)/$(basename "$voxr")
vdir=$(dirname "$voxr")
[ -x "$vdir/voxr-render" ] || { echo "gpu-bench: $vdir/voxr-render is missing (build the voxr-render target)" >&2; exit 1; }
if [ -d "$vdir/lib" ]; then
  export LD_LIBRARY_PATH="$vdir/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  [ -n "${VOXR_MESH_DIR:-}" ] || [ ! -d "$vdir/meshes" ] || export VOXR_MESH_DIR="$vdir/meshes"
fi
# A shared library the dynamic loader would find: ldconfig's cache, then the usual driver folders.
find_lib() {
  local found d
  found=$(ldconfig -p 2>/dev/null | awk -v n="$1" '$1 == n {print $NF; exit}')
  if [ -z "$found" ]; then
    for d in ${LD_LIBRARY_PATH//:/ } /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu \
      /usr/local/cuda/lib64; do
      [ -e "$d/$1" ] && { found=$d/$1; break; }
    done
  fi
  echo "$found"
}

device_args=()
[ -z "$device" ] || device_args=(--device "$device")

# Plan: one line per step, fields separated by \x1f: stage, name, outputs (space-separated, relative to
# the output folder; a trailing / marks a folder), then the arguments of voxr.
plan=()
add() {
  local stage=$1 name=$2 outputs=$3
  shift 3
  local line="$stage"$'\x1f'"$name"$'\x1f'"$outputs" a
  for a in "$@"; do line+=$'\x1f'"$a"; done
  plan+=("$line")
}
stage_on() { [[ " ${stages[*]} " == *" $1 "* ]]; }
label() { basename "$1" .json; }

if stage_on render; then
  add render voxelize-default "render/voxelize-default.json" voxelize "${device_args[@]}" \
    --channels occ,count,normal,material --res "$render_res" --report "@OUT@/render/voxelize-default.json" -q
  for size in "${sizes[@]}"; do
    add render "default-$size" "render/default-$size.png render/default-$size.json" render "${device_args[@]}" \
      --size "$size" --shadow-res "$render_res" --res "$render_res" -o "@OUT@/render/default-$size.png" \
      --report "@OUT@/render/default-$size.json" -q
    add render "default-$size-frames" "render/default-$size-frames.png render/default-$size-frames.json" render \
      "${device_args[@]}" --size "$size" --shadow-res "$render_res" --res "$render_res" --frames "$render_frames" \
      --profile -o "@OUT@/render/default-$size-frames.png" --report "@OUT@/render/default-$size-frames.json"
  done
  size=${sizes[${#sizes[@]}-1]} big=render/$(label "$render_big")-${sizes[${#sizes[@]}-1]}
  add render "${big#render/}" "$big.png $big.json" render "$render_big" "${device_args[@]}" --size "$size" \
    --shadow-res "$render_res" --frames "$render_frames" --profile -o "@OUT@/$big.png" --report "@OUT@/$big.json"
fi
if stage_on voxelize; then
  for res in "${vox_res[@]}"; do
    add voxelize "$vox_meshes-$res" "voxelize/$vox_meshes-$res.csv" bench voxelize "${device_args[@]}" \
      --meshes "$vox_meshes" --res "$res" --cases "$vox_cases" --repeat "$vox_repeat" --warmup "$vox_warmup" \
      --fresh "$vox_fresh" --out "@OUT@/voxelize/$vox_meshes-$res.csv"
  done
fi
if stage_on table1; then
  for res in "${t1_res[@]}"; do
    add table1 "res-$res" "table1/res-$res.csv table1/res-$res.md" bench table1 "${device_args[@]}" \
      "${t1_models[@]}" --res "$res" --repeat "$t1_repeat" --warmup "$t1_warmup" --out "@OUT@/table1/res-$res"
  done
fi
if stage_on shadows; then
  for size in "${sizes[@]}"; do
    add shadows "scenes-$size" "shadows-$size/scenes.csv shadows-$size/scenes.md" bench shadows \
      "${device_args[@]}" "${sh_args[@]}" --size "$size" --repeat "$sh_repeat" --warmup "$sh_warmup" \
      --fresh "$sh_fresh" --out "@OUT@/shadows-$size/scenes"
  done
  for size in "${sizes[@]}"; do
    big=$(label "$sh_big_scene")
    add shadows "$big-$size" "shadows-$size/$big.csv shadows-$size/$big.md" bench shadows "${device_args[@]}" \
      --scenes "$sh_big_scene" --methods voxel-center,uniform,filter,opaque --res "$sh_big_res" --size "$size" \
      --repeat "$sh_repeat" --warmup "$sh_warmup" --fresh "$sh_fresh" --out "@OUT@/shadows-$size/$big"
  done
fi
if stage_on refraction; then
  for size in "${sizes[@]}"; do
    for scene in "${rf_scenes[@]}"; do
      s=$(label "$scene")
      add refraction "$s-$size" "refraction-$size/$s.csv refraction-$size/$s.md" bench refraction \
        "${device_args[@]}" --scenes "$scene" "${rf_methods[@]}" --res "$rf_res" --shadow-res "$rf_shadow_res" \
        --size "$size" --repeat "$rf_repeat" --warmup "$rf_warmup" --fresh "$rf_fresh" --out "@OUT@/refraction-$size/$s"
    done
  done
fi
if stage_on animation; then
  for size in "${sizes[@]}"; do
    add animation "scenes-$size" "animation-$size.csv animation-$size.md" bench animation "${device_args[@]}" \
      "${an_scenes[@]}" --frames "$an_frames" --size "$size" --fresh "$an_fresh" --out "@OUT@/animation-$size"
  done
fi

# ---------------------------------------------------------------------------------------------------------
# Checking the plan without running it: the programs answer --help, every flag is in the subcommand's help,
# every scene file exists.

declare -A help_text=()
plan_errors=0
check_plan() {
  local line fields stage name args key a
  for line in "${plan[@]}"; do
    IFS=$'\x1f' read -r -a fields <<<"$line"
    stage=${fields[0]} name=${fields[1]}
    args=("${fields[@]:3}")
    key=${args[0]}
    [ "$key" != bench ] || key="bench ${args[1]}"
    if [ -z "${help_text[$key]+x}" ]; then
      # shellcheck disable=SC2086
      if ! help_text[$key]=$("$voxr" $key --help 2>&1); then
        echo "gpu-bench: \`voxr $key --help\` failed: ${help_text[$key]}" >&2
        plan_errors=$((plan_errors + 1))
        continue
      fi
    fi
    for a in "${args[@]}"; do
      if [[ $a == --* ]] && ! grep -qE -- "(^|[[:space:],])${a}([[:space:],=]|$)" <<<"${help_text[$key]}"; then
        echo "gpu-bench: step $stage/$name: \`voxr $key\` has no option $a" >&2
        plan_errors=$((plan_errors + 1))
      elif [[ $a == data/scenes/* && ! -f $a ]]; then
        echo "gpu-bench: step $stage/$name: scene $a does not exist" >&2
        plan_errors=$((plan_errors + 1))
      fi
    done
  done
}

quote_args() {
  local out="" a
  for a in "$@"; do
    if [[ $a =~ ^[A-Za-z0-9_./,:=+%@-]+$ ]]; then out+=" $a"; else out+=" $(printf '%q' "$a")"; fi
  done
  echo "${out# }"
}

if [ $dry = 1 ]; then
  echo "# gpu-bench plan ($([ $quick = 1 ] && echo quick || echo full)): ${#plan[@]} steps, budget ${budget} s," \
    "voxr = $voxr, output folder = \$OUT"
  prev=""
  for line in "${plan[@]}"; do
    IFS=$'\x1f' read -r -a fields <<<"$line"
    if [ "${fields[0]}" != "$prev" ]; then
      prev=${fields[0]}
      echo "# stage $prev (limit ${limit[$prev]} s)"
    fi
    echo "voxr $(quote_args "${fields[@]:3}")" | sed 's|@OUT@|$OUT|g'
  done
  check_plan
  if [ $plan_errors -gt 0 ]; then
    echo "gpu-bench: the plan has $plan_errors error(s)" >&2
    exit 1
  fi
  echo "# plan checked: every flag is accepted and every scene exists"
  exit 0
fi

# ---------------------------------------------------------------------------------------------------------
# Running.

if [ -z "$out" ]; then
  if [ -n "${OUT:-}" ]; then out=$OUT pack=1; else out=out/gpu-bench-$(date -u +%Y%m%d-%H%M%S); fi
fi
mkdir -p "$out" || { echo "gpu-bench: cannot create $out" >&2; exit 1; }
results_dir=$(cd "$out" && pwd)
out=$results_dir
if [ $pack = 1 ]; then
  scratch=$(mktemp -d "${TMPDIR:-/tmp}/gpu-bench.XXXXXX") || exit 1
  out=$scratch/gpu-bench
fi
mkdir -p "$out/logs"
check_plan
if [ $plan_errors -gt 0 ]; then
  echo "gpu-bench: the plan has $plan_errors error(s); nothing run" >&2
  exit 1
fi

# What the bundle's gpu-env.sh does for one program: register NVIDIA's OpenCL driver when the machine has
# not (in /etc when writable, else through OCL_ICD_VENDORS), and use the bundled OpenCL loader only when
# the machine has none.
if [ $quick = 0 ] && [ ! -e /etc/OpenCL/vendors/nvidia.icd ]; then
  nvlib=$(find_lib libnvidia-opencl.so.1)
  if [ -n "$nvlib" ]; then
    if ! { mkdir -p /etc/OpenCL/vendors 2>/dev/null && echo "$nvlib" >/etc/OpenCL/vendors/nvidia.icd 2>/dev/null; }; then
      mkdir -p "$out/logs/vendors" && echo "$nvlib" >"$out/logs/vendors/nvidia.icd"
      export OCL_ICD_VENDORS="$out/logs/vendors"
    fi
  fi
fi
if [ -d "$vdir/lib-loader" ] && [ -z "$(find_lib libOpenCL.so.1)" ]; then
  export LD_LIBRARY_PATH="$LD_LIBRARY_PATH:$vdir/lib-loader"
fi
# Kernel caches: keep what the caller set (ctest points them into the build tree), else one folder for the
# whole run, so that only the first process compiles.
export VOXR_CACHE_DIR=${VOXR_CACHE_DIR:-${TMPDIR:-/tmp}/voxr-gpu-bench-cache}
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-${TMPDIR:-/tmp}/voxr-gpu-bench-pocl-cache}

now_ms() { date +%s%3N; }
run_start=$(now_ms)
run_end=$((run_start + budget * 1000))
started_utc=$(date -u '+%Y-%m-%d %H:%M:%S UTC')

{
  echo "date: $started_utc"
  echo "host: $(uname -n) ($(uname -sr), $(nproc) cores)"
  echo "command: $argv_text"
  echo "voxr: $voxr"
  [ ! -f "$vdir/BUNDLE.txt" ] || sed 's/^/bundle: /' "$vdir/BUNDLE.txt"
  [ -d "$root/.git" ] || [ -f "$root/.git" ] && echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null)"
  if command -v nvidia-smi >/dev/null; then
    echo "nvidia-smi: $(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>&1 | head -4 | tr '\n' ';')"
  fi
  echo "load average: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
} >"$out/env.txt"
"$voxr" devices >"$out/devices.txt" 2>&1 || true

echo "gpu-bench: ${#plan[@]} steps into $out (budget $budget s; $([ $quick = 1 ] && echo quick || echo full))"

# Checks one output file; prints the reason when it is bad.
check_file() {
  local f=$1
  [ -s "$f" ] || { echo "missing or empty: ${f#"$out"/}"; return 1; }
  case $f in
    *.csv)
      awk '
        function fields(line, out,   i, c, n, q, cur) {
          n = 0; q = 0; cur = ""
          for (i = 1; i <= length(line); i++) {
            c = substr(line, i, 1)
            if (c == "\"") q = !q
            else if (c == "," && !q) { out[++n] = cur; cur = "" }
            else cur = cur c
          }
          out[++n] = cur
          return q ? -1 : n
        }
        { sub(/\r$/, "") }
        NR == 1 { want = fields($0, h); if (want < 2) { print "no CSV header"; bad = 1; exit } next }
        $0 == "" { next }
        {
          n = fields($0, f)
          if (n != want) { printf "line %d has %d fields, the header %d\n", NR, n, want; bad = 1; exit }
          for (i = 1; i <= n; i++) {
            v = tolower(f[i])
            # inf is a PSNR where an image equals its reference; anywhere else it is an error
            if (v ~ /^[-+]?nan$/ || (v ~ /^[-+]?inf(inity)?$/ && tolower(h[i]) !~ /psnr/)) {
              printf "line %d, %s: %s\n", NR, h[i], f[i]; bad = 1; exit
            }
          }
          rows++
        }
        END { if (!bad && rows < 1) { print "no data rows"; bad = 1 } exit bad }' "$f" |
        sed "s|^|${f#"$out"/}: |"
      return "${PIPESTATUS[0]}" ;;
    *.md)
      if grep -n -i -w -m1 -- 'nan' "$f" | sed "s|^|${f#"$out"/}:|" | grep .; then return 1; fi ;;
    *.json) # voxr's JSON writer turns NaN into null
      if grep -n -i -w -m1 -E -- 'nan|null' "$f" | sed "s|^|${f#"$out"/}:|" | grep .; then return 1; fi ;;
  esac
  return 0
}

# index.csv: one row per step.
echo "stage,step,status,seconds,limit_s,outputs,command" >"$out/index.csv"
declare -A stage_end=() stage_dead=()
failures=0
results=()
current_stage=""
for line in "${plan[@]}"; do
  IFS=$'\x1f' read -r -a fields <<<"$line"
  stage=${fields[0]} name=${fields[1]}
  read -r -a outputs <<<"${fields[2]}"
  args=("${fields[@]:3}")
  if [ "$stage" != "$current_stage" ]; then
    current_stage=$stage
    stage_end[$stage]=$(($(now_ms) + ${limit[$stage]} * 1000))
    echo "gpu-bench: stage $stage (limit ${limit[$stage]} s)"
  fi
  args=("${args[@]//@OUT@/$out}")
  cmd="voxr $(quote_args "${args[@]}")"
  cmd=${cmd//$out/\$OUT}
  log="$out/logs/$stage-$name.log"
  deadline=${stage_end[$stage]}
  [ "$run_end" -ge "$deadline" ] || deadline=$run_end
  left=$(((deadline - $(now_ms)) / 1000))
  status="" secs=0
  if [ -n "${stage_dead[$stage]:-}" ]; then
    status="skipped (${stage_dead[$stage]})"
  elif [ "$left" -lt 2 ]; then
    status="skipped (no time left: $([ "$deadline" = "$run_end" ] && echo "run budget" || echo "stage limit"))"
  else
    for o in "${outputs[@]}"; do mkdir -p "$out/$(dirname "$o")"; rm -f "$out/$o"; done
    echo "  $name: $cmd"
    t0=$(now_ms)
    timeout -k 5 "$left" "$voxr" "${args[@]}" >"$log" 2>&1
    rc=$?
    secs=$(awk -v ms=$(($(now_ms) - t0)) 'BEGIN { printf "%.1f", ms / 1000 }')
    if [ $rc = 124 ] || [ $rc = 137 ]; then
      status="timed out after $left s"
      stage_dead[$stage]="an earlier step of the stage timed out"
    elif [ $rc != 0 ]; then
      status="failed (exit $rc): $(grep -v '^$' "$log" | tail -1)"
    else
      bad=""
      for o in "${outputs[@]}"; do
        reason=$(check_file "$out/$o") || bad+="${bad:+; }$reason"
      done
      if [ -n "$bad" ]; then status="bad output: $bad"; else status=ok; fi
    fi
  fi
  [ "$status" = ok ] || failures=$((failures + 1))
  printf '  %s: %s%s\n' "$name" "$status" "$([ "$secs" = 0 ] || echo ", $secs s")"
  if [[ $status == failed* || $status == timed* ]] && [ -s "$log" ]; then tail -5 "$log" | sed 's/^/    | /'; fi
  csv_status=${status//\"/\'}
  printf '%s,%s,"%s",%s,%s,"%s","%s"\n' "$stage" "$name" "$csv_status" "$secs" "${limit[$stage]}" \
    "${fields[2]}" "${cmd//\"/\"\"}" >>"$out/index.csv"
  results+=("$stage|$name|$status|$secs|${fields[2]}|$cmd")
done

# Stages split into steps also get one CSV with every row (the steps' CSVs share a header): TARGET gets the
# CSV outputs of this run's steps whose path starts with PREFIX.
merge() {
  local target=$1 prefix=$2 files=() line f o
  for line in "${plan[@]}"; do
    IFS=$'\x1f' read -r -a f <<<"$line"
    for o in ${f[2]}; do
      [[ $o == "$prefix"*.csv && -s $out/$o ]] && files+=("$out/$o")
    done
  done
  [ ${#files[@]} -gt 0 ] || return 0
  { head -1 "${files[0]}"; for f in "${files[@]}"; do tail -n +2 "$f"; done; } >"$out/$target"
}
merge voxelize.csv voxelize/
merge table1.csv table1/
for size in "${sizes[@]}"; do merge "refraction-$size.csv" "refraction-$size/"; done

finished_utc=$(date -u '+%Y-%m-%d %H:%M:%S UTC')
total=$(awk -v ms=$(($(now_ms) - run_start)) 'BEGIN { printf "%.0f", ms / 1000 }')
device_line=$(grep -h -m1 '^device: ' "$out"/logs/*.log 2>/dev/null | head -1)
{
  echo "# voxr benchmark run ($([ $quick = 1 ] && echo "quick, tiny sizes" || echo "full matrix"))"
  echo
  echo "- ${device_line:-device: (no step printed one)}"
  sed 's/^/- /' "$out/env.txt"
  echo "- finished: $finished_utc, $total s in all (budget $budget s)"
  echo "- result: $([ $failures = 0 ] && echo "every step ok" || echo "$failures step(s) not ok")"
  echo
  echo "OpenCL devices (\`voxr devices\`):"
  echo
  echo '```'
  cat "$out/devices.txt"
  echo '```'
  echo
  echo "| stage | step | status | s | outputs | command |"
  echo "|---|---|---|---:|---|---|"
  for r in "${results[@]}"; do
    IFS='|' read -r stage name status secs outs cmd <<<"$r"
    links=""
    for o in $outs; do links+="${links:+ }[$o]($o)"; done
    echo "| $stage | $name | $status | $secs | $links | \`$cmd\` |"
  done
  echo
  echo "Every command ran in the repository root; \$OUT is this folder. What each printed is in logs/STAGE-STEP.log."
  echo "Merged CSVs: voxelize.csv, table1.csv, refraction-SIZE.csv (the steps' rows under one header)."
} >"$out/index.md"

if [ $pack = 1 ]; then
  cp "$out/index.md" "$out/index.csv" "$results_dir/"
  tar -czf "$results_dir/gpu-bench-results.tar.gz" -C "$scratch" gpu-bench || failures=$((failures + 1))
  # The device tool brings back files of at most 16 MiB: without the images if it must.
  if [ "$(wc -c <"$results_dir/gpu-bench-results.tar.gz")" -gt $((15 * 1024 * 1024)) ]; then
    echo "gpu-bench: the results are over 15 MiB packed: packed again without the PNG images"
    tar -czf "$results_dir/gpu-bench-results.tar.gz" --exclude='*.png' -C "$scratch" gpu-bench || failures=$((failures + 1))
  fi
  rm -rf "$scratch"
  echo "gpu-bench: everything packed into $results_dir/gpu-bench-results.tar.gz"
fi
echo "gpu-bench: $([ $failures = 0 ] && echo "every step ok" || echo "$failures step(s) not ok") in $total s;" \
  "summary in $results_dir/index.md"
[ $failures = 0 ]
