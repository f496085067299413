#!/bin/sh
# Install or check the Debian packages stiction needs.
#   tools/deps.sh check    exit 0 when every package is installed, else list the missing ones
#   tools/deps.sh install  apt-get install the missing ones (idempotent)
set -u
PKGS="build-essential pkg-config libfftw3-dev libgsl-dev libhdf5-dev libsuitesparse-dev \
libopenblas-dev libcmocka-dev libinih-dev gnuplot-nox libpng-dev hdf5-tools \
libopenmpi-dev openmpi-bin"

missing() {
    for p in $PKGS; do
        s=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)
        case "$s" in *"ok installed"*) ;; *) printf '%s ' "$p" ;; esac
    done
}

case "${1:-check}" in
check)
    m=$(missing)
    if [ -n "$m" ]; then
        echo "stiction: missing Debian packages: $m" >&2
        echo "stiction: install them with 'make deps' (runs apt-get install)" >&2
        exit 1
    fi
    ;;
install)
    m=$(missing)
    if [ -z "$m" ]; then
        echo "deps: all packages present"
        exit 0
    fi
    echo "deps: installing $m"
    SUDO=
    if [ "$(id -u)" -ne 0 ]; then
        if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
            echo "deps: not root and no sudo; run as root: apt-get install $m" >&2; exit 1
        fi
    fi
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -q || exit 1
    # shellcheck disable=SC2086
    $SUDO apt-get install -y -q --no-install-recommends $m || exit 1
    ;;
*)
    echo "usage: tools/deps.sh check|install" >&2; exit 2 ;;
esac
