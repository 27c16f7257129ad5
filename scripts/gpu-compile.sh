#!/usr/bin/env bash
# kdray's OpenCL programs compiled for GPUs without a GPU: clang and libclc (Debian's clang-15,
# libclc-15) compile each program for NVIDIA (nvptx64) and AMD (amdgcn) targets with the options
# kdray passes to the driver, every warning an error. This catches what PoCL forgives on a CPU:
# host-only builtins, address-space mistakes, unsupported extensions, stack arrays too large.
# Prints each program's private memory per work-item on each target (its largest kernel).
# Usage: scripts/gpu-compile.sh BUILD_DIR [CORPUS_DIR]
#          every program the sample scenes build (samples/Makefile, samples/gallery.mk), as
#          BUILD_DIR's print_kernel_builds lists them; scenes converted with its kdconvert
#        scripts/gpu-compile.sh --kernel FILE.cl [OPTIONS]
#          one kernel file with these build options
# Exit status: 0 every program compiled on both targets; 1 one did not; 2 bad command line or no
# clang-15/libclc-15.
set -euo pipefail
repo=$(realpath "$(dirname "$0")/..")
clang=clang-15 clc=/usr/lib/clc
command -v "$clang" >/dev/null && [[ -d $clc ]] || {
  echo "gpu-compile: error: needs $clang and libclc-15 ($clc): scripts/install-deps.sh" >&2
  exit 2
}

# Per target: what the driver would otherwise supply. clang does not define __OPENCL_VERSION__
# as the runtimes do; NVIDIA's 64-bit atomics (the film's statistics) are an extension clang
# must be told of; amdgcn without ROCm's device libraries takes libclc's builtins only.
targets=(nvptx64 amdgcn)
target_flags_nvptx64=(-target nvptx64-unknown-nvidiacl -Xclang -cl-ext=+cl_khr_int64_base_atomics
  -Xclang -mlink-builtin-bitcode -Xclang "$clc/nvptx64--nvidiacl.bc")
target_flags_amdgcn=(-target amdgcn-unknown-amdhsa -mcpu=gfx1030 -nogpulib
  -Xclang -mlink-builtin-bitcode -Xclang "$clc/amdgcn--amdhsa.bc")

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Private memory per work-item of the largest kernel in a compiled program: PTX's local depot,
# amdgcn's private segment.
private_bytes() {
  case "$1" in
    nvptx64) grep -o '__local_depot[0-9]*\[[0-9]*\]' "$2" | grep -o '\[[0-9]*' | tr -d '[' ;;
    amdgcn) grep -o 'private_segment_fixed_size: *[0-9]*' "$2" | grep -o '[0-9]*$' ;;
  esac | sort -n | tail -1
}

# Functions a PTX program calls but does not define, but for 64-bit atom_add, which libclc-15
# lacks for nvptx64 and NVIDIA's driver supplies. A plain `inline` function clang does not inline
# has no body of its own in OpenCL C (C99's inline), and a driver that does not inline it either
# cannot link the program: the kernels declare theirs `static inline` (KD_INLINE), and any such
# call fails the stage.
unresolved_functions() {
  if [[ $1 == nvptx64 ]]; then
    awk '/^\.extern \.func/ && $NF !~ /^_Z8atom_add/ {print $NF}' "$2" | tr '\n' ' '
  fi
}

# compile NAME FILE OPTIONS: one program on every target; a line per target; 1 on any diagnostic.
compile() {
  local name=$1 file=$2 options=$3 status=0
  for target in "${targets[@]}"; do
    local flags="target_flags_${target}[@]" asm="$work/program.$target.s" log="$work/log"
    # shellcheck disable=SC2086 # the options are a list of words, as the driver gets them
    if "$clang" -x cl $options -D__OPENCL_VERSION__=120 -Xclang -finclude-default-header -I "$repo/kernels" \
      -O2 -Werror -S "${!flags}" -o "$asm" "$file" 2>"$log" && [[ ! -s $log ]]; then
      printf '%-9s %8s bytes  %s\n' "$target" "$(private_bytes "$target" "$asm")" "$name"
      local calls
      calls=$(unresolved_functions "$target" "$asm")
      if [[ -n $calls ]]; then
        echo "    error: called without a body (plain C99 inline, not inlined): $calls"
        status=1
      fi
    else
      printf '%-9s %8s        %s\n' "$target" FAILED "$name"
      sed 's/^/    /' "$log"
      status=1
    fi
  done
  return $status
}

echo "target    private memory per work-item  program (builds: scenes)"
if [[ ${1:-} == --kernel ]]; then
  (($# >= 2)) || { echo "gpu-compile: error: --kernel needs a file" >&2; exit 2; }
  compile "$(basename "$2")" "$2" "${3:-}"
  exit
fi
(($# >= 1)) || { echo "gpu-compile: error: usage: $0 BUILD_DIR [CORPUS_DIR] | --kernel FILE.cl [OPTIONS]" >&2; exit 2; }
build=$(realpath "$1") corpus=${2:-$repo/../shared/corpus}
kdconvert=$build/tools/kdconvert/kdconvert

# The sample scenes' assets; those written by a script are written first. A missing corpus
# file leaves its scene out, said on stdout (CI has the corpus).
python3 "$repo/bench/cornell_bunny.py" "$work" "$corpus" >/dev/null
python3 "$repo/samples/gltf_scene.py" "$work/textured-scene" >/dev/null
python3 "$repo/samples/bunny_pair.py" "$corpus/bunny/stanford-bunny.obj" "$work/bunny-pair.obj" >/dev/null
assets=("$repo/samples/cornell-box.obj" "$work/cornell-bunny.obj" "$corpus/bunny/stanford-bunny.obj"
  "$corpus/misc/spot.obj" "$work/textured-scene/textured-scene.gltf" "$work/bunny-pair.obj"
  /usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf)
scenes=()
for asset in "${assets[@]}"; do
  if [[ ! -f $asset ]]; then
    echo "gpu-compile: left out (missing): $asset"
    continue
  fi
  scene=$work/$(basename "${asset%.*}").kdscene
  "$kdconvert" "$asset" "$scene" -q
  scenes+=("$scene")
done

status=0
while IFS=$'\t' read -r name entry options; do
  compile "$name" "$repo/kernels/$entry" "$options" || status=1
done < <("$build/tests/gpu_compile/print_kernel_builds" "${scenes[@]}")
exit $status
