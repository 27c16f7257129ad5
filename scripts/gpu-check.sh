#!/usr/bin/env bash
# On a machine with a GPU and its vendor's OpenCL driver: does the GPU compute what the CPU does,
# bit for bit, and how fast? In one go, in minutes:
#   1. builds kdray in build-gpu-check/ (or takes prebuilt programs from --bin) and lists the
#      OpenCL devices; without an OpenCL GPU it prints one line and exits 0;
#   2. runs the traversal and render test programs (kdtree_opencl_tests, render_tests: their
#      device tests take the GPU, as `auto` prefers one, and compare with the CPU bit for bit);
#   3. renders the Cornell box and the Cornell box with the bunny on the GPU, megakernel and
#      wavefront, and with the megakernel on the CPU (PoCL where installed, else --device host, the
#      C++ build of the same kernel code) and compares the films' fixed-point sums exactly
#      (bench/device_film_check);
#   4. traces random rays on the Cornell box, the box with the bunny and bunny_sub2 with kdtrace
#      on both, with the short and the full traversal stack, and compares the hit files byte for
#      byte;
#   5. writes OUT/gpu-check.json and OUT/gpu-check.txt: devices, test results, where and by how
#      much anything differs, and GPU against CPU times (bench/LOG.md, "GPU check"); the
#      programs' own output goes to OUT/log-*.txt.
# Usage: scripts/gpu-check.sh [--bin DIR] [--scenes DIR] [--corpus DIR] [--out DIR]
#   --bin DIR     a folder (searched by name, a build folder will do) holding kdrender, kdtrace,
#                 kdbuild, device_film_check and optionally kdconvert and the test programs
#   --scenes DIR  cornell-box.kdscene, cornell-bunny.kdscene and bunny_sub2.kdscene, already converted
#   --corpus DIR  the test corpus, for converting those scenes (default ../shared/corpus)
#   --out DIR     where the summaries go (default gpu-check)
# Exit status: 0 the GPU agrees with the CPU everywhere (or no GPU: skipped); 1 a difference, a
# failed test or a failure of the script; 2 bad command line.
set -euo pipefail
repo=$(realpath "$(dirname "$0")/..")

