#!/usr/bin/env bash
# Installs the Debian packages fit3dof needs, only those that are missing.
# Sourced by tools/run, tools/test and tools/bench.
set -euo pipefail

FIT3DOF_PACKAGES=(
  build-essential cmake
  libceres-dev libeigen3-dev libgflags-dev libgoogle-glog-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev nlohmann-json3-dev libfccp-dev libcli11-dev libboost-dev
  libssl-dev pybind11-dev python3-pybind11 python3-dev
  python3 python3-matplotlib python3-numpy python3-pytest python3-yaml
)

fit3dof_install_deps() {
  local missing=()
  local pkg
  for pkg in "${FIT3DOF_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "fit3dof: installing missing Debian packages: ${missing[*]}" >&2
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    sudo="sudo"
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

# Configures and builds into build/ (Release). Uses every core.
fit3dof_build() {
  local root
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$root/build" -j "$(nproc)"
}
