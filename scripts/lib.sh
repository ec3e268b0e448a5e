# Shared steps of scripts/demo and scripts/test: install missing Debian packages, build.
# Sourced, not run.

craterkit_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
craterkit_build=${CRATERKIT_BUILD_DIR:-$craterkit_root/build}

craterkit_log() { printf '\033[1m[craterkit]\033[0m %s\n' "$*"; }

# Installs the packages of scripts/debian-packages.txt that are not installed yet.
craterkit_install_deps() {
  local pkg missing=()
  while read -r pkg; do
    [[ -z "$pkg" || "$pkg" == \#* ]] && continue
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$pkg")
  done <"$craterkit_root/scripts/debian-packages.txt"
  if [[ ${#missing[@]} -eq 0 ]]; then
    craterkit_log "Debian packages: all present"
    return 0
  fi
  local sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "need root or sudo to install: ${missing[*]}" >&2; return 1; }
    sudo=(sudo)
  fi
  craterkit_log "installing ${#missing[@]} Debian packages: ${missing[*]}"
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
    "${missing[@]}"
}

# Configures (once) and builds in Release with both cores.
craterkit_build() {
  local jobs
  jobs=$(nproc 2>/dev/null || echo 2)
  if [[ ! -f "$craterkit_build/CMakeCache.txt" ]]; then
    craterkit_log "configuring into $craterkit_build"
    cmake -S "$craterkit_root" -B "$craterkit_build" -DCMAKE_BUILD_TYPE=Release
  fi
  craterkit_log "building with $jobs jobs"
  cmake --build "$craterkit_build" -j "$jobs"
}
