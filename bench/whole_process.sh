#!/usr/bin/env bash
# Whole-process speed against the yardstick (issue 19; docs/benchmarks.md "Whole process"):
# generates the inputs (fixed seeds) into OUT, then per input runs, in ROUNDS alternating rounds,
# the yardstick (read with fast_float + CGAL's Delaunay, bench/yardstick/cgal_delaunay.cpp) and
# `constrict reconstruct` (read to written result), single mode and `--topology auto`, and writes
# a Markdown table of the medians, their ratios and the peak memory (per point) to OUT/table.md.
# Usage: bench/whole_process.sh [BUILD_DIR (build-bench)] [OUT (out/bench)] [ROUNDS (3)] [N (1000000)]
# HOSTILE=1 adds the 2D families of docs/benchmarks.md "Hostile 2D families" that once had cliffs:
# a circle with 1 % outliers in its box, a noisy spiral, Cauchy-distributed points, a noisy
# circle with 20 outer clusters (about 5-10 s each at 10^6), and two concentric circles (single
# mode 11 s: a comb between the circles; auto 2 s: two rings).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build-bench}; OUT=${2:-out/bench}; ROUNDS=${3:-3}; N=${4:-1000000}
CLI=$BUILD/cli/constrict; YARD=$BUILD/bench/constrict_yardstick
for x in "$CLI" "$YARD"; do [ -x "$x" ] || { echo "missing $x: run make bench" >&2; exit 1; }; done
mkdir -p "$OUT"
/usr/bin/python3 - "$OUT" "$N" <<'PY'
import math, os, sys
import numpy as np
out, n = sys.argv[1], int(sys.argv[2])
def save(name, p):
    path = os.path.join(out, name)
    if not os.path.exists(path):
        np.savetxt(path, p, fmt="%.17g")
rng = np.random.default_rng(19)
# A smooth closed curve (five petals), one point per spacing along the arc, shuffled.
t = np.sort(rng.random(n)) * 2 * math.pi
r = 1 + 0.3 * np.cos(5 * t)
curve = np.c_[r * np.cos(t), r * np.sin(t)]
save("curve2.xy", curve[rng.permutation(n)])
# The same curve with noise about the spacing, normal to it.
length = 2 * math.pi * 1.25  # about the curve's length
h = length / n
save("noisy2.xy", (curve + rng.normal(scale=h, size=curve.shape))[rng.permutation(n)])
save("uniform2.xy", rng.random((n, 2)))
v = rng.normal(size=(n, 3))
v /= np.linalg.norm(v, axis=1)[:, None]
save("surface3.xyz", v * [2.0, 1.2, 0.8])
# A star-shaped surface that is not convex (lobes and a waist): most points are not on the convex
# hull, so the 3D engine grows the body from the inside (the ellipsoid above is all hull points and
# only carved). About 7.6 Delaunay tetrahedra per point instead of 4.6.
th = np.arctan2(v[:, 1], v[:, 0]); ph = np.arccos(np.clip(v[:, 2], -1, 1))
save("star3.xyz", v * (1 + 0.25 * np.sin(3 * th) * np.sin(ph) ** 3 + 0.15 * np.cos(4 * ph))[:, None])
# A torus (R = 1, r = 0.35) of N/3 uniformly random points (by area: rejection on the tube angle):
# a handle for --topology auto to close, and 17 Delaunay tetrahedra per point (docs/benchmarks.md,
# thirty-fourth session). Its own generator, so the inputs above keep their points.
trng = np.random.default_rng(29)
m, tor = n // 3, []
while sum(len(x) for x in tor) < m:
    k = 2 * m
    u, w, keep = trng.random(k) * 2 * math.pi, trng.random(k) * 2 * math.pi, trng.random(k)
    ok = keep < (1 + 0.35 * np.cos(w)) / 1.35
    u, w = u[ok], w[ok]
    tor.append(np.c_[(1 + 0.35 * np.cos(w)) * np.cos(u), (1 + 0.35 * np.cos(w)) * np.sin(u), 0.35 * np.sin(w)])
