#!/usr/bin/env bash
# Installs the Debian packages the build and the tests need, only those missing (root or sudo).
#   scripts/deps.sh          the normal and the sanitizer build (g++: ASan and UBSan come with it)
#                            and every tool a test runs: librsvg2-bin (rsvg-convert) and python3
#                            render and decode the preview picture in tests/preview; unzip and
#                            python3 check the written 3MF packages; python3 runs the meta tests
#                            (scripts/check_*.py); coreutils (timeout, sha256sum) is essential
#   scripts/deps.sh fuzz     also clang and its runtime libraries (libFuzzer), and python3 for
#                            the hostile-scale inputs (fuzz/make_hostile.py)
set -euo pipefail
packages=(g++ cmake make libeigen3-dev libtinyobjloader-dev doctest-dev librsvg2-bin python3 unzip)
if [[ ${1:-} == fuzz ]]; then
  packages+=(clang libclang-rt-14-dev python3)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=(); [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  echo "installing: ${missing[*]}" >&2
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >&2
fi
