#!/bin/sh
# The installed library, used as another program would (ctest: test_install).
#   1. cmake --install of this build tree into a temporary prefix (nothing is built);
#   2. every installed header compiles on its own, and none includes a private header;
#   3. the installed CLI runs: it carries the library (GD_STATIC_CLI: it maps no
#      libgeardyn.so) or finds the installed libgeardyn.so (RPATH $ORIGIN/..), as
#      geardyn-mpi does; it writes an HTML plot with the installed plotly.js
#      (share/geardyn) and a PNG through the installed plugin
#      LIBDIR/geardyn/geardyn-raster.so, also when found on PATH (a located error without it);
#   4. tests/install/consumer.c built with `pkg-config --cflags --libs geardyn` only
#      (shared), then with `pkg-config --static` against libgeardyn.a;
#   5. the same program built by tests/install/cmake_consumer (find_package(geardyn)),
#      against geardyn::geardyn and geardyn::geardyn_static;
# each program loads examples/kumar2011_torsional.yaml, solves the modes and must print
# the project version and a second natural frequency of 122.30 +- 0.01 rad/s.
# Writes only into a mktemp directory (removed on exit) and the build tree's
# install_manifest.txt and geardyn.pc.
# usage (from the source tree): test_install.sh BUILD_DIR CC CMAKE PKG_CONFIG LIBDIR VERSION [SANITIZE_FLAGS]
set -eu
build=$1 cc=$2 cmake=$3 pkgconfig=$4 libdir=$5 version=$6 san=${7:-}
model=examples/kumar2011_torsional.yaml
expect_omega=122.30 tol=0.01
cflags_strict="-std=c11 -Wall -Wextra -Werror -pedantic -Wstrict-prototypes"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' INT TERM
prefix=$tmp/prefix
fail() { echo "test_install: FAIL: $*" >&2; exit 1; }
# runs a command, its output shown only if it fails
quiet() { "$@" >"$tmp/log" 2>&1 || { cat "$tmp/log" >&2; fail "$*"; }; }

# checks a consumer's output: version, then omega2
check_output() { # NAME OUTPUT
    echo "$2" | sed 's/^/  /'
    v=$(echo "$2" | sed -n 's/^version //p')
    w=$(echo "$2" | sed -n 's/^omega2 //p')
    [ "$v" = "$version" ] || fail "$1: version '$v', expected '$version'"
    [ -n "$w" ] || fail "$1: no omega2 in its output"
    awk -v w="$w" -v e="$expect_omega" -v t="$tol" \
        'BEGIN { d = w - e; if (d < 0) d = -d; exit !(d <= t) }' ||
        fail "$1: omega2 $w rad/s, expected $expect_omega +- $tol"
}

# fails unless BINARY (run with the current environment) loads libgeardyn.so from the prefix
check_loads_installed() { # NAME BINARY
    lib=$(ldd "$2" | sed -n 's/^[[:space:]]*libgeardyn\.so[^ ]* => \([^ ]*\) .*/\1/p')
    [ -n "$lib" ] || fail "$1 does not load libgeardyn.so: $(ldd "$2" | grep geardyn || true)"
    [ "$(dirname "$(realpath "$lib")")" = "$(realpath "$prefix/$libdir")" ] ||
        fail "$1 loads $lib, not the installed library"
}

echo "1. cmake --install $build --prefix $prefix"
quiet "$cmake" --install "$build" --prefix "$prefix"
for f in bin/geardyn "$libdir/libgeardyn.so" "$libdir/libgeardyn.so.${version%%.*}" \
         "$libdir/libgeardyn.so.$version" "$libdir/libgeardyn.a" \
         "$libdir/pkgconfig/geardyn.pc" "$libdir/cmake/geardyn/geardynConfig.cmake" \
         "$libdir/cmake/geardyn/geardynConfigVersion.cmake" \
         include/geardyn/geardyn.h include/geardyn/version.h include/geardyn/export.h; do
    [ -e "$prefix/$f" ] || fail "not installed: $f"
