# shellcheck shell=bash
# install_packages PACKAGE...: installs the Debian packages that are missing (apt-get, with
# sudo when not root, without recommends). Sourced by scripts/setup.sh, scripts/sanitize.sh,
# scripts/fuzz.sh and scripts/compare/run_comparison.sh.
install_packages() {
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -gt 0 ] || return 0
  local sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -q
  $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
}
