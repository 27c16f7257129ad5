# shellcheck shell=bash disable=SC2034  # sourced: the variables are for the scripts that source it
# What the benchmark scripts share. A script in bench/ sources it, after setting BUILD (a build
# folder; default: build/ in the repository):
#   . "$(dirname "$0")/common.sh"
# It sets ROOT (the repository), CORPUS (the CORPUS variable, else ../shared/corpus beside the
# repository), YARDSTICKS (the YARDSTICKS variable, else ../shared/yardsticks: the scripts that
# drive Cycles and Mitsuba), MITSUBA_PYTHON (the variable, else the python of a venv
# ../venv-mitsuba beside the repository, where Mitsuba 3 is installed) and the tools' paths under
# BUILD, and defines the helpers below.
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=$(realpath "${BUILD:-$ROOT/build}")
CORPUS=$(realpath -m "${CORPUS:-$ROOT/../shared/corpus}")
YARDSTICKS=$(realpath -m "${YARDSTICKS:-$ROOT/../shared/yardsticks}")
# -s: a venv's python is a symbolic link to the base interpreter; resolved, it loses the venv.
MITSUBA_PYTHON=$(realpath -ms "${MITSUBA_PYTHON:-$ROOT/../venv-mitsuba/bin/python}")
KDCONVERT=$BUILD/tools/kdconvert/kdconvert
KDBUILD=$BUILD/tools/kdbuild/kdbuild
KDRENDER=$BUILD/tools/kdrender/kdrender
KDTRACE=$BUILD/tools/kdtrace/kdtrace
KDCOMPARE=$BUILD/tools/kdcompare/kdcompare
KDINFO=$BUILD/tools/kdinfo/kdinfo

# readable_by BUILD FILE: whether BUILD's kdinfo reads FILE (a tree kept from a run with another
# format version is not, and is rebuilt).
readable_by() { [[ -f "$2" ]] && "$1/tools/kdinfo/kdinfo" "$2" > /dev/null 2>&1; }

# corpus_file PATH: PATH itself when absolute (a mesh of bench/make_meshes.py, say), else the
# corpus file it names.
corpus_file() { if [[ $1 == /* ]]; then echo "$1"; else echo "$CORPUS/$1"; fi; }

# median: the median of the numbers on stdin, one a line (the mean of the middle two for an even count).
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

# json_field KEY...: a value of the JSON document on stdin (nested keys, outermost first).
json_field() {
  /usr/bin/python3 -c 'import json, sys
value = json.load(sys.stdin)
for key in sys.argv[1:]: value = value[key]
print(value)' "$@"
}

# machine_line: the machine, the time and the load average, which every figure depends on.
machine_line() {
  echo "machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'), L3 $(lscpu | sed -n 's/^L3 cache: *//p')," \
    "$(date -u +%Y-%m-%dT%H:%MZ), load average $(cut -d' ' -f1-3 /proc/loadavg)"
}

# scene_files SOURCE NAME: converts SOURCE (an asset kdconvert reads) to $WORK/NAME.kdscene and
# builds its tree $WORK/NAME.kdtree.
scene_files() {
  "$KDCONVERT" "$1" "$WORK/$2.kdscene" > /dev/null
  "$KDBUILD" "$WORK/$2.kdscene" "$WORK/$2.kdtree" > /dev/null
}