done
[ ! -e "$prefix/include/geardyn/version.h.in" ] || fail "version.h.in installed"

export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
pc_cflags=$("$pkgconfig" --cflags geardyn) || fail "pkg-config --cflags geardyn"

echo "2. installed headers: stand-alone, no private includes"
n=0
for h in "$prefix"/include/geardyn/*.h; do
    name=$(basename "$h")
    if grep -n '#include' "$h" | grep -v -e '<' -e '"geardyn/' | grep -q .; then
        fail "$name includes something other than a system or geardyn/ header"
    fi
    ! grep -q '_impl\.h' "$h" || fail "$name includes a private header"
    printf '#include <geardyn/%s>\n#include <geardyn/%s>\ntypedef int not_empty;\n' "$name" "$name" >"$tmp/h.c"
    # shellcheck disable=SC2086
    quiet "$cc" $cflags_strict $pc_cflags -fsyntax-only "$tmp/h.c"
    n=$((n + 1))
done
echo "  $n headers"

echo "3. installed CLI"
# the program carries the library when the build's does (GD_STATIC_CLI)
if ldd "$build/geardyn" | grep -q 'libgeardyn\.so'; then
    (unset LD_LIBRARY_PATH; check_loads_installed "installed CLI" "$prefix/bin/geardyn")
else
    ! (unset LD_LIBRARY_PATH; ldd "$prefix/bin/geardyn") | grep -q geardyn ||
        fail "the installed CLI loads a geardyn library; the build's carries it"
    echo "  bin/geardyn carries the library (no libgeardyn.so mapped)"
fi
if [ -e "$prefix/bin/geardyn-mpi" ]; then
    (unset LD_LIBRARY_PATH; check_loads_installed "installed geardyn-mpi" "$prefix/bin/geardyn-mpi")
fi
out=$(env -u LD_LIBRARY_PATH "$prefix/bin/geardyn" --version)
[ "$out" = "geardyn $version" ] || fail "geardyn --version printed '$out'"
echo "  $out"
# HTML plots inline the installed plotly.js (share/geardyn), found beside the library:
# a marked copy there must be the one in the page
js=$prefix/share/geardyn/plotly.min.js
[ -s "$js" ] || fail "not installed: share/geardyn/plotly.min.js"
cp "$js" "$tmp/plotly.js" && echo '/* the installed copy */' >>"$js"
env -u LD_LIBRARY_PATH -u GEARDYN_PLOTLY_JS "$prefix/bin/geardyn" mesh-stiffness \
    examples/rig2018_pair.yaml --plot "$tmp/k.html" >/dev/null || fail "installed CLI: --plot k.html"
grep -q 'the installed copy' "$tmp/k.html" || fail "the HTML plot did not inline the installed plotly.js"
echo "  --plot k.html inlines $js"
# PNG and PDF: the plugin geardyn-raster.so, installed in LIBDIR/geardyn, is found beside
# the installed library (when this build made it: librsvg and cairo found)
if [ -e "$build/geardyn-raster.so" ]; then
    [ -e "$prefix/$libdir/geardyn/geardyn-raster.so" ] || fail "not installed: $libdir/geardyn/geardyn-raster.so"
    env -u LD_LIBRARY_PATH -u GEARDYN_RASTER_PLUGIN "$prefix/bin/geardyn" modal "$model" \
        --plot "$tmp/m.png" >/dev/null || fail "installed CLI: --plot m.png"
    head -c 8 "$tmp/m.png" | od -An -c | grep -q 'P   N   G' || fail "m.png is not a PNG"
    # run as `geardyn` from PATH (the loader then knows the program by that bare name)
    (cd "$tmp" && env -u LD_LIBRARY_PATH -u GEARDYN_RASTER_PLUGIN PATH="$prefix/bin:$PATH" \
        geardyn modal "$OLDPWD/$model" --plot p.pdf >/dev/null) || fail "geardyn on PATH: --plot p.pdf"
    head -c 5 "$tmp/p.pdf" | grep -q '%PDF-' || fail "p.pdf is not a PDF"
    # and only there: without it the installed CLI says which plugin is missing
    mv "$prefix/$libdir/geardyn/geardyn-raster.so" "$tmp/"
    env -u LD_LIBRARY_PATH -u GEARDYN_RASTER_PLUGIN "$prefix/bin/geardyn" modal "$model" \
        --plot "$tmp/n.png" >/dev/null 2>"$tmp/err" && fail "--plot n.png without the plugin exited 0"
    grep -q "$prefix/$libdir/geardyn/geardyn-raster.so" "$tmp/err" ||
        fail "the missing-plugin error does not name $libdir/geardyn/geardyn-raster.so: $(cat "$tmp/err")"
    [ ! -e "$tmp/n.png" ] || fail "n.png written without the plugin"
    mv "$tmp/geardyn-raster.so" "$prefix/$libdir/geardyn/"
    echo "  --plot m.png (and p.pdf, geardyn on PATH) through $libdir/geardyn/geardyn-raster.so"
