# Sourced by the scripts that install Debian packages they need (install-deps.sh, vtk.sh,
# vtk-render.sh, vtk-image-render.sh, scaling.sh, make-image-fixtures.sh):
#   apt_install_missing PKG...   installs those of the packages that are not installed yet, with
#                                apt-get (through sudo when not root), without recommends;
#   vtk_report_setup TARGET      what the VTK report scripts need first (from the repository's
#                                root): rayint's build dependencies (install-deps.sh), VTK 9.1's
#                                Python bindings, xvfb (VTK's OpenGL window needs an X display),
#                                matplotlib (the figures); then build/ (Release) and TARGET built.
apt_install_missing() {
  local missing=() pkg sudo=""
  for pkg in "$@"; do
    dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
  done
  [ ${#missing[@]} -gt 0 ] || return 0
  echo "installing: ${missing[*]}" >&2
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
}

vtk_report_setup() {
  ./scripts/install-deps.sh
  apt_install_missing python3-vtk9 xvfb python3-matplotlib
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >&2
  cmake --build build -j2 --target "$1" >&2
}
