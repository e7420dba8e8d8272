#!/usr/bin/env bash
# The shared library exports exactly the public API: every symbol it exports is declared
# GD_API in include/geardyn/, and every GD_API declaration is exported (a definition in a
# file that does not see its declaration would be hidden). usage: check_exports.sh LIB.so
set -euo pipefail
cd "$(dirname "$0")/../.."
lib=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Not ours, made by the toolchain: a sanitizer build's __odr_asan.* / __asan_* symbols,
# the fuzzer coverage sections' __start_/__stop___sancov_*, and clang's OpenMP critical
# lock (.gomp_critical_user_*) and ifunc resolvers of multiversioned static kernels
# (NAME.resolver: the kernels themselves stay hidden)
nm -D --defined-only "$lib" | awk '{print $3}' |
    grep -v '^__odr_asan\.\|^__asan\|^__ubsan\|^__start___sancov\|^__stop___sancov' |
    grep -v '^\.gomp_critical_user_\|\.resolver$' | sort -u > "$tmp/exported"
# declarations may continue on the next lines (a list of objects): join each GD_API
# declaration up to its ';'
awk '/^GD_API/ {d = ""; on = 1} on {d = d " " $0} on && /;/ {print d; on = 0}' \
    include/geardyn/*.h include/geardyn/version.h.in |
    sed 's/([^)]*)*//g' | grep -o 'gd_[a-z0-9_]*' | sort -u > "$tmp/names"
# keep the declared names (types such as gd_status also match; drop what is not a symbol)
comm -12 "$tmp/names" "$tmp/exported" > "$tmp/declared_and_exported"
missing=$(comm -23 "$tmp/names" "$tmp/exported" | grep -v -x -f <(grep -ho 'typedef[^;]*\bgd_[a-z0-9_]*' include/geardyn/*.h | grep -o 'gd_[a-z0-9_]*$' | sort -u; grep -ho '\b\(struct\|enum\) gd_[a-z0-9_]*' include/geardyn/*.h | grep -o 'gd_[a-z0-9_]*' | sort -u) || true)
extra=$(comm -13 "$tmp/names" "$tmp/exported")
bad=0
unmarked=$(grep -n '^[a-z][a-z0-9_ ]*[ *]gd_[a-z0-9_]*(' include/geardyn/*.h | grep -v ':typedef' || true)
if [ -n "$unmarked" ]; then echo "public declarations without GD_API:"; echo "$unmarked"; bad=1; fi
if [ -n "$extra" ]; then echo "exported but not declared GD_API in include/geardyn:"; echo "$extra"; bad=1; fi
if [ -n "$missing" ]; then echo "declared GD_API but not exported:"; echo "$missing"; bad=1; fi
[ $bad -eq 0 ] || exit 1
echo "exports: $(wc -l < "$tmp/exported") symbols, all declared GD_API, every declaration exported"