fi

echo "4a. pkg-config --cflags --libs geardyn"
flags=$("$pkgconfig" --cflags --libs geardyn)
echo "  cc consumer.c $flags"
# shellcheck disable=SC2086
quiet "$cc" $cflags_strict $san tests/install/consumer.c -o "$tmp/consumer" $flags
readelf -d "$tmp/consumer" | grep -q 'NEEDED.*libgeardyn\.so' || fail "consumer not linked to libgeardyn.so"
out=$(LD_LIBRARY_PATH="$prefix/$libdir" "$tmp/consumer" "$model") || fail "consumer (shared) failed"
(export LD_LIBRARY_PATH="$prefix/$libdir"; check_loads_installed consumer "$tmp/consumer")
check_output "pkg-config shared" "$out"

echo "4b. pkg-config --static --cflags --libs geardyn, with libgeardyn.a"
flags=$("$pkgconfig" --static --cflags --libs geardyn | sed 's/-lgeardyn\b/-l:libgeardyn.a/')
echo "  cc -DGD_STATIC consumer.c $flags"
# shellcheck disable=SC2086
quiet "$cc" $cflags_strict $san -DGD_STATIC tests/install/consumer.c -o "$tmp/consumer_static" $flags
! readelf -d "$tmp/consumer_static" | grep -q 'NEEDED.*libgeardyn' || fail "static consumer needs libgeardyn.so"
out=$("$tmp/consumer_static" "$model") || fail "consumer (static) failed"
check_output "pkg-config static" "$out"

echo "5. find_package(geardyn CONFIG REQUIRED) in tests/install/cmake_consumer"
quiet "$cmake" -S tests/install/cmake_consumer -B "$tmp/cmake_build" \
    -DCMAKE_C_COMPILER="$cc" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF \
    -DCMAKE_C_FLAGS="$san" -DCMAKE_EXE_LINKER_FLAGS="$san" -DGD_EXPECTED_VERSION="$version"
grep -q "^geardyn_DIR:PATH=$prefix/$libdir/cmake/geardyn\$" "$tmp/cmake_build/CMakeCache.txt" ||
    fail "find_package found geardyn elsewhere: $(grep '^geardyn_DIR' "$tmp/cmake_build/CMakeCache.txt")"
quiet "$cmake" --build "$tmp/cmake_build"
[ -x "$tmp/cmake_build/consumer_static" ] || fail "geardyn::geardyn_static not defined by the package"
out=$("$tmp/cmake_build/consumer" "$model") || fail "cmake consumer (geardyn::geardyn) failed"
check_output "find_package geardyn::geardyn" "$out"
check_loads_installed "cmake consumer" "$tmp/cmake_build/consumer"
out=$("$tmp/cmake_build/consumer_static" "$model") || fail "cmake consumer (geardyn::geardyn_static) failed"
check_output "find_package geardyn::geardyn_static" "$out"
echo "test_install: all passed"
