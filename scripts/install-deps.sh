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
# python3-glad is only needed to regenerate third_party/glad*, never to build. The measurement helpers need two more
# tools, not installed here (neither demo.sh nor test.sh runs them): jq (parameter-guide.sh) and python3
# (bench-ab.sh); `apt-get install jq python3`.

# The viewer compiles Dear ImGui's GLFW and OpenGL 3 backends from the examples libimgui-dev ships under
# /usr/share/doc, which slim images (debian:12-slim) tell dpkg to leave out: a package installed there lacks them.
imgui_backends=/usr/share/doc/libimgui-dev/examples/backends
imgui_backends_present() { [[ -f "$imgui_backends/imgui_impl_glfw.cpp" && -f "$imgui_backends/imgui_impl_opengl3.cpp" ]]; }

missing=()
for package in "${required[@]}"; do
  status="$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)"
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$package")
  fi
done
reinstall=()
if [[ ! " ${missing[*]} " =~ " libimgui-dev " ]] && ! imgui_backends_present; then
  reinstall=(libimgui-dev)  # installed, but without the backends' sources
fi

if ((${#missing[@]} == 0 && ${#reinstall[@]} == 0)); then
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

if [[ -d /etc/dpkg/dpkg.cfg.d ]] && grep -qs 'path-exclude.*/usr/share/doc' /etc/dpkg/dpkg.cfg.d/*; then
  # Let the backends through the image's exclusion of /usr/share/doc (dpkg applies the last matching rule).
  echo "path-include=$imgui_backends/*" | "${as_root[@]}" tee /etc/dpkg/dpkg.cfg.d/zz-obscura-imgui-backends >/dev/null
fi
# A fresh VM's apt-daily may hold the dpkg lock for minutes: wait for it. An image whose lists predate a release
# change (bookworm from stable to oldstable) needs that change accepted.
apt=(env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600)
echo "install-deps: installing ${missing[*]} ${reinstall[*]}"
"${as_root[@]}" "${apt[@]}" update --allow-releaseinfo-change
if ((${#missing[@]} > 0)); then
  "${as_root[@]}" "${apt[@]}" install -y --no-install-recommends "${missing[@]}"
fi
if ((${#reinstall[@]} > 0)) || ! imgui_backends_present; then
  "${as_root[@]}" "${apt[@]}" install -y --no-install-recommends --reinstall libimgui-dev
fi
