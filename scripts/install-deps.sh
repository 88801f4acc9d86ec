#!/usr/bin/env bash
# Installs the Debian 12 packages needed to build and test Obscura, non-interactively. Idempotent:
# asks dpkg first and touches apt only when something is missing. Uses sudo when not run as root.
set -euo pipefail

required=(
  cmake make g++ pkg-config
  libegl-dev libgles-dev libopengl-dev   # EGL headless contexts (glvnd)
  libosmesa6-dev libgl1-mesa-dri         # OSMesa backend, llvmpipe software rendering
  libglm-dev libstb-dev                  # demo scene matrices, PNG writing
  libtinyobjloader-dev                   # OBJ scenes (samples/common/scene_library)
  libembree-dev                          # the geometry truth: rays against the scene's triangles (samples/common)
  glmark2-data                           # the "bunny" scene's model (optional at run time)
  libgtest-dev                           # test suite
  libglew-dev libepoxy-dev               # tests that act as a host using GLEW / libepoxy
  libglfw3-dev libimgui-dev              # obscura-viewer (window, Dear ImGui and its backend sources)
  xvfb xauth                             # the viewer's tests run it in a virtual X server
  clang libclang-rt-14-dev               # the libFuzzer targets (tests/fuzz); libclang-rt-14-dev holds libFuzzer's
                                         # runtime, only a recommendation of clang (skipped by --no-install-recommends)
)
# python3-glad is only needed to regenerate third_party/glad*, never to build.

missing=()
for package in "${required[@]}"; do
  status="$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)"
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$package")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#required[@]} packages present"
  exit 0
fi

as_root=()
if [[ "$(id -u)" -ne 0 ]]; then
  if ! command -v sudo >/dev/null 2>&1; then
    echo "install-deps: missing ${missing[*]}; run as root or install sudo" >&2
    exit 1
  fi
  as_root=(sudo)
fi

echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