# Folders named on the command line are taken from where it was given, then the script works
# from the repository.
bin="" scenes="" corpus=$repo/../shared/corpus out=gpu-check
while (($#)); do
  case "$1" in
    --bin | --scenes | --corpus | --out)
      (($# >= 2)) || { echo "gpu-check: error: $1 needs a folder" >&2; exit 2; }
      declare "${1#--}=$(realpath -m "$2")"
      shift 2
      ;;
    *) echo "gpu-check: error: unknown argument $1 (see the comment at the top of $0)" >&2; exit 2 ;;
  esac
done
out=$(realpath -m "$out")
cd "$repo"

# The OpenCL devices as JSON (kdrender --device list), or nothing where there is no platform.
device_list() { "$1" --device list --json 2>/dev/null || true; }
has_gpu() { grep -q '"gpu": *true' <<<"$1"; }

# Without prebuilt programs, clinfo decides before a build is spent on a machine without a GPU.
if [[ -z $bin ]] && command -v clinfo >/dev/null && ! clinfo --raw 2>/dev/null | grep -q 'CL_DEVICE_TYPE.*GPU'; then
  echo "gpu-check: skipped: no OpenCL GPU device (clinfo)"
  exit 0
fi
if [[ -z $bin ]]; then
  cmake -S . -B build-gpu-check -DCMAKE_BUILD_TYPE=Release -DKDRAY_BUILD_TESTS=ON >/dev/null
  cmake --build build-gpu-check -j"$(nproc)" >/dev/null
  bin=build-gpu-check
fi
bin=$(realpath "$bin")
find_program() { find "$bin" -name "$1" -type f -perm -u+x -print -quit; }
kdrender=$(find_program kdrender) kdtrace=$(find_program kdtrace) kdbuild=$(find_program kdbuild)
film_check=$(find_program device_film_check)
for program in kdrender kdtrace kdbuild film_check; do
  [[ -n ${!program} ]] || { echo "gpu-check: error: $bin: no ${program/film_check/device_film_check}" >&2; exit 1; }
done

devices=$(device_list "$kdrender")
if ! has_gpu "$devices"; then
  echo "gpu-check: skipped: no OpenCL GPU device (kdrender --device list)"
  exit 0
fi
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "$devices" >"$work/devices.json"
# The CPU to compare with: PoCL's device where there is one, else kdray's C++ build of the kernels.
cpu=host
grep -q '"gpu": *false' <<<"$devices" && cpu=cpu
# A program cache of its own unless one is named, so that build times are compile times.
export KDRAY_CACHE_DIR="${KDRAY_CACHE_DIR:-$work/program-cache}"

# 2. The test programs, each under a time limit so that one hung kernel cannot eat the budget.
for tests in kdtree_opencl_tests render_tests; do
  program=$(find_program "$tests")
  if [[ -z $program ]]; then
    echo "{\"program\": \"$tests\", \"missing\": true}" >"$work/tests-$tests.json"
    continue
  fi
  echo "gpu-check: $tests"
  status=0
  timeout 300 "$program" --gtest_brief=1 --gtest_output="json:$work/gtest-$tests.json" >"$out/log-$tests.txt" 2>&1 ||
    status=$?
  echo "{\"program\": \"$tests\", \"exit_status\": $status}" >"$work/tests-$tests.json"
done

# 3 and 4 need the scenes and their trees (built here: bunny_sub2's tree is too large to carry).
if [[ -z $scenes ]]; then
  scenes=$work/scenes
  kdconvert=$(find_program kdconvert)
  mkdir -p "$scenes"
  python3 bench/cornell_bunny.py "$scenes" "$corpus" >/dev/null
  "$kdconvert" samples/cornell-box.obj "$scenes/cornell-box.kdscene" -q
  "$kdconvert" "$scenes/cornell-bunny.obj" "$scenes/cornell-bunny.kdscene" -q
  "$kdconvert" "$corpus/large/bunny_sub2.ply" "$scenes/bunny_sub2.kdscene" -q
fi
for scene in cornell-box cornell-bunny bunny_sub2; do
  "$kdbuild" "$scenes/$scene.kdscene" "$work/$scene.kdtree" -q
done

# Cornell's published camera (samples/Makefile); enough samples and rays that the GPU's times
# are not mostly its launch overhead.
cornell_camera=278,273,-800,278,273,0,39.3077 spp=64 rays=4000000
for scene in cornell-box cornell-bunny; do
  for form in megakernel wavefront; do
    echo "gpu-check: render $scene ($form)"
    flags=(--size 512 --spp "$spp" --camera "$cornell_camera")
    [[ $form == wavefront ]] && flags+=(--wavefront)
    "$film_check" "$scenes/$scene.kdscene" "$work/$scene.kdtree" gpu "$cpu" "${flags[@]}" \
      >>"$work/renders.jsonl" 2>>"$out/log-renders.txt" ||
      echo "{\"scene\": \"$scene\", \"form\": \"$form\", \"failed\": true}" >>"$work/renders.jsonl"
  done
done

for scene in cornell-box cornell-bunny bunny_sub2; do
  for stack in short full; do
    echo "gpu-check: trace $scene ($stack stack)"
    for device in gpu "$cpu"; do
      run=$scene-$stack-$device
      "$kdtrace" "$scenes/$scene.kdscene" "$work/$scene.kdtree" --generate random --count "$rays" --stack "$stack" \
        --device "$device" --hits "$work/$run.hits" --json >"$work/trace-$run.json" 2>>"$out/log-traces.txt" ||
        echo '{"failed": true}' >"$work/trace-$run.json"
    done
  done
done

# 5. One JSON and one text summary.
python3 - "$work" "$out" "$cpu" "$spp" "$rays" <<'EOF'
import glob, json, os, struct, sys

work, out, cpu, spp, rays = sys.argv[1:]
def load(path):
    with open(path) as f:
        return json.load(f)

def hit_differences(a, b):
    # 16-byte hit records (formats/rays.md): t, u, v as float32, then the triangle index.
    if not (os.path.exists(a) and os.path.exists(b)):
        return None
    da, db = open(a, "rb").read(), open(b, "rb").read()
    if da == db:
        return {"differing_hits": 0}
    if len(da) != len(db):
        return {"differing_hits": -1, "note": "hit files differ in length"}
    differing = [i for i in range(0, len(da), 16) if da[i:i + 16] != db[i:i + 16]]
    report = {"differing_hits": len(differing)}
    if differing:
        i = differing[0]
        report["first"] = {"ray": i // 16, "gpu": struct.unpack("<fffI", da[i:i + 16]),
                           cpu: struct.unpack("<fffI", db[i:i + 16])}
    return report

tests = []
for path in sorted(glob.glob(f"{work}/tests-*.json")):
    entry = load(path)
    gtest = f"{work}/gtest-{entry['program']}.json"
    if os.path.exists(gtest):
        results = load(gtest)
        entry.update(tests=results["tests"], failures=results["failures"], seconds=results["time"])
        entry["failed"] = [f"{suite['name']}.{case['name']}: " + case["failures"][0]["failure"].splitlines()[0]
                           for suite in results["testsuites"] for case in suite["testsuite"] if case.get("failures")]
    tests.append(entry)
renders = [json.loads(line) for line in open(f"{work}/renders.jsonl")]
for r in renders:
    r["scene"] = os.path.basename(r["scene"]).removesuffix(".kdscene")
traces = []
for scene in ("cornell-box", "cornell-bunny", "bunny_sub2"):
    for stack in ("short", "full"):
        gpu_run, cpu_run = f"{scene}-{stack}-gpu", f"{scene}-{stack}-{cpu}"
        traces.append({"scene": scene, "stack": stack, "gpu": load(f"{work}/trace-{gpu_run}.json"),
                       "cpu": load(f"{work}/trace-{cpu_run}.json"),
                       "comparison": hit_differences(f"{work}/{gpu_run}.hits", f"{work}/{cpu_run}.hits")})

agree = (all(t.get("exit_status", 0) == 0 for t in tests)
         and all(r.get("bit_exact") for r in renders)
         and all(t["comparison"] and t["comparison"]["differing_hits"] == 0 for t in traces))
summary = {"devices": load(f"{work}/devices.json")["devices"], "cpu_reference": cpu, "tests": tests,
           "renders": renders, "traces": traces, "gpu_agrees_with_cpu": agree}
with open(f"{out}/gpu-check.json", "w") as f:
    json.dump(summary, f, indent=2)

lines = ["devices:"] + [f"  {d['index']}: {d['platform']} / {d['name']} ({'GPU' if d['gpu'] else 'CPU'}, "
                        f"driver {d['driver']})" for d in summary["devices"]]
lines.append(f"CPU reference: {cpu}")
for t in tests:
    if t.get("missing"):
        lines.append(f"tests {t['program']}: not present")
        continue
    lines.append(f"tests {t['program']}: exit {t['exit_status']}, {t.get('tests', '?')} tests, "
                 f"{t.get('failures', '?')} failed, {t.get('seconds', '?')}")
    lines += [f"  FAILED {name}" for name in t.get("failed", [])]
lines.append(f"renders (512x512, {spp} spp; film sums compared exactly; render seconds without the program build):")
for r in renders:
    if r.get("failed"):
        lines.append(f"  {r['scene']} {r['form']}: FAILED (log-renders.txt)")
        continue
    verdict = "bit-exact" if r["bit_exact"] else (
        f"{r['differing_values']} of {r['values']} sums differ, at most {r['max_abs_difference']}, "
        f"first {r['first_difference']}")
    a, b = r["a"], r["b"]
    lines.append(f"  {r['scene']} {r['form']}: {verdict}; GPU {a['render_seconds']:.3f} s "
                 f"(build {a['build_seconds']:.2f} s), {cpu} {b['render_seconds']:.3f} s, "
                 f"GPU {b['render_seconds'] / a['render_seconds']:.1f}x")
lines.append(f"traces ({rays} random rays; hit files compared byte for byte; trace seconds):")
for t in traces:
    g, c, comparison = t["gpu"], t["cpu"], t["comparison"]
    if g.get("failed") or c.get("failed") or comparison is None:
        lines.append(f"  {t['scene']} {t['stack']} stack: FAILED (log-traces.txt)")
        continue
    verdict = "bit-exact" if comparison["differing_hits"] == 0 else f"{comparison['differing_hits']} hits differ, first {comparison.get('first')}"
    lines.append(f"  {t['scene']} {t['stack']} stack: {verdict}; GPU {g['seconds']:.4f} s ({g['mrays_per_s']:.1f} Mrays/s), "
                 f"{cpu} {c['seconds']:.4f} s ({c['mrays_per_s']:.1f} Mrays/s), GPU {c['seconds'] / g['seconds']:.1f}x")
lines.append("GPU agrees with the CPU: " + ("yes" if agree else "NO"))
with open(f"{out}/gpu-check.txt", "w") as f:
    f.write("\n".join(lines) + "\n")
print("\n".join(lines))
sys.exit(0 if agree else 1)
EOF
