#!/usr/bin/env bash
# Which stages of one `optimize` run use one core and which two: perf samples every thread at
# 2 kHz, and bench/optimize/thread_timeline.py prints, per 25 ms, each busy thread's sample count
# (50 is a full core) and its hottest function. Needs perf; a figure, not a test, and only
# meaningful on a quiet machine.
#
# usage: bench/optimize/thread_timeline.sh BINARY MESH [optimize options...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
binary=$(readlink -f "$1")
mesh=$2
shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
perf record -F 2000 -o "$out/perf.data" "$binary" optimize "$mesh" "$@" -o "$out/o.stl" --quiet >/dev/null 2>&1
perf script -i "$out/perf.data" -F tid,time,ip,sym 2>/dev/null |
  sed -E 's/^ *([0-9]+) +([0-9.]+): +[0-9a-f]+ +/\1 \2: x /' >"$out/samples.txt"
/usr/bin/python3 "$here/thread_timeline.py" "$out/samples.txt" 0.025 | cut -c1-220
