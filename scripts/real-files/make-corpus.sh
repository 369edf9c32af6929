#!/usr/bin/env bash
# Generates the real-files corpus of issue 27 into OUT (default: a new temporary folder; printed):
# meshes, images and colour maps written by the real tools on this machine, never imitations:
#   gmsh 4.8 (Debian gmsh)           this script: 9 geometries x order 1 (+ 5 at order 2), the
#                                    mesh as gmsh writes it (msh 4.1 ASCII, legacy .vtk: no field)
#                                    and, through gmsh's own views (NewView + ModifyComponents +
#                                    Save View), with the field s as $NodeData in msh 2.2/4.1
#                                    ASCII/binary
#   TetGen 1.5 (Debian tetgen)       this script: PLCs and point sets, -p -q -a -A -o2 -z, with
#                                    and without point attributes (the field)
#   meshio, VTK 9.1 writers          corpus_vtk.py (/usr/bin/python3: python3-meshio,
#                                    python3-vtk9): conversions, every XML encoding/compressor/
#                                    header, legacy ASCII/binary float/double, .pvtu with ghost
#                                    cells, .vts/.vtr, tet10, cell types, images .vti/.pvti/legacy
#   ParaView 5.11 (pvpython, VTK 9.2) corpus_paraview.py: Wavelet/Clip/Tetrahedralize/Append
#                                    Datasets pipelines saved with SaveData, every built-in colour
#                                    map (presets.json) and a few exported by ParaView's exporter
# and then corpus_oracle.py (/usr/bin/python3) writes OUT/manifest.json: for every file how it was
# made (tool, version, options), its family (files of one family hold the same mesh and field),
# and what VTK's (or meshio's, for .msh/.ele) reader reads from it: points, cells by VTK type,
# ghost cells, the field's range. scripts/real-files/count.sh runs rayint on it.
#
#   scripts/real-files/make-corpus.sh [OUT]      (about 1-2 minutes on 2 busy cores)
#
# pvpython: `pvpython` on PATH, else PVROOT (an extracted python3-paraview, see
# scripts/paraview-presets.sh), else /opt/colormaps-pv/root if present; without it the ParaView
# part is skipped with a note (the manifest says so).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:-$(mktemp -d /tmp/rayint-corpus.XXXXXX)}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
for tool in gmsh tetgen /usr/bin/python3; do
  command -v "$tool" >/dev/null || { echo "make-corpus.sh: $tool not found (apt-get install gmsh tetgen python3-vtk9 python3-meshio)" >&2; exit 2; }
