#!/usr/bin/env bash
# Installs the Debian 12 packages vmass needs to build, test and run. Idempotent: packages that
# are already installed are skipped, and apt is not touched at all when nothing is missing.
# Run as root (or through sudo).
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git clang-format clang-tidy
  # libFuzzer and the sanitizer runtimes for clang-14 (the `fuzz` preset, scripts/fuzz.sh)
  clang-14 libclang-rt-14-dev
  # libraries
  libeigen3-dev libceres-dev libyaml-cpp-dev libcli11-dev libspdlog-dev libsystemd-dev
  libboost-dev libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev
  # zlib: the BLF reader inflates the log containers (src/runtime/blf_reader.cpp)
  zlib1g-dev
  # LCM: library, tools (lcm-gen, lcm-logger), Java bindings for lcm-spy
  liblcm-dev liblcm-bin liblcm-java libglib2.0-dev default-jdk-headless libjchart2d-java
  # plotting (tools/vmass-plot) and Python test oracles
  python3 python3-matplotlib python3-venv python3-yaml
  # man pages (help2man from --help) and the .debs (CPack runs dpkg-shlibdeps, dpkg-deb; the
  # package test runs lintian on them)
  help2man dpkg-dev lintian
  # compiler cache: a fresh clone compiles only what no earlier build compiled (CMakeLists.txt)
  ccache
  # network namespaces and SocketCAN user space for integration tests
  iproute2 can-utils util-linux
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
