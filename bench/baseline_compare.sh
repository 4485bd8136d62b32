#!/bin/sh
# Equal-time error of two builds in one run (docs/performance.md, "Today against the 2026-12-02
# defaults"): each scene with BASE's tyndall_quality and NEW's, one after the other, against the same
# cached references, so that both see the same references (and the same noise taken off) and the
# same machine. Budgets are process CPU seconds, so a loaded machine costs both alike; still the two
# alternate, the order flipping from scene to scene and round to round, and each round takes the
# next seeds (round r: seeds 1 + r*K ... K + r*K), so R rounds are R*K independent seeds a row.
#
# Usage: bench/baseline_compare.sh [options] BASE_QUALITY NEW_QUALITY REFERENCE_DIR [-- NEW_OPTION...]
#   BASE_QUALITY, NEW_QUALITY  the two builds' bench/tyndall_quality
#   REFERENCE_DIR              the reference cache both read (<scene>-<W>x<H>-<spp>spp.exr); a missing
#                              reference is first rendered by NEW alone, before any timed row
#   --scene FILE               a bench scene (tyndall_quality --scene), repeatable
#   --library-scene FILE       a library scene (tyndall_quality --library: made index-matched for the
#                              path tracer, named <scene>-no-specular), repeatable
#   --rounds R                 default 1
#   --seeds K                  default 3
#   --cpu-seconds S            default 7.3
#   --size WxH                 default 64x64
#   --reference-spp N          default 4096
#   --threads T                default 2
#   --log DIR                  keep every run's output there (default: a temporary folder, removed)
#   -- NEW_OPTION...           more options for NEW only (e.g. --no-switch-rows, --scattered-beam-rows 0.05)
# Both get --no-legacy where their --help lists it. Prints every run's rows as they come, then per
# scene BASE's "DEFAULTS (--TIME)" row, each of NEW's rows (passes, RMSE over all seeds, RMSE without
# the brightest 1% of the reference, bias) and the ratio of NEW's defaults' RMSE to BASE's.
set -eu
usage() {
    sed -n '9,26p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}
rounds=1 seeds=3 cpu=7.3 size=64x64 spp=4096 threads=2 log=
scenes=
while [ $# -gt 0 ]; do
    case "$1" in
        --scene) scenes="$scenes box:$2"; shift 2 ;;
        --library-scene) scenes="$scenes lib:$2"; shift 2 ;;
        --rounds) rounds=$2; shift 2 ;;
        --seeds) seeds=$2; shift 2 ;;
        --cpu-seconds) cpu=$2; shift 2 ;;
        --size) size=$2; shift 2 ;;
        --reference-spp) spp=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        --log) log=$2; shift 2 ;;
        -h | --help) usage ;;
        -*) echo "$0: unknown option $1" >&2; usage ;;
        *) break ;;
    esac
