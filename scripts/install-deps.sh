#!/usr/bin/env bash
# Installs every Debian bookworm package fovrt needs to build, test and run headless.
# Nothing is fetched from outside Debian.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
  build-essential cmake ninja-build pkg-config git \
  libembree-dev libtbb-dev embree-tools \
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools \
  glslang-tools glslang-dev spirv-tools \
  libglfw3-dev libopenxr-dev libopenxr-loader1 libglm-dev libopenexr-dev libimath-dev \
  catch2 libtinygltf-dev libtinyobjloader-dev libstb-dev libtomlplusplus-dev libcli11-dev \
  nlohmann-json3-dev libspdlog-dev libfmt-dev libimgui-dev xvfb xauth \
  xdotool x11-apps netpbm openxr-layer-corevalidation chromium python3 \
  python3-torch python3-numpy slurm-wlm munge parallel \
  >/dev/null