done
rm -rf "$out"/gmsh "$out"/tetgen "$out"/meshio "$out"/vtk "$out"/paraview "$out"/colormaps
mkdir -p "$out"/gmsh "$out"/tetgen
tsv="$out/manifest-shell.tsv"   # file, kind, tool, format, family, field, how (tab-separated)
: > "$tsv"
record() { printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$@" >> "$tsv"; }
gmsh_version="gmsh $(gmsh --version 2>&1 | tail -1)"
tetgen_version="TetGen 1.5 (Debian tetgen $(dpkg-query -W -f='${Version}' tetgen 2>/dev/null || echo '?'))"

# ---------------------------------------------------------------- gmsh
# Geometry bodies (.geo, OpenCASCADE or built-in kernel); each gets the field s below.
FIELD_EXPR="0.5+0.3*x-0.2*y+0.4*z"
declare -A GEO
GEO[box]='SetFactory("OpenCASCADE"); Box(1) = {-1,-1,-1,2,2,2}; Mesh.MeshSizeMax = 0.6;
Physical Volume("solid", 7) = {1}; Physical Surface("walls", 3) = {1:6};
Physical Curve("edges", 2) = {1:12}; Physical Point("corners", 1) = {1:8};'
GEO[sphere]='SetFactory("OpenCASCADE"); Sphere(1) = {0,0,0,1}; Mesh.MeshSizeMax = 0.35;
Physical Volume("ball") = {1}; Physical Surface("skin") = {1};'
GEO[torus]='SetFactory("OpenCASCADE"); Torus(1) = {0,0,0,1,0.4}; Mesh.MeshSizeMax = 0.3;'
GEO[tube]='SetFactory("OpenCASCADE"); Cylinder(1) = {0,0,-1,0,0,2,1}; Cylinder(2) = {0,0,-1,0,0,2,0.5};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;}; Mesh.MeshSizeMax = 0.3;
Physical Volume("tube") = {3};'
GEO[twoblocks]='SetFactory("OpenCASCADE"); Box(1) = {0,0,0,1,1,1}; Box(2) = {1,0,0,1,1,1};
v() = BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }; Mesh.MeshSizeMax = 0.3;
Physical Volume("left", 1) = {v(0)}; Physical Volume("right", 2) = {v(1)};'
GEO[lshape]='SetFactory("OpenCASCADE"); Box(1) = {0,0,0,2,2,0.5}; Box(2) = {1,1,-1,2,2,2};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;}; Mesh.MeshSizeMax = 0.25;
Mesh.SaveAll = 1;'
GEO[hex]='SetFactory("OpenCASCADE"); Box(1) = {0,0,0,1,1,1}; Transfinite Curve {:} = 5;
Transfinite Surface {:}; Recombine Surface {:}; Transfinite Volume {1}; Physical Volume("block") = {1};'
GEO[prism]='SetFactory("Built-in"); Mesh.MeshSizeMax = 0.4;
Point(1) = {0,0,0}; Point(2) = {1,0,0}; Point(3) = {0,1,0}; Point(4) = {-1,0,0}; Point(5) = {0,-1,0};
Circle(1) = {2,1,3}; Circle(2) = {3,1,4}; Circle(3) = {4,1,5}; Circle(4) = {5,1,2};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
out[] = Extrude {0,0,0.6} { Surface{1}; Layers{3}; Recombine; }; Physical Volume("disc") = {out[1]};'
GEO[mixed]='SetFactory("OpenCASCADE"); Box(1) = {0,0,0,1,1,1}; Box(2) = {1,0,0,1,1,1}; Coherence;
Mesh.MeshSizeMax = 0.35; Transfinite Curve {:} = 4; Transfinite Surface {1:6}; Recombine Surface {1:6};
Transfinite Volume {1};'
ORDER2="box sphere torus tube hex"

gmsh_family() {  # name order
  local name=$1 order=$2 d="$out/gmsh" base="$1-o$2" fam="gmsh-$1-o$2"
  cat > "$d/$base.geo" <<GEOEOF
// generated by scripts/real-files/make-corpus.sh: $name, element order $order
${GEO[$name]}
Mesh.ElementOrder = $order;
Mesh 3;
Mesh.MshFileVersion = 4.1; Mesh.Binary = 0; Save "$base-mesh-41.msh";
Save "$base-mesh.vtk";
Plugin(NewView).NumComp = 1; Plugin(NewView).Run;
Plugin(ModifyComponents).Expression0 = "$FIELD_EXPR"; Plugin(ModifyComponents).View = 0;
Plugin(ModifyComponents).Run;
View[0].Name = "s";
Mesh.MshFileVersion = 2.2; Mesh.Binary = 0; Save View[0] "$base-22a.msh";
Mesh.MshFileVersion = 2.2; Mesh.Binary = 1; Save View[0] "$base-22b.msh";
Mesh.MshFileVersion = 4.1; Mesh.Binary = 0; Save View[0] "$base-41a.msh";
Mesh.MshFileVersion = 4.1; Mesh.Binary = 1; Save View[0] "$base-41b.msh";
GEOEOF
  (cd "$d" && gmsh -0 "$base.geo" > "$base.log" 2>&1) || { echo "make-corpus.sh: gmsh failed on $base.geo (see $d/$base.log)" >&2; exit 1; }
  rm -f "$d/$base.geo_unrolled"
  local how="gmsh -0 $base.geo (Mesh.ElementOrder=$order; Mesh 3"
  record "gmsh/$base-mesh-41.msh" mesh "$gmsh_version" "msh 4.1 ascii" "$fam" "" "$how; Save: the mesh as written, no field)"
  record "gmsh/$base-mesh.vtk" mesh "$gmsh_version" "vtk legacy ascii (gmsh)" "$fam" "" "$how; Save .vtk: gmsh's legacy VTK export, no field)"
  local v
  for v in 22a:"msh 2.2 ascii" 22b:"msh 2.2 binary" 41a:"msh 4.1 ascii" 41b:"msh 4.1 binary"; do
    record "gmsh/$base-${v%%:*}.msh" mesh "$gmsh_version" "${v#*:}" "$fam" s \
      "$how; NewView + ModifyComponents s=$FIELD_EXPR; Save View[0] with Mesh.MshFileVersion/Binary: mesh + \$NodeData)"
  done
}
for name in box sphere torus tube twoblocks lshape hex prism mixed; do gmsh_family "$name" 1; done
for name in $ORDER2; do gmsh_family "$name" 2; done

