#!/usr/bin/env bash
# Cases per second of a parameter study (issue 12): [Chen1998] Fig. 4 (Chen 1998 gear
# pair, six frequencies over k_m/k_a, 200 log-spaced points) by `geardyn study`, against
# the floor measured in the same run: a shell loop that runs the CLI once per point,
# (a) with --set and (b) editing a copy of the YAML with sed, as users did before.
# Then a simulated large study (random design, 20000 cases, four shards run one after
# the other, merged) for the output volume and merge time quoted in docs/studies.md.
# Prints figures only. usage: bench/bench_study.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=$(cd "${1:-build}" && pwd)
G="$B/geardyn"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
# CPU seconds (user + sys) of a command and its children: on a machine shared with
# other jobs, wall time measures the neighbours as much as geardyn
cpu() { /usr/bin/time -f "%U %S" -o "$tmp/cpu" "$@"; awk '{ printf "%.3f", $1 + $2 }' "$tmp/cpu"; }
rate() { echo "$1 / ($3 - $2)" | bc -l | xargs printf "%.1f"; }
export OPENBLAS_NUM_THREADS=1

N=200
# the mesh stiffness of the study's 200 ratios: k_a * 0.1 * 10^(4 k / 199), k_a = 5.683e6
stiff=$(awk -v n=$N 'BEGIN { for (k = 0; k < n; k++) printf "%.17g\n", 5.683e6 * 0.1 * 10^(4 * k / (n - 1)) }')

echo "Fig. 4 of [Chen1998]: $N cases, modal (undamped) of the 6-DOF gear pair"
cat > "$tmp/loop.sh" <<LEOF
for k in $(echo $stiff); do
    "$G" modal examples/chen1998_gear_pair.yaml --undamped --set "meshes.mesh.stiffness=\$k" > /dev/null
done
LEOF
t0=$(now)
loop_cpu=$(cpu bash "$tmp/loop.sh")
t1=$(now)
loop_set=$(rate $N "$t0" "$t1")
echo "  shell loop, geardyn modal --set per point:  $loop_set cases/s, $loop_cpu CPU s"
t0=$(now)
for k in $stiff; do
    sed "s|^    stiffness: 34.098 MN/m.*|    stiffness: $k|" examples/chen1998_gear_pair.yaml > "$tmp/edited.yaml"
    "$G" modal "$tmp/edited.yaml" --undamped > /dev/null
done
t1=$(now)
loop_sed=$(rate $N "$t0" "$t1")
echo "  shell loop, sed-edited YAML per point:      $loop_sed cases/s"

# the study: median of 5 runs (a single ~0.1 s run is at the mercy of the machine's load)
for threads in 1 2; do
    times=()
    cpus=()
    for rep in 1 2 3 4 5; do
        rm -rf "$tmp/s$threads"
        t0=$(now)
        c=$(cpu "$G" study examples/studies/chen1998_mesh_stiffness.yaml --out "$tmp/s$threads" \
            --threads $threads --quiet 2> /dev/null)
        t1=$(now)
        times+=("$(echo "$t1 - $t0" | bc -l)")
        cpus+=("$c")
    done
    med=$(printf "%s\n" "${times[@]}" | sort -g | sed -n 3p)
    # CPU: the mean of the 5 (time counts in 10 ms steps)
    medc=$(printf "%s\n" "${cpus[@]}" | awk '{ t += $1 } END { printf "%.3f", t / NR }')
    r=$(rate $N 0 "$med")
    echo "  geardyn study --threads $threads (end to end, median of 5): $r cases/s" \
         "= $(echo "$r / $loop_set" | bc -l | xargs printf "%.0f")x the --set loop (wall);" \
         "$medc CPU s = $(echo "$loop_cpu / $medc" | bc -l | xargs printf "%.0f")x less CPU"
done
cmp -s "$tmp/s1/results.csv" "$tmp/s2/results.csv" && echo "  1 and 2 threads: identical results.csv"

# the study itself grows: 20000 cases show the per-case cost without start-up
cat > "$tmp/big.yaml" <<YEOF
model: $PWD/examples/chen1998_gear_pair.yaml
analysis: {type: modal, kind: undamped}
design: random
samples: 20000
seed: 3
parameters:
  - {name: km_over_ka, path: meshes.mesh.stiffness, scale: 5.683e6, unit: N/m,
     range: {from: 0.1, to: 1000, spacing: log}}
  - {name: ka, path: bearings.support_a.k, range: {from: 2e6, to: 2e7, spacing: log}}
outputs: ["omega_n[1:6]"]
YEOF
echo
echo "Simulated large study: 20000 random cases (2 parameters, 6 outputs), 4 shards"
t0=$(now)
for i in 0 1 2 3; do
    "$G" study "$tmp/big.yaml" --out "$tmp/big" --shard $i/4 --threads 2 --quiet 2> /dev/null
done
t1=$(now)
echo "  4 shards one after the other, 2 threads:    $(rate 20000 "$t0" "$t1") cases/s"
t2=$(now)
"$G" study "$tmp/big.yaml" --merge "$tmp/big" 2> /dev/null
t3=$(now)
echo "  merge of the 4 shards: $(echo "$t3 - $t2" | bc -l | xargs printf "%.2f") s"
csv=$(stat -c %s "$tmp/big/results.csv")
h5=$(stat -c %s "$tmp/big/results.h5")
jr=$(stat -c %s "$tmp/big/shard-0-of-4/journal.csv")
echo "  results.csv $csv bytes ($(echo "$csv / 20000" | bc) B/case)," \
     "results.h5 $h5 bytes ($(echo "$h5 / 20000" | bc) B/case), one shard's journal $jr bytes"
if command -v mpirun > /dev/null && [ -x "$B/geardyn-mpi" ]; then
    t0=$(now)
    mpirun --allow-run-as-root --oversubscribe -n 3 -x OMP_NUM_THREADS=1 -x OPENBLAS_NUM_THREADS=1 \
        "$G" study "$tmp/big.yaml" --out "$tmp/bigmpi" --quiet > /dev/null 2>&1
    t1=$(now)
    echo "  mpirun -n 3 (rank 0 hands out, 2 workers): $(rate 20000 "$t0" "$t1") cases/s"
    cmp -s "$tmp/big/results.csv" "$tmp/bigmpi/results.csv" && echo "  MPI and merged shards: identical results.csv"
fi
