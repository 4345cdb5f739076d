#!/usr/bin/env bash
# The small picture of each view in the README (docs/views/), drawn by `spinfold render`.
# Usage: scripts/view_pictures.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
spinfold="${1:-build}/spinfold"
out=docs/views
mkdir -p "$out"
render() {  # name preset view time [layers]
  "$spinfold" render --scene "$2" --view "$3" --t "$4" --width 320 --height 240 \
    --layers "${5:-surface,grid,body,frame,trail}" --out "$out/$1.png"
}
render sphere spin_vs_geodesic_sphere sphere 2
render stereographic spin_vs_geodesic_sphere disk 2
render disk spin_vs_geodesic_pseudosphere disk 6
render hyperboloid spin_vs_geodesic_pseudosphere hyperboloid 6
render klein spin_vs_geodesic_pseudosphere klein 6
render halfplane spin_vs_geodesic_pseudosphere halfplane 6
render tractricoid spin_vs_geodesic_pseudosphere tractricoid 6
render plane spinning_rigid_plane plane 6
render conformal_sphere spin_vs_geodesic_sphere conformal 2
render conformal_pseudosphere spin_vs_geodesic_pseudosphere conformal 6
render revolution_torus spin_vs_geodesic_torus revolution 12 surface,grid,body,frame,trail,curvature
render revolution_spheroid opposite_spins_spheroid revolution 20
render revolution_bump trapped_spin_bump revolution 20 surface,grid,body,frame,trail,curvature
render chart_torus spin_vs_geodesic_torus chart 16
render revolution_catenoid spin_vs_geodesic_catenoid revolution 12 surface,grid,body,frame,trail,curvature
echo "view_pictures: wrote $(ls "$out" | wc -l) pictures to $out"
