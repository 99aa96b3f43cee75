#!/usr/bin/env bash
# Sets up a Debian 12 machine for StickRep and builds it: installs the Debian packages that
# are missing, configures, and builds into build/ (executables in build/bin): everything (with
# the fuzz targets in build/fuzz and the unit tests under ASan+UBSan in build/asan), or with
# `main` only what the main job runs. Safe to run again: it installs nothing that is present
# and rebuilds incrementally.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools   # Fast DDS 2.9 and its IDL compiler
  libopencv-dev libeigen3-dev libyaml-cpp-dev
  libgtest-dev libgmock-dev libbenchmark-dev libtinyxml2-dev
  iproute2 nftables                                           # the deploy test's two hosts
  libcli11-dev libfmt-dev nlohmann-json3-dev libspdlog-dev
  libsqlite3-dev                                              # recordings (components/bag)
  openssl libssl-dev                                          # DDS Security: make-keys.sh, runtime
  cyclonedds-dev cyclonedds-tools                             # the security test's outside peer
  clang libclang-rt-14-dev                                    # the fuzz targets (libFuzzer)
  python3                                                     # tools/scripts and their tests
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# UDP socket buffers of 4 MB (the processes ask for them; the kernel caps them here): room
# for the fragments of several 250 kB camera frames, which go over UDP also within one host
# (docs/reliability.md, "Supervision"). Only raised, never lowered.
for key in net.core.rmem_max net.core.wmem_max; do
  if [ "$(sysctl -n "$key" 2>/dev/null || echo 0)" -lt 4194304 ]; then
    if [ "$(id -u)" -eq 0 ] && sysctl -q -w "$key=4194304" 2>/dev/null; then
      echo "setup: $key raised to 4194304"
    else
      echo "setup: $key is below 4194304; as root: sysctl -w $key=4194304" >&2
    fi
  fi
done

# Two cores: build with -j2. Generated IDL code is rebuilt only when an .idl file changes.
# build/'s ctest also runs the sanitized unit suite of build/asan, once that is built.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSTICKREP_EXTRA_TEST_DIRS=asan \
  > build.configure.log 2>&1 || { cat build.configure.log; exit 1; }
rm -f build.configure.log
# `main`: only what the main job runs (the processes and stickrep-launch), for a first
# result sooner; `all` (the default): everything, tests and benchmarks included.
case "${1:-all}" in
  main) targets=(--target stickrep-launch stickrep-virtual-robot stickrep-sonar stickrep-camera
                 stickrep-locomotion stickrep-landmark stickrep-localizer stickrep-executive) ;;
  all) targets=() ;;
  *) echo "usage: bash deploy/setup.sh [main|all]" >&2; exit 2 ;;
esac
cmake --build build -j2 "${targets[@]}"
[ "${1:-all}" = all ] || exit 0

# The unit tests again under AddressSanitizer and UBSan, in build/asan (no benchmarks, no
# multi-process tests): tests asan.*, label asan, run by build/'s ctest (docs/reliability.md).
cmake -S . -B build/asan -DCMAKE_BUILD_TYPE=Release -DSTICKREP_SANITIZE=address,undefined \
  -DSTICKREP_BUILD_BENCHMARKS=OFF -DSTICKREP_BUILD_INTEGRATION_TESTS=OFF \
  -DSTICKREP_FUZZ_TESTS=OFF > build.configure.log 2>&1 || { cat build.configure.log; exit 1; }
rm -f build.configure.log
cmake --build build/asan -j2