done
[ $# -ge 3 ] || usage
base=$1 new=$2 refs=$3
shift 3
if [ $# -gt 0 ]; then
    [ "$1" = -- ] || usage
    shift
fi
newExtra="$*"
[ -n "$scenes" ] || { echo "$0: no --scene or --library-scene" >&2; exit 2; }
for b in "$base" "$new"; do [ -x "$b" ] || { echo "$0: $b: not an executable" >&2; exit 2; }; done
mkdir -p "$refs"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -n "$log" ] || log="$tmp/log"
mkdir -p "$log"
legacy() { if "$1" --help | grep -q -- --no-legacy; then echo --no-legacy; fi; }
baseLegacy=$(legacy "$base")
newLegacy=$(legacy "$new")

# The options that pick one scene: a library scene goes through a folder of its own holding it and
# whatever else its folder holds (textures), not the other scene files.
sceneArgs() {
    kind=${1%%:*} file=${1#*:}
    case "$file" in /*) ;; *) file="$PWD/$file" ;; esac
    [ -f "$file" ] || { echo "$0: $file: no such scene" >&2; exit 2; }
    if [ "$kind" = box ]; then
        echo "--scene $file"
    else
        dir="$tmp/lib-$(basename "$file" .json)"
        if [ ! -d "$dir" ]; then
            mkdir -p "$dir"
            for e in "$(dirname "$file")"/*; do
                case "$e" in *.json) ;; *) ln -s "$e" "$dir/" ;; esac
            done
            ln -s "$file" "$dir/"
        fi
        echo "--library $dir"
    fi
}

common="--size $size --threads $threads --reference-spp $spp --reference-dir $refs"
echo "baseline_compare: $(date -u '+%Y-%m-%d %H:%M UTC'), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "  base: $base"
echo "  new:  $new $*"
# Missing references: NEW renders them (one seed, no budget to speak of) before anything is timed.
for s in $scenes; do
    # shellcheck disable=SC2046,SC2086
    "$new" $common $(sceneArgs "$s") --cpu-seconds 0.01 --seeds 1 $newLegacy | grep 'reference .* rendered' || true
done

run() {  # run WHICH ROUND SCENE
    if [ "$1" = base ]; then bin=$base extra=$baseLegacy; else bin=$new extra="$newLegacy $newExtra"; fi
    out="$log/$1-round$2-$(basename "${3#*:}" .json).txt"
    # shellcheck disable=SC2046,SC2086
    "$bin" $common $(sceneArgs "$3") --cpu-seconds "$cpu" --seeds "$seeds" --seed $((1 + $2 * seeds)) $extra >"$out"
    if grep -q 'reference .* rendered' "$out"; then
        echo "$0: $1 rendered a reference: its scene or reference differs from NEW's ($out)" >&2
        exit 1
    fi
    grep -v '^quality\|^  scene\|LEGACY' "$out" | sed "s/^/  $1 round $2:/" | cut -c1-150
}

r=0
i=0
while [ $r -lt "$rounds" ]; do
    for s in $scenes; do
        if [ $(((r + i) % 2)) -eq 0 ]; then
            run new $r "$s"
            run base $r "$s"
        else
            run base $r "$s"
            run new $r "$s"
        fi
        i=$((i + 1))
    done
    r=$((r + 1))
done
echo "load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u '+%H:%M UTC')"

# The rows over the rounds: passes and bias as means, the RMSEs as root mean squares (each round's
# figure is already one over its K seeds).
for s in $scenes; do
    stem=$(basename "${s#*:}" .json)
    ls "$log"/base-round*-"$stem".txt "$log"/new-round*-"$stem".txt
done | while read -r f; do
    who=$(basename "$f" | cut -d- -f1)
    sed -n 's/ *(radius.*//p' "$f" | grep -v LEGACY | awk -v who="$who" '{
        n = NF; label = $2; for (k = 3; k <= n - 6; ++k) label = label " " $k
        print $1 "\t" who ": " label "\t" $(n-5) "\t" $(n-3) "\t" $(n-2) "\t" $(n-1) }'
done | tr -d '%' | awk -F'\t' '
    { key = $1 "\t" $2; if (!(key in cnt)) order[++nk] = key
      cnt[key]++; passes[key] += $3; e2[key] += $4 * $4; t2[key] += $5 * $5; bias[key] += $6 }
    END {
        printf "\n%-30s %-26s %7s %8s %9s %9s %8s\n", "scene", "row", "passes", "RMSE", "(-1% top)", "bias", "new/base"
        for (k = 1; k <= nk; ++k) { split(order[k], p, "\t"); if (!(p[1] in seen)) { seen[p[1]] = 1; scene[++ns] = p[1] } }
        for (j = 1; j <= ns; ++j) for (k = 1; k <= nk; ++k) {
            s = scene[j]
            split(order[k], p, "\t"); if (p[1] != s) continue
            key = order[k]; c = cnt[key]; rmse = sqrt(e2[key] / c)
            if (p[2] == "base: DEFAULTS (--TIME)") baseRmse[s] = rmse
            line[s] = line[s] sprintf("%-30s %-26s %7.0f %7.2f%% %8.2f%% %+8.2f%%", s, p[2], passes[key] / c, rmse,
                                      sqrt(t2[key] / c), bias[key] / c)
            if (p[2] == "new: DEFAULTS (--TIME)") line[s] = line[s] "@RATIO@"
            line[s] = line[s] "\n"
        }
        for (j = 1; j <= ns; ++j) {
            s = scene[j]
            # No ratio where the error of BASE is below the noise of the reference (0.00%).
            ratio = (s in baseRmse) && baseRmse[s] > 0 ? sprintf(" %8.2f", sqrt(e2[s "\tnew: DEFAULTS (--TIME)"] / cnt[s "\tnew: DEFAULTS (--TIME)"]) / baseRmse[s]) : "        -"
            sub(/@RATIO@/, ratio, line[s]); printf "%s", line[s]
        }
    }'
