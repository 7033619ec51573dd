#!/usr/bin/env bash
# Installs what symcompress needs to build and test, skipping what is already there.
#   Debian packages: compilers (clang and its libFuzzer for scripts/fuzz.sh), CMake, and the libraries
#   (apt-get; sudo when not root).
#   The peer tools in ../shared/bench (Khronos glTF validator, glTF Transform's decoder, X_ITE, the render
#   check's three.js and puppeteer-core), used by the interoperability tests, when Node.js >= 20 and
#   ../shared are present. Chromium (Debian's) opens the HTML reports in the tests (and, with python3-pil,
#   draws ../shared/bench/render/render_compare.sh); the report's own viewer
#   (viewer/package-lock.json) is installed by CMake into the build folder.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(build-essential clang libclang-rt-14-dev cmake pkg-config libtinygltf-dev libdraco-dev libmeshoptimizer-dev libeigen3-dev
          libpugixml-dev catch2 libcli11-dev nlohmann-json3-dev libtbb-dev zlib1g-dev libpng-dev chromium python3-pil)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""; [[ $(id -u) -eq 0 ]] || sudo="sudo"
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

bench="$here/../shared/bench"
if [[ -d "$bench" ]] && command -v node >/dev/null && command -v npm >/dev/null; then
  major=$(node -p 'process.versions.node.split(".")[0]')
  if ((major >= 20)); then
    for dir in node x3d render; do
      if [[ -f "$bench/$dir/package-lock.json" && ! -d "$bench/$dir/node_modules" ]]; then
        echo "install-deps: npm ci in $bench/$dir"
        # Once more on failure: the registry is sometimes briefly unreachable.
        npm ci --prefix "$bench/$dir" --no-audit --no-fund >/dev/null 2>&1 ||
          { sleep 5; npm ci --prefix "$bench/$dir" --no-audit --no-fund >/dev/null 2>&1; } ||
          echo "install-deps: warning: npm ci in $bench/$dir failed; the interoperability tests will be skipped"
      fi
    done
  else
    echo "install-deps: Node.js $major is older than 20; the interoperability tests will be skipped"
  fi
else
  echo "install-deps: no Node.js or no ../shared/bench; the interoperability tests will be skipped"
fi
