#!/usr/bin/env bash
# A/B timing of two or more tyndall binaries in one run (e.g. an old commit's build and this one):
# `tyndall render` runs alternating between the variants, the order flipped every round, so load
# on a shared machine falls on all alike. Prints, per variant, the median over the rounds of
# wall seconds per pass (the render's own "N s" figure: the pass loop only, no start-up or EXR
# writing) and CPU seconds (user + sys of the whole process, start-up included), and each
# variant's median ratio against the first.
#
#   scripts/bench-ab.sh ROUNDS PASSES "NAME=BINARY ARGS..." "NAME=BINARY ARGS..." [...]
#
# Example (docs/performance.md, "Comparing two builds"):
#   scripts/bench-ab.sh 4 10 \
#     "old=OLD/build/app/tyndall render --size 512x512 --radius 0.0353553 --radius-offset 1000" \
#     "new=build/app/tyndall render --size 512x512 --radius 0.0353553 --radius-offset 1000"
# Every run gets --passes PASSES --threads 2 --gpu off -o a scratch EXR appended.
set -euo pipefail
if [ $# -lt 4 ]; then
    echo "usage: $0 ROUNDS PASSES \"NAME=BINARY ARGS...\" \"NAME=BINARY ARGS...\" [...]" >&2
    exit 2
fi
rounds=$1 passes=$2
shift 2
variants=("$@")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=${#variants[@]}
for ((r = 0; r < rounds; ++r)); do
    for ((k = 0; k < n; ++k)); do
        i=$(( r % 2 == 0 ? k : n - 1 - k ))  # flip the order every round
        name=${variants[$i]%%=*}
        cmd=${variants[$i]#*=}
        out=$(/usr/bin/time -f "TIME %U %S" $cmd --passes "$passes" --threads 2 --gpu off -o "$tmp/x.exr" 2>&1) || {
            echo "$name failed: $out" >&2
            exit 1
        }
        wall=$(sed -n 's/.* passes, .* beams, \([0-9.]*\) s (.*/\1/p' <<<"$out")
        cpu=$(awk '/^TIME/ {print $2 + $3}' <<<"$out")
        printf '%s %s %s\n' "$i" "$wall" "$cpu" >>"$tmp/results"
        printf 'round %d  %-12s wall %7.3f s/pass  CPU %7.2f s  (load %s)\n' "$((r + 1))" "$name" \
            "$(awk -v w="$wall" -v p="$passes" 'BEGIN {print w / p}')" "$cpu" "$(cut -d' ' -f1 /proc/loadavg)"
    done
done
python3 - "$tmp/results" "$passes" "${variants[@]}" <<'EOF'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
passes = int(sys.argv[2])
names = [v.split('=', 1)[0] for v in sys.argv[3:]]
by = {i: [(float(w) / passes, float(c)) for k, w, c in rows if int(k) == i] for i in range(len(names))}
rounds = len(by[0])
print(f"median of {rounds} rounds ({passes} passes each)")
for i, name in enumerate(names):
    wall = statistics.median(w for w, _ in by[i])
    cpu = statistics.median(c for _, c in by[i])
    # ratio per round (variant 0 over this one: > 1 means this one is faster), then the median
    rw = statistics.median(by[0][r][0] / by[i][r][0] for r in range(rounds))
    rc = statistics.median(by[0][r][1] / by[i][r][1] for r in range(rounds))
    print(f"  {name:12s} wall {wall:7.3f} s/pass  CPU {cpu:7.2f} s   {names[0]}/{name}: wall {rw:.2f}x  CPU {rc:.2f}x")
EOF
