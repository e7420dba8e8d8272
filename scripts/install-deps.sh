#!/usr/bin/env bash
# Installs the Debian packages geardyn builds and tests with, if any is missing.
# Safe to run repeatedly: it only calls apt-get when something is absent.
set -euo pipefail
pkgs=(build-essential cmake pkg-config libyaml-dev libcjson-dev liblapacke-dev
      libopenblas-dev libsuitesparse-dev libsundials-dev libfftw3-dev
      valgrind)
pkgs+=(nodejs chromium libxml2-dev librsvg2-dev libcairo2-dev poppler-utils); command -v npm >/dev/null || pkgs+=(npm)  # plots: npm installs plotly.js (package.json), Chromium runs the HTML tests, libxml2 parses the SVG in tests; librsvg + cairo write PNG and PDF plots, poppler-utils (pdfinfo) checks them in tests; the machine's Node.js may bring its own npm
pkgs+=(clang libclang-rt-dev libomp-dev)  # make fuzz: libFuzzer harness (fuzz/fuzz_model.c)
pkgs+=(libhdf5-dev libopenmpi-dev openmpi-bin)  # geardyn study: results.h5, mpirun (geardyn-mpi)
pkgs+=(python3 python3-dev python3-cffi python3-setuptools python3-numpy python3-scipy python3-pandas python3-pytest python3-plotly)  # Python package (result.plot(): plotly) (python/, make python, issue 13)
missing=()
for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
        echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
    fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
