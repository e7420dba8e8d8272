#!/usr/bin/env bash
# What the core links (issue 35 item 1): libgeardyn.so and the geardyn program load only
# what the analyses need (LAPACK/BLAS, SuiteSparse, SUNDIALS, FFTW, the YAML and JSON
# readers, OpenMP) and the C and compiler runtimes. PNG/PDF rendering (librsvg, cairo and
# their ~45 image, font, PDF and GUI libraries) and HDF5 are plugins loaded with dlopen
# on first use (geardyn-raster.so, geardyn-hdf5.so), so none of them may appear here.
# Both the direct dependencies (readelf -d NEEDED) and everything the loader maps (ldd)
# are checked against the allowed list; exits 1 naming each library that is not on it.
# The program carries the library (GD_STATIC_CLI, the default: it maps libc, libm and
# libcjson only) or loads libgeardyn.so. With HDF5_PLUGIN: the plugin links no geardyn
# library and calls back into the program, so every gd_ function it needs must be in
# the program's dynamic symbols (cmake/hdf5_plugin.dynlist) or in libgeardyn.so when the
# program loads it.
# usage: check_linked_libs.sh LIBGEARDYN_SO GEARDYN_PROGRAM [HDF5_PLUGIN]
set -euo pipefail
[ $# -eq 2 ] || [ $# -eq 3 ] || { echo "usage: $0 LIBGEARDYN_SO GEARDYN_PROGRAM [HDF5_PLUGIN]" >&2; exit 2; }
plugin=${3:-}
set -- "$1" "$2"

# base names without the .so version; a sanitizer build adds its runtimes
allowed='linux-vdso ld-linux-x86-64 ld-linux-aarch64 libc libm libdl libpthread librt
libgcc_s libgomp libgfortran libquadmath libstdc++ libasan libubsan liblsan
libgeardyn libopenblas libopenblasp-r0 libblas liblapack liblapacke libtmglib libcblas
libcxsparse libklu libbtf libamd libcolamd libcamd libccolamd libcholmod libsuitesparseconfig
libsundials_cvode libsundials_nvecserial libsundials_sunlinsolspgmr
libfftw3 libfftw3_threads libyaml-0 libcjson'

bad=0
is_allowed() { # soname
    local base=${1%%.so*}
    for a in $allowed; do [ "$base" = "$a" ] && return 0; done
    return 1
}
for f in "$@"; do
    [ -e "$f" ] || { echo "check_linked_libs: $f does not exist"; exit 1; }
    direct=$(readelf -d "$f" | sed -n 's/.*(NEEDED).*\[\(.*\)\].*/\1/p')
    mapped=$(ldd "$f" | awk '{ print $1 }' | sed 's|.*/||')
    nd=0 nm=0 fbad=0
    for lib in $direct; do
        nd=$((nd + 1))
        is_allowed "$lib" || { echo "$f: links $lib (readelf -d NEEDED), which is not on the allowed list"; fbad=1; }
    done
    for lib in $mapped; do
        nm=$((nm + 1))
        is_allowed "$lib" || { echo "$f: loads $lib (ldd), which is not on the allowed list"; fbad=1; }
    done
    ((fbad)) && bad=1 || echo "$(basename "$f"): $nd direct, $nm mapped, all on the allowed list"
done
if [ -n "$plugin" ]; then
    prog=$2
    ldd "$prog" | grep -q 'libgeardyn\.so' && prog=$1 # the program's gd_ come from the library
    needs=$(nm -D --undefined-only "$plugin" | awk '$2 ~ /^gd_/ { print $2 }' | sort)
    has=$(nm -D --defined-only "$prog" | awk '{ print $3 }' | sort)
    missing=$(comm -23 <(echo "$needs") <(echo "$has"))
    nmap=$(ldd "$plugin" | grep -c 'libgeardyn' || true)
    if [ -n "$missing" ] || [ "$nmap" -ne 0 ]; then
        [ -z "$missing" ] || echo "$(basename "$plugin") calls" $missing "which $(basename "$prog") does not export (cmake/hdf5_plugin.dynlist)"
        [ "$nmap" -eq 0 ] || echo "$(basename "$plugin") loads libgeardyn itself: it calls back into the program"
        bad=1
    else
        echo "$(basename "$plugin"): its $(echo "$needs" | wc -w) gd_ functions exported by $(basename "$prog")"
    fi
fi
if ((bad)); then
    echo "linked libraries: image, font, PDF, GUI or other optional libraries belong in a plugin"
    echo "  loaded with dlopen (src/plot/raster.c, cli/study_output.c), not in the core;"
    echo "  a new library the analyses need goes on the allowed list in $0"
    exit 1
fi
