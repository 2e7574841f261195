#!/usr/bin/env bash
# Runs constrict on the bundled examples and writes results and pictures to OUT.
# Usage: scripts/demo.sh PATH/TO/constrict OUT
set -euo pipefail
CLI=${1:?constrict binary}
OUT=${2:-out}
EX=examples/data
mkdir -p "$OUT"
run() { echo "+ constrict $*"; "$CLI" "$@"; }

# Reconstruction, 2D: a simple polygon through all points (SVG: polygon solid, Delaunay graph
# dashed, stuck points circled, fallback edges orange), plus GeoJSON and a JSON report.
for f in flower greedy_lock nonhamiltonian9 rectangle_point; do
  run reconstruct "$EX/2d/$f.xy" -o "$OUT/${f}_polygon.svg" --report "$OUT/${f}_polygon.json"
done
run reconstruct "$EX/2d/flower.xy" -o "$OUT/flower_polygon.geojson" --quiet

# Reconstruction, 3D: closed genus-0 surfaces through all points (PLY/OFF) and the tetrahedral
# body (VTK, opens in ParaView).
run reconstruct "$EX/3d/candlestick.xyz" -o "$OUT/candlestick_surface.ply" --body "$OUT/candlestick_body.vtk" \
    --report "$OUT/candlestick_surface.json"
run reconstruct "$EX/3d/ellipsoid.xyz" -o "$OUT/ellipsoid_surface.off"
run reconstruct "$EX/3d/tetra_interior.xyz" -o "$OUT/tetra_interior_surface.obj"

# The γ-graph family on a 2D curve sample: Delaunay, Gabriel, a β-skeleton, the convex hull and a
# γ0 < 0 graph with crossing edges (pictures as SVG, values as CSV).
for preset in delaunay gabriel hull beta-circle=1.5; do
  name=${preset//=/}
  run graph "$EX/2d/flower.xy" --preset "$preset" -o "$OUT/flower_${name}.svg" --quiet
done
run graph "$EX/2d/flower.xy" --gamma -0.1,-0.1 -o "$OUT/flower_gamma-0.1.svg"
run graph "$EX/2d/flower.xy" --interval -1,1,0,1 -o "$OUT/flower_delaunay.csv" --report "$OUT/flower_delaunay.json"
run graph "$EX/2d/nonhamiltonian9.xy" --interval -1,1,-0.2,1 -o "$OUT/nonhamiltonian9_gamma-0.2.svg"

# 3D: γ([-1,1],[0,1]) (Delaunay faces) and the Gabriel-like γ(0,0) of two closed surfaces.
run graph "$EX/3d/candlestick.xyz" --preset delaunay -o "$OUT/candlestick_delaunay.ply" --report "$OUT/candlestick_delaunay.json"
run graph "$EX/3d/candlestick.xyz" --preset gabriel -o "$OUT/candlestick_gabriel.off"
run graph "$EX/3d/ellipsoid.xyz" --preset hull -o "$OUT/ellipsoid_hull.obj"

# Pictures (docs/rendering.md): 2D PNG/SVG, 3D PNG (views sheet with wireframe), constriction stage
# sheets (2D and 3D, paper Figure 7), a 2D animation as SVG frames, and a comparison report.
run render "$EX/2d/nonhamiltonian9.xy" -o "$OUT/nonhamiltonian9.png"
run render "$EX/2d/flower.xy" -o "$OUT/flower_stages.png" --stages auto --columns 5 --size 1600x320
run render "$EX/2d/flower.xy" -o "$OUT/flower_final.svg" --animate "$OUT/flower_animation"
run reconstruct "$EX/3d/candlestick.xyz" -o "$OUT/candlestick_surface.off" --render "$OUT/candlestick.png" --quiet
run render "$OUT/candlestick_surface.off" -o "$OUT/candlestick_views.png" --views 4 --wireframe --columns 4 --size 1600x400
run render "$EX/3d/candlestick.xyz" -o "$OUT/candlestick_stages.png" --stages auto --columns 5 --size 1600x320
run compare "$OUT/candlestick_surface.ply" "$OUT/candlestick_surface.off" --report "$OUT/candlestick_compare.json"

echo "demo: results in $OUT/"
ls -1 "$OUT"
