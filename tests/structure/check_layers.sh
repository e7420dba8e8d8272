#!/usr/bin/env bash
# The library's layers (DESIGN.md, docs/architecture.md): data flows one way, model file ->
# model -> system -> analyses -> output, so a module may include only its own headers
# and those of lower layers; two modules of one layer never include each other. Every
# #include "..." under src/ and include/geardyn/ is checked against this table, and the
# CLI may include only public headers. Exits 1 listing every violation.
set -euo pipefail
cd "$(dirname "$0")/../.."

declare -A level=(
    [core]=0
    [linalg]=1 [mesh_stiffness]=1 [signal]=1 [testdata]=1
    [laws]=2 [ema]=2
    [model]=3
    [model_file]=4 [elements]=4
    [system]=5
    [modal]=6 [static]=6
    [condense]=7
    [campbell]=8 [response]=8 [transient]=8
    [periodic]=9 [correlate]=9
    [plot]=10
    [report]=11
    [study]=11
    [api]=12
)
# public header -> module
declare -A header=(
    [error.h]=core [units.h]=core [version.h]=core [export.h]=core
    [testdata.h]=testdata [ema.h]=ema [correlate.h]=correlate
    [sparse.h]=linalg [blas.h]=linalg [mesh_stiffness.h]=mesh_stiffness [spectrum.h]=signal [cycles.h]=signal [rattle.h]=signal
    [laws.h]=laws [law_type.h]=laws [bearing_geometry.h]=laws [reynolds.h]=laws
    [model.h]=model [material.h]=model [builder.h]=model [planetary.h]=model
    [model_file.h]=model_file [bearing_table.h]=model_file [elements.h]=elements
    [system.h]=system
    [modal.h]=modal [static.h]=static
    [condense.h]=condense
    [campbell.h]=campbell [waterfall.h]=campbell [probe.h]=response [frf.h]=response [unbalance.h]=response
    [transient.h]=transient [transient_model.h]=transient
    [periodic.h]=periodic
    [plot.h]=plot [report.h]=report
    [study.h]=study
    [geardyn.h]=api
)

module_of_include() { # "geardyn/x.h" | "module/x_impl.h"
    local inc=$1
    case $inc in
        geardyn/*) echo "${header[${inc#geardyn/}]:-unknown:$inc}" ;;
        */*) echo "${inc%%/*}" ;;
        *) echo "unknown:$inc" ;;
    esac
}

bad=0
check_file() { # file module
    local f=$1 mod=$2 inc target
    while IFS= read -r inc; do
        target=$(module_of_include "$inc")
        if [[ $target == unknown:* ]]; then
            echo "$f: #include \"$inc\": not a known module header (use \"module/x_impl.h\" or \"geardyn/x.h\")"
            bad=1
        elif [[ $target != "$mod" ]] && ((level[$target] >= level[$mod])); then
            echo "$f: #include \"$inc\": $mod (layer ${level[$mod]}) may not include $target (layer ${level[$target]})"
            bad=1
        fi
    done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f")
}

# a module's subfolders (src/periodic/hb/, ...) belong to it
shopt -s nullglob
for f in src/*/*.c src/*/*.h src/*/*/*.c src/*/*/*.h; do
    mod=${f#src/}
    mod=${mod%%/*}
    [[ -n ${level[$mod]+x} ]] || { echo "$f: module '$mod' is not in the layer table"; bad=1; continue; }
    check_file "$f" "$mod"
done
for f in include/geardyn/*.h include/geardyn/*.h.in; do
    [[ -e $f ]] || continue
    h=$(basename "$f" .in)
    mod=${header[$h]:-}
    [[ -n $mod ]] || { echo "$f: public header not in the layer table"; bad=1; continue; }
    check_file "$f" "$mod"
done
# the CLI and the installed-library test use public headers only
for f in cli/*.c cli/*.h; do
    while IFS= read -r inc; do
        case $inc in geardyn/*) ;; *) [[ -e cli/$inc ]] || { echo "$f: #include \"$inc\": the CLI uses public headers only"; bad=1; } ;; esac
    done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f")
done
if ((bad)); then
    echo "layers: violations found"
    exit 1
fi
echo "layers: $(ls src/*/*.[ch] src/*/*/*.[ch] include/geardyn/*.h | wc -l) files, no upward or sideways includes"
