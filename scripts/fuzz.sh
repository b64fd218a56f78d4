#!/usr/bin/env bash
# Builds the libFuzzer harnesses and the binary (clang, ASan + UBSan, fuzz/README.md) in
# build-fuzz/, then
#  1. runs `offsetopt check` and `inspect` on the hostile-scale inputs of fuzz/make_hostile.py,
#     each under a time cap: exit 0 or 2 with only Error:/Warning: lines, nothing else;
#  2. runs each harness in turn, one process at a time, for SECONDS.
# Any finding (crash, sanitizer report, hang beyond -timeout, memory beyond the budget) fails
# the script; the input is saved in build-fuzz/artifacts/ and the log in build-fuzz/logs/.
#   scripts/fuzz.sh [SECONDS] [HARNESS...]   SECONDS per harness (default 60), every harness by default
#   harnesses: read_obj read_stl read_off read_ply read_3mf load_inspect
#   FUZZ_SKIP_HOSTILE=1 skips step 1.
# The working corpus (build-fuzz/corpus/<harness>) persists between runs; seeds come from
# tests/data/bad, tests/data/accepted, meshes/ and fuzz/corpus/<harness> (committed, minimised).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
[[ $# -gt 0 ]] && shift
harnesses=("$@")
((${#harnesses[@]})) || harnesses=(read_obj read_stl read_off read_ply read_3mf load_inspect)

./scripts/deps.sh fuzz
jobs=$(nproc)
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DOFFSETOPT_SANITIZE=ON -DOFFSETOPT_FUZZ=ON \
  -DOFFSETOPT_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" >/dev/null
targets=(--target offsetopt)
for h in "${harnesses[@]}"; do targets+=(--target "fuzz_$h"); done
cmake --build build-fuzz -j"$jobs" "${targets[@]}"

out=build-fuzz
mkdir -p "$out/artifacts" "$out/logs" "$out/dict"
cat fuzz/dict/*.dict >"$out/dict/all.dict"
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"

failed=()
if [[ -z ${FUZZ_SKIP_HOSTILE:-} ]]; then
  rm -rf "$out/hostile"
  python3 fuzz/make_hostile.py "$out/hostile"
  for f in "$out"/hostile/*; do
    for command in check inspect; do
      start=$SECONDS
      status=0
      nice -n 10 timeout 120 "$out/offsetopt" "$command" "$f" >"$out/logs/hostile.out" 2>"$out/logs/hostile.err" || status=$?
      if [[ $status != 0 && $status != 2 ]] || grep -qvE '^(Error|Warning): ' "$out/logs/hostile.err"; then
        echo "hostile $command $(basename "$f"): FINDING (exit $status after $((SECONDS - start)) s)" >&2
        head -c 3000 "$out/logs/hostile.err" >&2
        failed+=("hostile:$command:$(basename "$f")")
      else
        echo "hostile $command $(basename "$f"): exit $status in $((SECONDS - start)) s"
      fi
    done
  done
fi
for h in "${harnesses[@]}"; do
  case $h in
    read_obj) extensions=(obj); dict=fuzz/dict/obj.dict ;;
    read_stl) extensions=(stl); dict=fuzz/dict/stl.dict ;;
    read_off) extensions=(off); dict=fuzz/dict/off.dict ;;
    read_ply) extensions=(ply); dict=fuzz/dict/ply.dict ;;
    read_3mf) extensions=(3mf); dict=fuzz/dict/3mf.dict ;;
    load_inspect) extensions=(obj stl off ply 3mf); dict=$out/dict/all.dict ;;
    *) echo "unknown harness '$h'" >&2; exit 2 ;;
  esac
  seeds=$out/seeds/$h
  rm -rf "$seeds"
  mkdir -p "$seeds" "$out/corpus/$h"
  for ext in "${extensions[@]}"; do
    for f in tests/data/bad/*."$ext" tests/data/accepted/*."$ext" meshes/*."$ext"; do
      [[ -f $f ]] && cp "$f" "$seeds/$(basename "$(dirname "$f")")_$(basename "$f")"
    done
  done
  [[ -d fuzz/corpus/$h ]] && cp fuzz/corpus/"$h"/* "$seeds/" 2>/dev/null || true
  log=$out/logs/$h.log
  start=$SECONDS
  status=0
  nice -n 10 "$out/fuzz/fuzz_$h" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -max_len=65536 -dict="$dict" -artifact_prefix="$out/artifacts/$h-" -print_final_stats=1 \
    "$out/corpus/$h" "$seeds" >"$log" 2>&1 || status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  units=$(ls "$out/corpus/$h" | wc -l)
  if ((status != 0)); then
    echo "fuzz_$h: FINDING (exit $status) after $((SECONDS - start)) s; log $log" >&2
    grep -E "^(==[0-9]+==ERROR|SUMMARY|fuzz assertion|.*runtime error|artifact_prefix|Test unit written)" "$log" | head -20 >&2 || true
    tail -40 "$log" >&2
    failed+=("$h")
  else
    echo "fuzz_$h: ok, ${execs:-?} executions in $((SECONDS - start)) s, corpus $units inputs"
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]} (inputs in $out/artifacts/)" >&2
  exit 1
fi
