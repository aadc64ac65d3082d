#!/usr/bin/env bash
# Installs every build and run dependency from Debian 12's packages (DESIGN.md, "Dependencies").
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-dev glslang-tools libglm-dev
  libembree-dev libtbb-dev
  libopenimageio-dev openimageio-tools
  libbenchmark-dev libgtest-dev
  libcli11-dev nlohmann-json3-dev libtinyobjloader-dev libmeshoptimizer-dev
  python3-matplotlib
)
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages already installed"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