save("torus3.xyz", np.vstack(tor)[:m])
if os.environ.get("HOSTILE") == "1":
    rng = np.random.default_rng(23)
    m = n - n // 100
    t = rng.random(m) * 2 * math.pi
    save("outliers2.xy", np.vstack([np.c_[np.cos(t), np.sin(t)], rng.uniform(-1.2, 1.2, (n - m, 2))]))
    u = np.sort(rng.random(n)) * 40 * math.pi
    r = u / (40 * math.pi) * 10 + 1
    save("spiral2.xy", np.c_[r * np.cos(u), r * np.sin(u)] + rng.normal(0, 1e-4, (n, 2)))
    save("cauchy2.xy", rng.standard_cauchy((n, 2)))
    k = n - 20 * 50
    t = rng.random(k) * 2 * math.pi
    ring = np.c_[np.cos(t), np.sin(t)] * (1 + rng.normal(0, 2 * math.pi / k, k))[:, None]
    cl = np.vstack([rng.normal(2 * np.array([math.cos(a), math.sin(a)]), 0.02, (50, 2))
                    for a in np.linspace(0, 2 * math.pi, 20, endpoint=False)])
    save("clusters2.xy", np.vstack([ring, cl]))
    k = 2 * n // 3
    t = rng.random(n) * 2 * math.pi
    save("concentric2.xy", np.c_[np.cos(t), np.sin(t)] * np.where(np.arange(n) < k, 1.0, 0.5)[:, None])
PY
inputs=("curve2.xy 2" "noisy2.xy 2" "uniform2.xy 2" "surface3.xyz 3" "star3.xyz 3" "torus3.xyz 3")
[ "${HOSTILE:-0}" = 1 ] && inputs+=("outliers2.xy 2" "spiral2.xy 2" "cauchy2.xy 2" "clusters2.xy 2" "concentric2.xy 2")
[ -f ../shared/data/3d/igea.xyz ] && inputs+=("../shared/data/3d/igea.xyz 3")
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
table="$OUT/table.md"
{
  echo "| input | points | yardstick s | constrict s | ratio | yardstick with huge pages s | ratio to it | constrict peak MB | bytes/point | --topology auto s | auto ÷ single | auto peak MB |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$table"
for entry in "${inputs[@]}"; do
  set -- $entry; name=$1; dim=$2; in="$OUT/$name"
  [ -f "$in" ] || in=$name
  # 3D results as binary PLY, as issue 19 measures them (ASCII OFF formatting costs ~0.7 s more at 10^6).
  ext=$([ "$dim" = 2 ] && echo idx || echo ply)
  ys=(); hs=(); cs=(); mem=(); as=(); amem=()
  for ((k = 0; k < ROUNDS; ++k)); do
    ys+=("$( { /usr/bin/time -f "%e" "$YARD" "$dim" "$in" >/dev/null; } 2>&1 | tail -1)")
    # The CLI runs with transparent huge pages (cli/main.cpp); the yardstick as given does not:
    # the second column gives it the same pages (docs/benchmarks.md, "Huge pages").
    hs+=("$( { /usr/bin/time -f "%e" env GLIBC_TUNABLES=glibc.malloc.hugetlb=1 "$YARD" "$dim" "$in" >/dev/null; } 2>&1 | tail -1)")
    line=$( { /usr/bin/time -f "%e %M" "$CLI" reconstruct "$in" -o "$OUT/result.$ext" -q >/dev/null; } 2>&1 | tail -1)
    cs+=("${line% *}"); mem+=("${line#* }")
    # The same input with --topology auto (issues 16 and 19: within 1.3x of single mode), 2D
    # written as .rings (one ring or several). A run that fails counts as missing.
    aext=$([ "$dim" = 2 ] && echo rings || echo ply)
    line=$( { /usr/bin/time -f "%e %M %x" "$CLI" reconstruct "$in" -o "$OUT/result_auto.$aext" -q --topology auto >/dev/null; } 2>&1 | tail -1) || true
    set -- $line
    if [ "${3:-1}" = 0 ]; then as+=("$1"); amem+=("$2"); fi
  done
  y=$(printf '%s\n' "${ys[@]}" | median); yh=$(printf '%s\n' "${hs[@]}" | median); c=$(printf '%s\n' "${cs[@]}" | median); m=$(printf '%s\n' "${mem[@]}" | median)
  a=n/a; am=n/a
  if [ ${#as[@]} -gt 0 ]; then a=$(printf '%s\n' "${as[@]}" | median); am=$(printf '%s\n' "${amem[@]}" | median); fi
  pts=$(wc -l < "$in")
  awk -v n="$(basename "$name")" -v p="$pts" -v y="$y" -v yh="$yh" -v c="$c" -v m="$m" -v a="$a" -v am="$am" \
    'BEGIN { printf "| %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %.0f | ", n, p, y, c, c / y, yh, c / yh, m / 1024, m * 1024 / p;
             if (a == "n/a") printf "n/a | n/a | n/a |\n"; else printf "%.2f | %.2f | %.0f |\n", a, a / c, am / 1024 }' >> "$table"
  echo "$(basename "$name"): yardstick $y s, constrict $c s"
done
echo "table: $table"
cat "$table"
