#!/usr/bin/env bash
# Installs every build and run dependency from Debian's packages (docs/design.md, "Dependencies"), by
# release:
#   Debian 12 (bookworm): Mesa's Vulkan drivers come from Debian's bookworm-backports suite: its
#     lavapipe (Mesa 25) has no per-invocation loop cap and has the ray-tracing extensions; Debian
#     12's own Mesa 22.3 caps every shader invocation at 65535 loop iterations. The suite is added
#     in a sources file of its own, only when no configured source already provides it.
#   Debian 13 (trixie): everything from trixie itself (Mesa 25 with LLVM 19, Embree 4); nothing
#     from another suite is installed and the apt configuration is not changed.
# Any other system: one error line naming what is supported. On both releases the tests of the
# loop-cap guard also get Debian 12's own lavapipe, unpacked into .deps/ (fetch_old_lavapipe.sh).
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  libvulkan-dev vulkan-validationlayers vulkan-tools
  glslang-dev glslang-tools libglm-dev
  libembree-dev libtbb-dev
  libopenexr-dev libstb-dev libopenimageio-dev openimageio-tools
  libbenchmark-dev libgtest-dev
  libcli11-dev nlohmann-json3-dev libtinyobjloader-dev libmeshoptimizer-dev libopenmesh-dev
  libassimp-dev assimp-testmodels
  libbenchmark-tools python3-scipy
  python3-matplotlib
  chromium
)
min_mesa_version="25"
backports_sources=/etc/apt/sources.list.d/sdfbench-bookworm-backports.sources

release=""
if [ -r /etc/os-release ]; then release="$(. /etc/os-release && echo "${ID:-}:${VERSION_CODENAME:-}")"; fi
case "$release" in
  debian:bookworm)
    # From bookworm-backports, with libdrm at the version that Mesa 25 needs.
    mesa_packages=(mesa-vulkan-drivers libdrm2 libdrm-amdgpu1)
    mesa_suite=bookworm-backports ;;
  debian:trixie)
    mesa_packages=(mesa-vulkan-drivers)
    mesa_suite=""
    # fetch_old_lavapipe.sh gives Debian 12's driver Debian 12's LLVM 15 (RUNPATH set by patchelf).
    packages+=(patchelf) ;;
  *)
    system="$( (. /etc/os-release 2>/dev/null && echo "${PRETTY_NAME:-}") || true)"
    echo "install_deps: error: sdfbench installs its dependencies on Debian 12 (bookworm) and Debian 13 (trixie)" \
      "only; this system is '${system:-unknown (no /etc/os-release)}' (docs/development.md, \"Supported systems\")" >&2
    exit 1 ;;
esac

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi

installed_version() {
  { dpkg-query -W -f='${Status} ${Version}' "$1" 2>/dev/null || true; } | sed -n 's/^install ok installed //p'
}

backports_configured() {
  grep -rqsE '(^|[[:space:]])bookworm-backports([[:space:]]|$)' /etc/apt/sources.list /etc/apt/sources.list.d/
}

missing=()
for p in "${packages[@]}"; do
  [ -n "$(installed_version "$p")" ] || missing+=("$p")
done
mesa_version="$(installed_version mesa-vulkan-drivers)"
mesa_ok=false
if [ -n "$mesa_version" ] && dpkg --compare-versions "$mesa_version" ge "$min_mesa_version"; then
  mesa_ok=true
fi
old_lavapipe="$(dirname "$0")/fetch_old_lavapipe.sh"
if [ ${#missing[@]} -eq 0 ] && $mesa_ok; then
  echo "install_deps: all ${#packages[@]} packages installed ($release); mesa-vulkan-drivers $mesa_version"
  "$old_lavapipe"
  exit 0
fi

if ! $mesa_ok && [ -n "$mesa_suite" ] && ! backports_configured; then
  echo "install_deps: adding Debian's bookworm-backports suite ($backports_sources)"
  $sudo tee "$backports_sources" >/dev/null <<'SOURCES'
# Added by sdfbench's install_deps.sh: Mesa 25 (lavapipe without the loop cap, ray tracing).
Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SOURCES
fi

echo "install_deps: apt-get update ($release)"
$sudo apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  echo "install_deps: installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if ! $mesa_ok; then
  suite_flags=()
  if [ -n "$mesa_suite" ]; then
    if ! apt-cache policy mesa-vulkan-drivers | grep "$mesa_suite" >/dev/null; then  # not grep -q: under pipefail its early exit can fail the pipe (SIGPIPE)
      echo "install_deps: error: Debian's $mesa_suite suite cannot be reached (apt-get update" \
        "did not list it); sdfbench needs its mesa-vulkan-drivers (>= $min_mesa_version). Check the" \
        "network or mirror for $backports_sources" >&2
      exit 1
    fi
    suite_flags=(-t "$mesa_suite")
  fi
  echo "install_deps: installing ${mesa_packages[*]}${mesa_suite:+ from $mesa_suite}"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${suite_flags[@]}" "${mesa_packages[@]}"
  mesa_version="$(installed_version mesa-vulkan-drivers)"
  if ! dpkg --compare-versions "$mesa_version" ge "$min_mesa_version"; then
    echo "install_deps: error: mesa-vulkan-drivers $mesa_version was installed; sdfbench needs >= $min_mesa_version" >&2
    exit 1
  fi
fi
echo "install_deps: mesa-vulkan-drivers $(installed_version mesa-vulkan-drivers)"
# Debian 12's own Mesa 22.3 lavapipe, unpacked (not installed) for the loop-cap tests.
"$old_lavapipe"
