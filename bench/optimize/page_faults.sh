#!/usr/bin/env bash
# The six demo goals (bench/optimize/demo_goals.sh): page faults, system and user seconds, peak
# memory and wall clock of one run each, for one or two binaries (two threads). Page faults are
# what the heap's set-up (src/cli/process_heap.h) cuts; on a virtual machine each costs several
# microseconds of system time. A figure, not a test: the load is printed beside it.
#
# usage: bench/optimize/page_faults.sh BINARY [REFERENCE_BINARY]
set -euo pipefail
[[ $# -ge 1 ]] || { echo "usage: bench/optimize/page_faults.sh BINARY [REFERENCE_BINARY]" >&2; exit 2; }
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/bench/optimize/demo_goals.sh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "machine: $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg); THP: $(cat /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null || echo unknown)"
printf '%-10s %-28s %8s %7s %7s %8s %7s\n' goal binary faults "sys s" "user s" "peak MB" "wall s"
for entry in "${demo_goals[@]}"; do
  IFS='|' read -r name _ _ <<<"$entry"
  demo_goal_args "$name" "$root/meshes"
  for binary in "$@"; do
    /usr/bin/python3 - "$(readlink -f "$binary")" "$out/o.stl" "${args[@]}" <<'PY' | sed "s|^|$(printf '%-10s ' "$name")|"
import resource, subprocess, sys, time
binary, output, args = sys.argv[1], sys.argv[2], sys.argv[3:]
start = time.monotonic()
subprocess.run([binary, "optimize", *args, "-o", output, "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
wall = time.monotonic() - start
u = resource.getrusage(resource.RUSAGE_CHILDREN)
name = binary if len(binary) <= 28 else "..." + binary[-25:]
print(f"{name:28s} {u.ru_minflt + u.ru_majflt:8d} {u.ru_stime:7.3f} {u.ru_utime:7.3f} {u.ru_maxrss / 1024:8.1f} {wall:7.3f}")
PY
  done
done
