#!/usr/bin/env bash
# Installs what Blueshift needs on Debian 12 (run as root), skipping what is present.
# Sourced by scripts/main.sh and scripts/test.sh; safe to run any number of times.
set -euo pipefail

# Vulkan loader + lavapipe + validation layers; shaderc's static archives (crates/shaderc-link);
# fonts for plots; Xvfb and X11 client libraries for the windowed demo and its tests.
PACKAGES=(
  libvulkan1 libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  libshaderc-dev glslang-dev spirv-tools glslc pkg-config g++ cmake
  fontconfig fonts-dejavu-core libfontconfig1-dev
  xvfb x11-apps libx11-6 libxcursor1 libxrandr2 libxi6 libxkbcommon-x11-0
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: need root to install packages: ${missing[*]}" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if ! command -v cargo >/dev/null; then
  echo "setup: cargo not found. Blueshift needs Rust >= 1.85 (edition 2024) from rustup." >&2
  exit 1
fi

# A persistent target dir outside the clone keeps repeat runs warm (CI clones afresh each time).
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/blueshift/target}"
mkdir -p "$CARGO_TARGET_DIR"
# Silences "XDG_RUNTIME_DIR is invalid" from the Vulkan loader and X11 libraries.
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "${XDG_RUNTIME_DIR}" ]; then
  export XDG_RUNTIME_DIR="$HOME/.cache/blueshift/xdg"
  mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
fi
