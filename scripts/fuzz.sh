#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan+UBSan, build-fuzz/) and runs each for SECONDS.
# Usage: bash scripts/fuzz.sh SECONDS [TARGET...]   (targets: kdscene kdtree rays exr obj ply)
# Exits non-zero when any target finds a crash, a hang (>10 s per input), a leak or an
# allocation over 2 GB; the input that caused it is saved in build-fuzz/findings/.
# The corpus of each target grows in build-fuzz/corpus/TARGET across runs; the seeds are
# regenerated from valid files (fuzz/seeds and files the tools write) every run.
# The seed files are written by the tools of the build in build/ when it is configured (as
# scripts/test.sh leaves it), else by tools built here; targets run nproc at a time, each on
# one core (libFuzzer is single-threaded), so every target still gets SECONDS of fuzzing.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:?usage: fuzz.sh SECONDS [TARGET...]}"
shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(kdscene kdtree rays exr obj ply)
root="$PWD"
out="$root/build-fuzz"
jobs="$(nproc)"

cmake -S . -B "$out" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DKDRAY_FUZZ=ON -DKDRAY_BUILD_TESTS=OFF -DKDRAY_BUILD_BENCH=OFF >/dev/null
seed_tools=(kdconvert kdbuild kdtrace kdrender)
if [ -f build/CMakeCache.txt ]; then
  # A no-op when build/ is current; otherwise brings the tools up to this source tree.
  cmake --build build -j"$jobs" --target "${seed_tools[@]}"
  tools="$root/build/tools"
else
  cmake --build "$out" -j"$jobs" --target "${seed_tools[@]}"
  tools="$out/tools"
fi
cmake --build "$out" -j"$jobs" --target $(printf 'fuzz_%s ' "${targets[@]}")

# ---- seeds from valid files -------------------------------------------------------------
seeds="$out/seeds"
rm -rf "$seeds"
mkdir -p "$seeds"/{obj,ply,kdscene,kdtree,rays,exr}
cp fuzz/seeds/obj/* samples/cornell-box.obj samples/cornell-box.mtl "$seeds/obj/"
# The corpus where the bench scripts look for it (bench/common.sh): CORPUS, else ../shared/corpus.
odd="${CORPUS:-$root/../shared/corpus}/tinyobjloader-odd"
[ -d "$odd" ] && cp "$odd"/*.obj "$odd"/*.mtl "$seeds/obj/"
cp fuzz/seeds/ply/* "$seeds/ply/"
export ASAN_OPTIONS=detect_leaks=0  # the seeds' tools run PoCL, which allocates for the process lifetime
for source in fuzz/seeds/obj/quad-material.obj fuzz/seeds/ply/triangle-ascii.ply samples/cornell-box.obj; do
  name="$(basename "${source%.*}")"
  "$tools/kdconvert/kdconvert" --quiet "$source" "$seeds/kdscene/$name.kdscene" >/dev/null
  "$tools/kdbuild/kdbuild" --quiet "$seeds/kdscene/$name.kdscene" "$seeds/kdtree/$name.kdtree" >/dev/null
done
"$tools/kdbuild/kdbuild" --quiet --max-depth 3 "$seeds/kdscene/cornell-box.kdscene" "$seeds/kdtree/cornell-shallow.kdtree" >/dev/null
"$tools/kdtrace/kdtrace" "$seeds/kdscene/cornell-box.kdscene" "$seeds/kdtree/cornell-box.kdtree" --generate hard \
  --count 64 --write-rays "$seeds/rays/hard.rays" --hits "$seeds/rays/hard.hits" >/dev/null
"$tools/kdrender/kdrender" "$seeds/kdscene/quad-material.kdscene" "$seeds/kdtree/quad-material.kdtree" --quiet \
  --width 4 --height 3 --spp 2 -o "$seeds/exr/quad.exr"
"$tools/kdrender/kdrender" "$seeds/kdscene/quad-material.kdscene" "$seeds/kdtree/quad-material.kdtree" --quiet \
  --width 2 --height 2 --spp 1 --aov albedo,normal,depth -o "$seeds/exr/quad-aov.exr"
unset ASAN_OPTIONS

# ---- fuzzing ---------------------------------------------------------------------------
declare -A dictionary=([kdscene]=container [kdtree]=container [rays]=rays [exr]=exr [obj]=obj [ply]=ply)
mkdir -p "$out/findings" "$out/logs"
fuzz_target() {  # fuzz_target TARGET: runs it for SECONDS; its exit status says whether it found something
  local target="$1" corpus="$out/corpus/$1"
  mkdir -p "$corpus"
  # Leaks are findings too; OpenImageIO keeps per-process caches, which LSan sees as reachable.
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$out/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -max_len=65536 -dict="fuzz/dict/${dictionary[$target]}.dict" -artifact_prefix="$out/findings/$target-" \
    -print_final_stats=1 "$corpus" "$seeds/$target" >"$out/logs/$target.log" 2>&1
}
failed=()
for ((first = 0; first < ${#targets[@]}; first += jobs)); do
  batch=("${targets[@]:first:jobs}")
  declare -A pid=()
  for target in "${batch[@]}"; do
    echo "fuzz: $target for ${seconds}s"
    fuzz_target "$target" &
    pid[$target]=$!
  done
  for target in "${batch[@]}"; do
    log="$out/logs/$target.log"
    if wait "${pid[$target]}"; then
      executions="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
      echo "fuzz: $target: ${executions:-?} executions, no finding; corpus $(ls "$out/corpus/$target" | wc -l) inputs"
    else
      echo "fuzz: $target: FINDING (log: $log)"
      grep -m3 -E "ERROR|SUMMARY|Test unit written" "$log" || tail -20 "$log"
      failed+=("$target")
    fi
  done
  unset pid
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in: ${failed[*]}"
  exit 1
fi