# ---------------------------------------------------------------- TetGen
d="$out/tetgen"
# cube [-1,1]^3 as a PLC, point attribute s (the field) at the corners: TetGen interpolates
# attributes linearly at the Steiner points it adds
cat > "$d/cube.poly" <<'POLY'
# the cube [-1,1]^3; point attribute s = 0.5 + 0.3x - 0.2y + 0.4z
8 3 1 0
1 -1 -1 -1 0.0
2 1 -1 -1 0.6
3 -1 1 -1 -0.4
4 1 1 -1 0.2
5 -1 -1 1 0.8
6 1 -1 1 1.4
7 -1 1 1 0.4
8 1 1 1 1.0
6 1
1 0 1
4 1 2 4 3
1 0 2
4 5 6 8 7
1 0 3
4 1 2 6 5
1 0 4
4 3 4 8 7
1 0 5
4 1 3 7 5
1 0 6
4 2 4 8 6
0
0
POLY
# two regions (a box cut by the plane x = 0 into halves, region attributes 1 and 2), no field
cat > "$d/halves.poly" <<'POLY'
# the box [-1,1]x[0,1]x[0,1] cut at x = 0; regions with attributes 1 and 2
12 3 0 1
1 -1 0 0 1
2 0 0 0 1
3 1 0 0 1
4 -1 1 0 1
5 0 1 0 1
6 1 1 0 1
7 -1 0 1 1
8 0 0 1 1
9 1 0 1 1
10 -1 1 1 1
11 0 1 1 1
12 1 1 1 1
11 1
1 0 1
4 1 2 5 4
1 0 1
4 2 3 6 5
1 0 2
4 7 8 11 10
1 0 2
4 8 9 12 11
1 0 3
4 1 2 8 7
1 0 3
4 2 3 9 8
1 0 4
4 4 5 11 10
1 0 4
4 5 6 12 11
1 0 5
4 1 4 10 7
1 0 6
4 3 6 12 9
1 0 7
4 2 5 11 8
0
2
1 -0.5 0.5 0.5 1 0.05
2 0.5 0.5 0.5 2 0.05
POLY
# a point cloud with one attribute (s at each point): TetGen's Delaunay tetrahedralisation
/usr/bin/python3 - "$d/cloud.node" <<'PY'
import random, sys
random.seed(27)
pts = [(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)) for _ in range(300)]
with open(sys.argv[1], "w") as f:
    f.write("# 300 random points in [-1,1]^3 (seed 27), attribute s = 0.5 + 0.3x - 0.2y + 0.4z\n")
    f.write("%d 3 1 0\n" % len(pts))
    for i, (x, y, z) in enumerate(pts, 1):
        f.write("%d %.17g %.17g %.17g %.17g\n" % (i, x, y, z, 0.5 + 0.3 * x - 0.2 * y + 0.4 * z))
