#!/usr/bin/env bash
# Test: `invasim render` refuses frames it cannot draw faithfully instead of writing an SVG
# with cx="nan" or r="inf" or silently dropping rows: NaN/infinite coordinates and radii, an
# XYZ count line that disagrees with the rows (more or fewer), a plane more than one period
# outside the box on a periodic axis. Each refusal exits 1, names the file, the row and the
# value, and writes nothing; a plane within one period is wrapped and renders. With SNAPS (the
# directory app_write_snapshot writes), copies of its VTP files with an infinite radius and a
# NaN mesh point are refused too.
# Usage: render_invalid_frames.sh INVASIM WORKDIR [SNAPS]
set -euo pipefail
invasim=$1 work=$2 snaps=${3:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work"

fail() {
  echo "FAILED: $1"
  [ -n "${2:-}" ] && cat "$2"
  exit 1
}

# frame FILE COUNT ROW...: an extended XYZ frame of the box [0, 20]^3 (walls in x).
frame() {
  local file=$1 count=$2
  shift 2
  {
    echo "$count"
    echo 'Lattice="20 0 0 0 20 0 0 0 20" Origin="0 0 0" Properties=species:S:1:pos:R:3:radius:R:1 pbc="F T T" Time=25 Step=500'
    printf '%s\n' "$@"
  } > "$file"
}

# refused NAME FILE PLANE EXPECT: render exits 1 with a message matching EXPECT, no picture.
refused() {
  local name=$1 file=$2 plane=$3 expect=$4 status=0
  "$invasim" render "$file" --slice "$plane" -o "$name.svg" > "$name.log" 2>&1 || status=$?
  [ "$status" -eq 1 ] || fail "$name: exit status $status (expected 1)" "$name.log"
  grep -q -- "$expect" "$name.log" || fail "$name: no message matching '$expect'" "$name.log"
  [ ! -e "$name.svg" ] || fail "$name: $name.svg was written" "$name.log"
  echo "render_invalid_frames: $name refused: $(cat "$name.log")"
}

frame nan.xyz 2 "C 2 2 10 0.5" "C nan 4 9.8 0.5"
refused nan_position nan.xyz z=10 \
  "^invasim: error: 'nan.xyz': cell 1 (line 4): position (nan, 4, 9.8) is not finite"
frame inf.xyz 2 "C 2 2 10 0.5" "C 8 4 inf 0.5"
refused inf_position inf.xyz z=10 "'inf.xyz': cell 1 (line 4): position (8, 4, inf) is not finite"
frame inf_radius.xyz 2 "C 2 2 10 inf" "C 8 4 9.8 0.5"
refused inf_radius inf_radius.xyz z=10 "'inf_radius.xyz': cell 0 (line 3): radius inf is not finite"
frame nan_radius.xyz 1 "C 2 2 10 nan"
refused nan_radius nan_radius.xyz z=10 "'nan_radius.xyz': cell 0 (line 3): radius nan is not finite"
frame too_many.xyz 1 "C 2 2 10 0.5" "C 8 4 9.8 0.5" "C 9 9 9.9 0.5"
refused too_many_rows too_many.xyz z=10 \
  "'too_many.xyz': line 1 says 1 particle, but the frame has 3 rows (2 more from line 4)"
frame too_few.xyz 3 "C 2 2 10 0.5" "C 8 4 9.8 0.5"
refused too_few_rows too_few.xyz z=10 \
  "'too_few.xyz': line 1 says 3 particles, but the frame has 2 rows (the file ends after line 4)"
frame good.xyz 2 "C 2 2 10 0.5" "C 8 4 9.8 0.5"
refused far_plane good.xyz z=-1e300 \
  "'good.xyz': slice z = -1e+300 lies outside the box \[0, 20\] by more than one period of the periodic z axis"
refused far_plane_above good.xyz y=40.5 "'good.xyz': slice y = 40.5 lies outside the box \[0, 20\]"
# One period below the box on the periodic z axis: z = -10 is z = 10, which cuts both cells.
"$invasim" render good.xyz --slice z=-10 -o wrapped.svg > wrapped.log 2>&1 ||
  fail "z=-10: render failed" wrapped.log
grep -q "^render: 2 discs, 0 polygons -> wrapped.svg$" wrapped.log || fail "z=-10: wrong counts" wrapped.log
if [ -n "$snaps" ]; then
  mkdir -p spheres meshes  # apart: each file of a frame loads its companions
  sed '/Name="radius"/{n;s/^\( *\)0\.5/\1inf/}' "$snaps/spheres_000000500.vtp" > spheres/spheres_000000500.vtp
  refused vtp_inf_radius spheres/spheres_000000500.vtp z=10 \
    "'spheres/spheres_000000500.vtp': cell 0: radius inf is not finite"
  sed '/Name="Points"/{n;s/^\( *\)[^ ]*/\1nan/}' "$snaps/adipocytes_000000500.vtp" > meshes/adipocytes_000000500.vtp
  refused vtp_nan_point meshes/adipocytes_000000500.vtp z=10 \
    "'meshes/adipocytes_000000500.vtp': adipocyte point 0: position (nan, 6.70130161670408, 10) is not finite"
fi
echo "render_invalid_frames: invalid frames and far planes refused, a plane one period away wrapped"