PY
tetgen_run() {  # input switches tag field note
  local in=$1 sw=$2 tag=$3 field=$4 note=$5 stem="${1%.*}"
  mkdir -p "$d/$tag"
  cp "$d/$in" "$d/$tag/"
  (cd "$d/$tag" && tetgen -Q $sw "$in" > tetgen.log 2>&1) || { echo "make-corpus.sh: tetgen $sw $in failed" >&2; exit 1; }
  local ele; ele=$(cd "$d/$tag" && ls "$stem".1.ele)
  record "tetgen/$tag/$ele" mesh "$tetgen_version" "tetgen .node/.ele$note" "tetgen-$tag" "$field" "tetgen $sw $in"
}
tetgen_run cube.poly "-p" cube-p s ""
tetgen_run cube.poly "-pq1.4" cube-pq s ""
tetgen_run cube.poly "-pq1.2a0.01" cube-pqa s " (fine)"
tetgen_run cube.poly "-pq1.4a0.1z" cube-pqz s " (zero-based, -z)"
tetgen_run cube.poly "-pq1.4a0.1o2" cube-o2 s " (-o2: 10-node tetrahedra)"
tetgen_run cube.poly "-pq1.4a0.1nf" cube-nf s " (with .neigh/.face)"
tetgen_run cube.poly "-pq1.4a0.1B" cube-B s " (-B: no boundary markers)"
tetgen_run halves.poly "-pq1.4A" halves-A "" " (-A: region attributes, no field)"
tetgen_run halves.poly "-pq1.4Aa" halves-Aa "" " (-Aa: region attributes and volume constraints, no field)"
tetgen_run halves.poly "-pq1.4Ao2" halves-Ao2 "" " (-A -o2, no field)"
tetgen_run cloud.node "" cloud s " (Delaunay of points with an attribute)"
tetgen_run cloud.node "-o2" cloud-o2 s " (Delaunay, -o2)"
tetgen_run cube.poly "-pq1.4a0.1A" cube-A s " (-A on one region: region attribute 0 beside the field)"

# ---------------------------------------------------------------- meshio, VTK 9.1
/usr/bin/python3 "$here/corpus_vtk.py" "$out"

# ---------------------------------------------------------------- ParaView 5.11 (pvpython)
pvpython=""; pvpath=""
if command -v pvpython >/dev/null; then pvpython="$(command -v pvpython)"
elif [ -n "${PVROOT:-}" ]; then pvpython="$PVROOT/usr/bin/pvpython3.11"; pvpath="$PVROOT/usr/lib/python3/dist-packages"
elif [ -x /opt/colormaps-pv/root/usr/bin/pvpython3.11 ]; then
  pvpython=/opt/colormaps-pv/root/usr/bin/pvpython3.11; pvpath=/opt/colormaps-pv/root/usr/lib/python3/dist-packages
fi
if [ -n "$pvpython" ]; then
  home="$(mktemp -d)"  # ParaView keeps settings and imported presets in the user's config folder
  HOME="$home" XDG_CONFIG_HOME="$home" PYTHONPATH="$pvpath" "$pvpython" --force-offscreen-rendering \
    "$here/corpus_paraview.py" "$out" 2> "$out/paraview.log" || { echo "make-corpus.sh: pvpython failed (see $out/paraview.log)" >&2; rm -rf "$home"; exit 1; }
  rm -rf "$home"
else
  echo "make-corpus.sh: pvpython not found: the ParaView part is skipped" >&2
fi

# ---------------------------------------------------------------- manifest with VTK's reading
/usr/bin/python3 "$here/corpus_oracle.py" "$out"
echo "$out"
