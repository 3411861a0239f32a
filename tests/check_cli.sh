#!/bin/bash
# The proxima command: every subcommand on shipped models, its errors and
# exit codes. Usage: check_cli.sh PROXIMA MODELS_DIR [MAKE_ASSEMBLY]
# (MAKE_ASSEMBLY: tests/make_assembly.c, for `proxima check`).
set -u
B=$1
M=$2
A=${3:-}
P=$M/puma560/rtb_puma560_description/meshes
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail=0
pass=0
# expect RC PATTERN -- command...: the exit code and a pattern of the output
expect() {
  local rc=$1 pat=$2
  shift 3
  local out
  out=$("$@" 2>&1)
  local got=$?
  if [ "$got" != "$rc" ] || ! grep -qE -- "$pat" <<<"$out"; then
    echo "check_cli: FAILED: $* (exit $got, wanted $rc; wanted /$pat/):" >&2
    echo "$out" | head -5 >&2
    fail=$((fail + 1))
  else
    pass=$((pass + 1))
  fi
}
expect 0 "proxima info FILE" -- "$B" --help
expect 2 "usage" -- "$B"
expect 0 "^proxima [0-9]+\.[0-9]+\.[0-9]+" -- "$B" --version
expect 0 "triangles: +12248" -- "$B" info "$P/puma560_link3.dae"
expect 0 "closed: +yes" -- "$B" info "$P/puma560_link3.dae"
expect 0 "units: +1 unit = 1 m" -- "$B" info "$P/puma560_link3.dae"
expect 0 "parts" -- "$B" build "$P/puma560_link2.dae" -o "$T/l2.pxm"
expect 0 "leaves: +1 \(parts\)" -- "$B" info "$T/l2.pxm"
expect 0 "triangles" -- "$B" build "$P/puma560_link3.dae" -o "$T/l3.pxm" --pieces triangles
expect 0 "leaves: +12248 \(triangles\)" -- "$B" info "$T/l3.pxm"
# The same distance from the mesh files and from the .pxm files.
d1=$("$B" distance "$P/puma560_link3.dae" "$P/puma560_link3.dae" --pose-b 0,0.5,0 | grep '^distance')
d2=$("$B" distance "$T/l3.pxm" "$T/l3.pxm" --pose-b 0,0.5,0 | grep '^distance')
if [ -n "$d1" ] && [ "$d1" = "$d2" ]; then pass=$((pass + 1)); else
  echo "check_cli: FAILED: distance from meshes '$d1' and from .pxm '$d2' differ" >&2
  fail=$((fail + 1))
fi
expect 0 "collide: +no" -- "$B" distance "$T/l3.pxm" "$T/l3.pxm" --pose-b 0,0.5,0
expect 0 "collide: +yes" -- "$B" distance "$T/l3.pxm" "$T/l3.pxm" --pose-b 0.01,0,0,1,0.1,0,0
expect 0 "bracket" -- "$B" distance "$T/l2.pxm" "$P/puma560_link3.dae" --pieces parts --pose-b 0,0.6,0
expect 0 "approximate convex pieces" -- "$B" build "$P/puma560_link2.dae" -o "$T/a2.pxm" --pieces approximate --tolerance 0.1 --threads 2
expect 0 "leaves: +[0-9]+ \(approximate convex pieces\)" -- "$B" info "$T/a2.pxm"
expect 0 "bracket" -- "$B" distance "$T/a2.pxm" "$T/l2.pxm" --pose-b 0,0.6,0
# --scale: half the size at half the offset is half the distance.
tp=$M/teapot/trimesh_mit/teapot.stl
s1=$("$B" distance "$tp" "$tp" --pose-b 100,0,0 | awk '/^distance/ {print $2}')
s2=$("$B" distance "$tp" "$tp" --pose-b 50,0,0 --scale 0.5 | awk '/^distance/ {print $2}')
if awk -v a="$s1" -v b="$s2" 'BEGIN { d = a / 2 - b; exit !(a > 1 && d < 1e-9 * a && d > -1e-9 * a) }'; then
  pass=$((pass + 1))
else
  echo "check_cli: FAILED: --scale 0.5 gives $s2, scale 1 gives $s1" >&2
  fail=$((fail + 1))
fi
# Errors name the file; usage errors exit 2.
expect 1 "/nonexistent.stl" -- "$B" info /nonexistent.stl
expect 1 "Is a directory|not a regular file" -- "$B" info "$T"
printf 'PXMODEL\0xxxx' >"$T/short.pxm"
expect 1 "short.pxm' is too short" -- "$B" info "$T/short.pxm"
head -c 300 "$T/l3.pxm" >"$T/cut.pxm"
expect 1 "cut.pxm" -- "$B" distance "$T/cut.pxm" "$T/l2.pxm"
expect 2 "needs -o" -- "$B" build "$P/puma560_link2.dae"
expect 2 "already a .pxm" -- "$B" build "$T/l2.pxm" -o "$T/x.pxm"
expect 2 "unknown option" -- "$B" info x --bogus
expect 2 "unknown command" -- "$B" frobnicate
expect 2 "bad pose" -- "$B" distance a b --pose-a 1,2
expect 2 "bad pose" -- "$B" distance a b --pose-a 1,2,3,0,0,0,0
expect 2 "positive number" -- "$B" info x --scale -1
expect 2 "parts, triangles or approximate" -- "$B" info x --pieces hulls
expect 2 "need --pieces approximate" -- "$B" build x -o y --tolerance 0.1
expect 2 "need --pieces approximate" -- "$B" build x -o y --threads 2
expect 2 "from 1 to 256" -- "$B" build x -o y --pieces approximate --threads 0
expect 2 "in \[0.0001, 1\]" -- "$B" build x -o y --pieces approximate --tolerance 0
expect 2 "in \[0.0001, 1\]" -- "$B" build x -o y --pieces approximate --tolerance 1e-5
expect 1 "cannot create" -- "$B" build "$P/puma560_link2.dae" -o /nonexistent/dir/x.pxm
expect 2 "options of check" -- "$B" info x --json
expect 2 "options of check" -- "$B" build x -o y --clearance 1

# proxima check (issue 11 §4): every pair of parts that interferes or is
# closer than the clearance.
# ok CONDITION MESSAGE: one assertion
ok() {
  if eval "$1"; then pass=$((pass + 1)); else
    echo "check_cli: FAILED: $2" >&2
    fail=$((fail + 1))
  fi
}
# findings FILE: the findings of a --json report, one per line, names
# dropped (they differ between formats)
findings() { grep -E '^    \{"a": ' "$1" | sed -E 's/"part_a": "[^"]*", "part_b": "[^"]*", //'; }
if [ -n "$A" ]; then
  mkdir -p "$T/stl" "$T/empty" "$T/bad" "$T/qz" "$T/q3a" "$T/q3b" "$T/q3c"
  "$A" boxes --obj "$T/boxes.obj" && "$A" boxes --stl "$T/stl" && "$A" boxes --dae "$T/boxes.dae"
  ok '[ $? = 0 ]' "make_assembly boxes"
  # The shipped example is the generated one.
  ok 'cmp -s "$T/boxes.dae" "$M/assembly/boxes.dae"' "models/assembly/boxes.dae differs from make_assembly's"
  # The same answers from one OBJ, one COLLADA (parts placed by node
  # matrices) and a folder of STL files. Known: a-b overlap, c-d touch, e-f
  # 0.5 apart (witnesses x = 21 and 21.5), h and the open sheet i inside the
  # closed g (surfaces 1 and 0.5 apart), h-i sqrt(3), j-k 2, others >= 5.
  for f in boxes.obj boxes.dae stl; do
    "$B" check "$T/$f" --clearance 0.75 --json >"$T/$f.json"
    ok "[ $? = 1 ]" "check $f --clearance 0.75: exit status 1"
    findings "$T/$f.json" >"$T/$f.found"
    ok '[ $(wc -l <"$T/$f.found") = 5 ]' "check $f --clearance 0.75: 5 findings"
    ok 'grep -qE "^    \{\"a\": 0, \"b\": 1, \"status\": \"interference\", \"distance\": 0," "$T/$f.found"' "$f: a-b overlap"
    ok 'grep -qE "^    \{\"a\": 2, \"b\": 3, \"status\": \"interference\", \"distance\": 0," "$T/$f.found"' "$f: c-d touch"
    ok 'grep -qE "^    \{\"a\": 4, \"b\": 5, \"status\": \"clearance\", \"distance\": 0.5, \"upper_bound\": 0.5, \"point_a\": \[21, .*\"point_b\": \[21.5, " "$T/$f.found"' "$f: e-f at 0.5"
    ok 'grep -qE "^    \{\"a\": 6, \"b\": 7, \"status\": \"inside\", \"distance\": 0, .*\"surface_distance\": 1, \"inside\": \"b\"" "$T/$f.found"' "$f: h inside g"
    ok 'grep -qE "^    \{\"a\": 6, \"b\": 8, \"status\": \"inside\", \"distance\": 0, .*\"surface_distance\": 0.5, \"inside\": \"b\"" "$T/$f.found"' "$f: i inside g"
    ok 'grep -q "\"counts\": {\"interference\": 2, \"inside\": 2, \"clearance\": 1, \"possible\": 0}" "$T/$f.json"' "$f: counts"
  done
  ok 'cmp -s "$T/boxes.obj.found" "$T/stl.found"' "OBJ and STL folder findings differ"
  ok 'cmp -s "$T/boxes.dae.found" "$T/stl.found"' "COLLADA and STL folder findings differ"
  if command -v python3 >/dev/null; then
    ok 'python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$T/stl.json"' "--json is not valid JSON"
  fi
  # Deterministic: the same report twice.
  "$B" check "$T/stl" --clearance 3 --json >"$T/r1" 2>&1
  "$B" check "$T/stl" --clearance 3 --json >"$T/r2" 2>&1
  ok 'cmp -s "$T/r1" "$T/r2"' "two runs differ"
  # Clearance 3 adds h-i (sqrt 3) and j-k (2); clearance 0 drops e-f.
  ok '[ $(findings "$T/r1" | wc -l) = 7 ]' "check --clearance 3: 7 findings"
  ok 'findings "$T/r1" | grep -qE "\"a\": 7, \"b\": 8, \"status\": \"clearance\", \"distance\": 1.73205080756887[67]"' "h-i at sqrt(3)"
  ok 'findings "$T/r1" | grep -qE "\"a\": 9, \"b\": 10, \"status\": \"clearance\", \"distance\": 2, .*\"point_a\": \[41, .*\"point_b\": \[43, "' "j-k at 2"
  ok '[ $("$B" check "$T/stl" --json | grep -c "\"status\"") = 4 ]' "check (clearance 0): 4 findings"
  expect 1 "^e_gap.stl +f_gap.stl +clearance +0.5 +21 1 0 +21.5 1 0" -- "$B" check "$T/stl" --clearance 0.75
  expect 1 "^g_shell +h_inner +b inside a +0 " -- "$B" check "$T/boxes.obj" --clearance 0.75
  expect 1 "found: +5 pairs: 2 interfering, 2 inside another part, 1 closer than 0.75" -- "$B" check "$T/boxes.dae" --clearance 0.75
  # A part of two cubes, one inside a box and one outside: only part of
  # it is inside (a review found "a inside b" said of it).
  cube() { # cube NAME X0 HALF VERTEX_OFFSET
    local i=$4
    [ -n "$1" ] && echo "o $1"
    for x in -1 1; do for y in -1 1; do for z in -1 1; do
      awk -v c="$2" -v h="$3" -v x=$x -v y=$y -v z=$z 'BEGIN { print "v", c + x * h, y * h, z * h }'
    done; done; done
    for f in "1 2 4" "1 4 3" "5 7 8" "5 8 6" "1 5 6" "1 6 2" "3 4 8" "3 8 7" "1 3 7" "1 7 5" "2 6 8" "2 8 4"; do
      set -- $f
      echo "f $(($1 + i)) $(($2 + i)) $(($3 + i))"
    done
  }
  { cube two 0 0.25 0; cube "" 10 0.25 8; cube big 0 1.5 16; cube small 20 0.25 24; cube box 20 1.5 32; } >"$T/partial.obj"
  expect 1 "^two +big +part of a in b +0 " -- "$B" check "$T/partial.obj"
  expect 1 "^small +box +a inside b +0 " -- "$B" check "$T/partial.obj"
  ok '"$B" check "$T/partial.obj" --json | grep -q "\"part_a\": \"two\", \"part_b\": \"big\", .*\"inside\": \"part of a\"}"' "check --json: part of a inside"
  # --ignore: the pairs touching by design; then clean (exit 0), with the
  # closest pair named.
  IGN="--ignore a_overlap.stl,b_overlap.stl --ignore c_touch.stl,d_touch.stl --ignore g_shell.stl,h_inner.stl --ignore i_sheet.stl,g_shell.stl"
  expect 0 "found: +nothing" -- "$B" check "$T/stl" --clearance 0.25 $IGN
  expect 0 "closest: +0.5 between e_gap.stl and f_gap.stl" -- "$B" check "$T/stl" --clearance 0.25 $IGN
  expect 1 "found: +1 pairs" -- "$B" check "$T/stl" --clearance 0.75 $IGN
  # Decimal numbers only (review s29: 0x10 ran as 16, -0 printed as -0).
  expect 2 "finite number >= 0, not '0x10'" -- "$B" check "$T/stl" --clearance 0x10
  expect 2 "finite number >= 0, not 'inf'" -- "$B" check "$T/stl" --clearance inf
  expect 1 "closer than 0$" -- "$B" check "$T/stl" --clearance -0
  expect 2 "positive number, not '0x1p-1'" -- "$B" check "$T/stl" --scale 0x1p-1
  expect 2 "bad pose" -- "$B" distance "$T/l3.pxm" "$T/l3.pxm" --pose-b 0x1,0,0
  expect 0 "distance" -- "$B" distance "$T/l3.pxm" "$T/l3.pxm" --pose-b 1e-310,0.5,0
  expect 2 "not two part names" -- "$B" check "$T/stl" --ignore a_overlap.stl,nope.stl
  expect 2 "two part names" -- "$B" check "$T/stl" --ignore a_overlap.stl
  # A part of lines only is skipped, and --ignore may still name it.
  mkdir -p "$T/wire" && cp "$T/stl/a_overlap.stl" "$T/stl/b_overlap.stl" "$T/wire/"
  printf 'v 0 0 0\nv 1 0 0\nl 1 2\n' >"$T/wire/lines.obj"
  expect 1 "found: +1 pairs" -- "$B" check "$T/wire" --ignore lines.obj,a_overlap.stl
  expect 0 "found: +nothing" -- "$B" check "$T/wire" --ignore lines.obj,a_overlap.stl --ignore a_overlap.stl,b_overlap.stl
  expect 2 "not two part names" -- "$B" check "$T/wire" --ignore lines.obj,nope.stl
  # Exact where the triangles sit: two coplanar triangles 1e-12 across at
  # x = 100 overlap (were measured 5e-29 apart); 1e-9 apart they do not,
  # and 1e-10 apart they are closer than a clearance of 1e-9.
  mkdir -p "$T/cop" "$T/cop2" "$T/cop3"
  tri() { printf 'solid p\n facet normal 0 0 0\n  outer loop\n   vertex %s\n   vertex %s\n   vertex %s\n  endloop\n endfacet\nendsolid p\n' "$@"; }
  tri "100 0 0" "100 1e-12 0" "100 0 1e-12" >"$T/cop/a.stl"
  tri "100 3e-13 3e-13" "100 -5e-13 1e-13" "100 2e-13 -6.999999999999999e-13" >"$T/cop/b.stl"
  expect 1 "^a.stl +b.stl +interference" -- "$B" check "$T/cop"
  cp "$T/cop/a.stl" "$T/cop2/" && cp "$T/cop/a.stl" "$T/cop3/"
  tri "100.000000001 0 0" "100.000000001 1 0" "100.000000001 0 1" >"$T/cop2/b.stl"
  expect 0 "found: +nothing" -- "$B" check "$T/cop2"
  tri "100.0000000001 0 0" "100.0000000001 1 0" "100.0000000001 0 1" >"$T/cop3/b.stl"
  expect 1 "^a.stl +b.stl +clearance +1.000" -- "$B" check "$T/cop3" --clearance 1e-9
  # Exactly coplanar triangles that overlap (faces on one plane, as parts
  # touching by design have them) measure 0: near the origin, and at 1e15
  # (were 3.6e-12 apart, a review's random case).
  mkdir -p "$T/flat" "$T/flat15"
  tri "0.1 0.2 0.3" "0.7 0.25 0.3" "0.2 0.9 0.3" >"$T/flat/a.stl"
  tri "0.4 0.1 0.3" "0.3 0.8 0.3" "0.9 0.6 0.3" >"$T/flat/b.stl"
  expect 1 "^a.stl +b.stl +interference +0 " -- "$B" check "$T/flat"
  tri "-674766667690497.1 17703854475077.46 969097046843295.5" "-674766667570632.9 17703854465677.66 969097046843295.5" \
    "-674766667762453.9 17703854461989.99 969097046843295.5" >"$T/flat15/a.stl"
  tri "-674766667643193.6 17703854490190.227 969097046843295.5" "-674766667744063.1 17703854462198.715 969097046843295.5" \
    "-674766667629218.9 17703854560643.01 969097046843295.5" >"$T/flat15/b.stl"
  expect 1 "^a.stl +b.stl +interference +0 " -- "$B" check "$T/flat15"
  # A triangle of no area in the other's plane is not inside it: a point
  # triangle at the origin and a triangle 1.414 away on z = 0.
  mkdir -p "$T/dot"
  tri "0 0 0" "0 0 0" "0 0 0" >"$T/dot/a.stl"
  tri "1 1 0" "2 1 0" "1 2 0" >"$T/dot/b.stl"
  expect 1 "^a.stl +b.stl +clearance +1.41421356 " -- "$B" check "$T/dot" --clearance 10
  # Skipped names never make a name of two parts ambiguous: parts a and
  # "b,c", lines-only objects "a,b" and c; "a,b,c" is still a with b,c.
  printf 'o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b,c\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 4 5 6\no a,b\nv 5 5 5\nv 6 5 5\nl 7 8\no c\nv 7 5 5\nv 8 5 5\nl 9 10\n' >"$T/amb.obj"
  expect 0 "1 pairs ignored" -- "$B" check "$T/amb.obj" --ignore 'a,b,c'
  expect 1 "found: +1 pairs" -- "$B" check "$T/amb.obj" --ignore 'c,a'
  # OBJ objects the loader would merge although their names differ
  # ("bolt 1" and "bolt 2" are both "bolt" to Assimp 5.2) are refused;
  # objects of one name are one part, as documented.
  printf 'o bolt 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no bolt 2\nv 0 0 0.05\nv 1 0 0.05\nv 0 1 0.05\nf 4 5 6\n' >"$T/bolts.obj"
  expect 2 "line 6: object 'bolt 2' is 'bolt' to Assimp 5.2, as is 'bolt 1' on line 1" -- "$B" check "$T/bolts.obj"
  printf 'g bolt\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no bolt\t1\nv 0 0 0.05\nv 1 0 0.05\nv 0 1 0.05\nf 4 5 6\n' >"$T/bolts_g.obj"
  expect 2 "line 6: object 'bolt\\\\t1' is 'bolt' to Assimp 5.2, as is 'bolt' on line 1" -- "$B" check "$T/bolts_g.obj"
  # An object continued after another: Assimp 5.2 puts its later faces
  # (refused at the first of them)
  # into the other's part (here the bolt's second triangle into the nut,
  # reported 0.05 from the bolt). Consecutive `o` of one name are one part.
  printf 'o bolt\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no nut\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 4 5 6\no bolt\nv 0 0 0.05\nv 1 0 0.05\nv 0 1 0.05\nf 7 8 9\n' >"$T/same.obj"
  expect 2 "line 15: object 'bolt' \(line 1\) continues after object 'nut' \(line 6\)" -- "$B" check "$T/same.obj" --clearance 0.1
  printf 'g a\no bolt\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no bolt\nv 0 0 0.05\nv 1 0 0.05\nv 0 1 0.05\nf 4 5 6\ng a\no nut\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 7 8 9\n' >"$T/same2.obj"
  expect 0 "found: +nothing" -- "$B" check "$T/same2.obj" --clearance 0.1
  # A file name with a line break is shown escaped on the assembly line
  # and in notes; a clearance below the double range is refused.
  NL="$T/$(printf 'nl\nfake: x')"
  mkdir -p "$NL" && cp "$T/bolts.obj" "$NL/"
  expect 2 "line 6: object 'bolt 2'" -- "$B" check "$NL/bolts.obj"
  expect 2 'nl\\nfake: x/bolts.obj.. line 6' -- "$B" check "$NL/bolts.obj"
  printf 'o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$NL/a.obj"
  rm "$NL/bolts.obj"
  expect 0 'assembly: +.*nl\\nfake: x \(folder, 1 part' -- "$B" check "$NL"
  expect 2 "'1e-400' is beyond the range of doubles" -- "$B" check "$NL" --clearance 1e-400
  # The same with CR line ends; the active group named again after
  # another object (`g a`, `o b`, `g a`) changes nothing: the faces stay in
  # b, the object they follow, 0.05 from a; a subnormal clearance is a
  # number.
  printf 'o bolt\rv 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\ro nut\rv 5 0 0\rv 6 0 0\rv 5 1 0\rf 4 5 6\ro bolt\rv 0 0 0.05\rv 1 0 0.05\rv 0 1 0.05\rf 7 8 9\r' >"$T/same_cr.obj"
  expect 2 "line 15: object 'bolt' \(line 1\) continues after object 'nut'" -- "$B" check "$T/same_cr.obj"
  printf 'g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 4 5 6\ng a\nv 0 0 0.05\nv 1 0 0.05\nv 0 1 0.05\nf 7 8 9\n' >"$T/gog.obj"
  expect 1 "^a +b +clearance +0.05[0-9]* " -- "$B" check "$T/gog.obj" --clearance 0.1
  expect 0 "clearance 1e-310" -- "$B" check "$T/same2.obj" --clearance 1e-310
  # The JSON lists the skipped parts by both their names.
  expect 0 '"skipped": \[$' -- "$B" check "$T/amb.obj" --ignore 'a,b,c' --json
  expect 0 '\{"name": "a,b", "mesh_name": "a,b/a,b"\},' -- "$B" check "$T/amb.obj" --ignore 'a,b,c' --json
  expect 1 '\{"name": "lines.obj", "mesh_name": null\}' -- "$B" check "$T/wire" --json
  # Two slivers about 1e-10 across at (-2e4, 2.4, -3.7e4): 3.1094680939e-14
  # apart in exact rational arithmetic. Measured where they sit, an edge
  # pair within ulps of 4e4 was taken as closest (1.76e-10).
  mkdir -p "$T/sliver"
  tri "-20804.98931634255 2.364129635524833 -37323.24561155667" "-20804.989316342475 2.364129635553021 -37323.245611556435" \
    "-20804.98931634232 2.364129635566344 -37323.24561155675" >"$T/sliver/a.stl"
  tri "-20804.989316342366 2.3641296355623473 -37323.24561155665" "-20804.98931634229 2.364129635590535 -37323.24561155642" \
    "-20804.989316342133 2.3641296356038586 -37323.24561155673" >"$T/sliver/b.stl"
  expect 1 "^a.stl +b.stl +clearance +3.1094680[89]e-14 " -- "$B" check "$T/sliver" --clearance 1e-10
  # Control characters in part names (glTF node names) are escaped in the
  # table, so that the columns hold: one triangle twice, overlapping.
  z='\x00\x00\x00\x00' o='\x00\x00\x80\x3f'
  data=$(printf "$z$z$z$o$z$z$z$o$z" | base64 -w0)
  # gltf FILE NODES MESHES: a glTF of those nodes and meshes (JSON lists
  # without brackets), every mesh the triangle (0,0,0) (1,0,0) (0,1,0).
  gltf() {
    local n
    n=$(grep -o '"mesh"' <<<"$2" | wc -l)
    printf '{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [%s]}],\n "nodes": [%s],\n "meshes": [%s],\n' \
      "$(seq -s, 0 $((n - 1)))" "$2" "$3" >"$1"
    printf ' "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],\n "bufferViews": [{"buffer": 0, "byteLength": 36}],\n "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,%s"}]}\n' \
      "$data" >>"$1"
  }
  tri0='{"primitives": [{"attributes": {"POSITION": 0}}]}'
  gltf "$T/tab.gltf" '{"name": "left\tpart", "mesh": 0}, {"name": "right\npart", "mesh": 0, "translation": [0.25, 0.25, 0]}' "$tri0"
  expect 1 '^left\\tpart +right\\npart +interference +0 +0.75 0.25 0 ' -- "$B" check "$T/tab.gltf"
  expect 1 '"name": "left\\u0009part"' -- "$B" check "$T/tab.gltf" --json
  # Instances of one mesh under nodes of one name get unique names
  # node/mesh#k, and their base name still names them all.
  gltf "$T/inst.gltf" '{"name": "bolt", "mesh": 0}, {"name": "bolt", "mesh": 0, "translation": [0.25, 0.25, 0]},
    {"name": "bolt", "mesh": 0, "translation": [5, 0, 0]}' "$tri0"
  expect 1 '^bolt/meshes\[0\]#1 +bolt/meshes\[0\]#2 +interference' -- "$B" check "$T/inst.gltf"
  expect 0 "found: +nothing" -- "$B" check "$T/inst.gltf" --ignore 'bolt/meshes[0]#2,bolt/meshes[0]#1'
  expect 0 "3 pairs ignored" -- "$B" check "$T/inst.gltf" --ignore 'bolt/meshes[0],bolt/meshes[0]'
  # A generated name never takes a name the file gives: meshes "m" (twice
  # under nodes "x") and "m#1" (under a third "x") are x/m#2, x/m#3, x/m#1.
  gltf "$T/clash.gltf" '{"name": "x", "mesh": 0}, {"name": "x", "mesh": 0, "translation": [5, 0, 0]},
    {"name": "x", "mesh": 1, "translation": [0.25, 0.25, 0]}' \
    '{"name": "m", "primitives": [{"attributes": {"POSITION": 0}}]}, {"name": "m#1", "primitives": [{"attributes": {"POSITION": 0}}]}'
  expect 1 '^x/m#2 +x/m#1 +interference' -- "$B" check "$T/clash.gltf"
  expect 1 "found: +1 pairs" -- "$B" check "$T/clash.gltf" --ignore 'x/m#2,x/m#3'
  # A skipped part's name is taken too: nodes "bolt" twice (mesh cube),
  # a points-only node "bolt/cube" and "other" on the first bolt. The
  # bolts are bolt/cube#1 and #2 with no shared name, so --ignore
  # bolt/cube,other names the skipped part and leaves the interference.
  gltf "$T/skip.gltf" '{"name": "bolt", "mesh": 0}, {"name": "bolt", "mesh": 0, "translation": [5, 0, 0]},
    {"name": "bolt/cube", "mesh": 1}, {"name": "other", "mesh": 2, "translation": [0.25, 0.25, 0]}' \
    '{"name": "cube", "primitives": [{"attributes": {"POSITION": 0}}]},
     {"name": "pts", "primitives": [{"attributes": {"POSITION": 0}, "mode": 0}]}, '"$tri0"
  expect 1 '^bolt/cube#1 +other +interference' -- "$B" check "$T/skip.gltf" --ignore bolt/cube,other
  # A part's own name is never a skipped part's: nodes W (mesh a), W (mesh
  # b, far), a points-only W/a and "other" on the first: that part is W/a#1,
  # so --ignore W/a,other names the skipped part and leaves the interference.
  gltf "$T/skip2.gltf" '{"name": "W", "mesh": 0}, {"name": "W", "mesh": 1, "translation": [5, 0, 0]},
    {"name": "W/a", "mesh": 2}, {"name": "other", "mesh": 1, "translation": [0.25, 0.25, 0]}' \
    '{"name": "a", "primitives": [{"attributes": {"POSITION": 0}}]}, {"name": "b", "primitives": [{"attributes": {"POSITION": 0}}]},
     {"name": "pts", "primitives": [{"attributes": {"POSITION": 0}, "mode": 0}]}'
  expect 1 '^W/a#1 +other +interference' -- "$B" check "$T/skip2.gltf" --ignore W/a,other
  # Names in the table never look alike: a backslash is doubled.
  gltf "$T/bs.gltf" '{"name": "a\\x01", "mesh": 0}, {"name": "a\u0001", "mesh": 0, "translation": [0.25, 0.25, 0]}' "$tri0"
  expect 1 '^a\\\\x01 +a\\x01 +interference' -- "$B" check "$T/bs.gltf"
  # Open parts are named in a note (a part inside one is not found).
  expect 1 "part 'a.stl' is not a closed surface" -- "$B" check "$T/flat"
  # A file name that is not UTF-8 (Latin-1) still gives valid JSON.
  mkdir -p "$T/latin1" && cp "$T/flat/a.stl" "$T/latin1/b.stl" && cp "$T/flat/b.stl" "$T/latin1/$(printf 'Geh\344use.stl')"
  "$B" check "$T/latin1" --json >"$T/latin1.json" 2>/dev/null
  ok 'python3 -c "import json,sys; d=json.load(open(sys.argv[1],encoding=\"utf-8\")); assert d[\"parts\"][0][\"name\"]==\"Geh\\ufffduse.stl\"" "$T/latin1.json"' \
    "non-UTF-8 name: invalid JSON or not U+FFFD"
  # check takes no .pxm model; the clearance is printed as given.
  expect 2 "l2.pxm' is a .pxm model" -- "$B" check "$T/l2.pxm"
  expect 0 "clearance 0.5000000001," -- "$B" check "$T/inst.gltf" --clearance 0.5000000001 --ignore 'bolt/meshes[0],bolt/meshes[0]'
  # Coarse leaves: brackets, and a bracket across the clearance is "possible".
  expect 1 "possible" -- "$B" check "$T/stl" --pieces parts --clearance 0.75
  expect 1 "upper bound" -- "$B" check "$T/boxes.obj" --pieces approximate --tolerance 0.05 --clearance 0.75
  # Errors: exit 2, naming the file and the problem.
  expect 2 "nonexistent.dae" -- "$B" check /nonexistent.dae
  expect 2 "empty'?: the folder holds no mesh file" -- "$B" check "$T/empty"
  # A part that cannot be read (a broken link) is an error, not a part
  # left out of a clean report (review s30); a sub-folder is not a part.
  mkdir -p "$T/dangling/sub.stl" && cp "$T/stl/a_overlap.stl" "$T/dangling/"
  ln -sf "$T/nowhere.stl" "$T/dangling/gone.stl"
  expect 2 "gone.stl'?: cannot read this part" -- "$B" check "$T/dangling"
  rm "$T/dangling/gone.stl"
  expect 0 "" -- "$B" check "$T/dangling"
  # A binary STL that declares 5 triangles and holds 20 bytes of them.
  # (An ASCII STL with a bad number is refused too, but Assimp 5.2 leaks
  # 2.4 KB on that path, which LeakSanitizer fails under make test.)
  { head -c 80 /dev/zero; printf '\005\000\000\000'; head -c 20 /dev/zero; } >"$T/bad/broken.stl"
  cp "$T/stl/a_overlap.stl" "$T/bad/"
  expect 2 "broken.stl" -- "$B" check "$T/bad"
  expect 2 "broken.stl" -- "$B" check "$T/bad/broken.stl"
  expect 2 "a part and itself are no pair" -- "$B" check "$T/stl" --ignore a_overlap.stl,a_overlap.stl
  expect 2 "finite number >= 0, not '-1'" -- "$B" check "$T/stl" --clearance -1
  expect 2 "finite number >= 0, not 'nan'" -- "$B" check "$T/stl" --clearance nan
  expect 2 "finite number >= 0, not 'inf'" -- "$B" check "$T/stl" --clearance inf
  expect 2 "finite number >= 0, not 'abc'" -- "$B" check "$T/stl" --clearance abc
  expect 2 "finite number >= 0, not '1mm'" -- "$B" check "$T/stl" --clearance 1mm
  expect 2 "needs a number" -- "$B" check "$T/stl" --clearance
  expect 2 "takes one assembly" -- "$B" check "$T/stl" "$T/boxes.obj"
  expect 2 "takes one assembly" -- "$B" check
  expect 2 "no -o" -- "$B" check "$T/stl" --pose-a 1,0,0
  # The commands README.md and docs/check.md show, as written (from the
  # repository's root).
  R="$M/.."
  expect 1 "found: +5 pairs: 2 interfering, 2 inside another part, 1 closer than 0.75" -- \
    bash -c "cd '$R' && '$B' check models/assembly/boxes.dae --clearance 0.75"
  expect 1 '"counts": \{"interference": 0, "inside": 2, "clearance": 0, "possible": 0\}' -- \
    bash -c "cd '$R' && '$B' check models/assembly/boxes.dae --clearance 0.25 --json --ignore a_overlap,b_overlap --ignore c_touch,d_touch"
  expect 0 "closest: +0.5 between e_gap and f_gap" -- \
    bash -c "cd '$R' && '$B' check models/assembly/boxes.dae --clearance 0.25 --ignore a_overlap,b_overlap --ignore c_touch,d_touch --ignore g_shell,h_inner --ignore g_shell,i_sheet"
  expect 0 "found: +nothing \(one part only\)" -- "$B" check "$M/puma560/rtb_puma560_description/meshes/puma560_link3.dae"

  # The Puma 560 (SOURCE.md table 1) at joint configurations, a folder of
  # seven link STLs each. Adjacent links meet at their joints (found unless
  # ignored); link5-link7 (wrist and flange) stay 5.04 mm apart.
  ADJ="--ignore link1.stl,link2.stl --ignore link2.stl,link3.stl --ignore link3.stl,link4.stl --ignore link4.stl,link5.stl --ignore link5.stl,link6.stl --ignore link6.stl,link7.stl"
  "$A" puma "$T/qz" "$M" 0 0 0 0 0 0 && "$A" puma "$T/q3a" "$M" 0 0 -1 0 0 0 &&
    "$A" puma "$T/q3b" "$M" 0 0 -1.05 0 0 0 && "$A" puma "$T/q3c" "$M" 0 0 -1.6 0 0 0
  ok '[ $? = 0 ]' "make_assembly puma"
  expect 1 "^link1.stl +link2.stl +interference" -- "$B" check "$T/qz"
  expect 0 "closest: +0.00503999" -- "$B" check "$T/qz" $ADJ --clearance 0.005
  expect 1 "^link5.stl +link7.stl +clearance +0.00503999" -- "$B" check "$T/qz" $ADJ --clearance 0.01
  expect 1 "found: +1 pairs" -- "$B" check "$T/qz" $ADJ --clearance 0.01
  # Elbow folded back: at q3 = -1 the forearm clears the shoulder by 29.8
  # mm, at -1.05 its wrist comes 17.9 mm from link3, at -1.6 the forearm
  # passes through the upper arm and the wrist's last links lie inside it.
  expect 0 "closest: +0.0298" -- "$B" check "$T/q3a" $ADJ --ignore link5.stl,link7.stl --clearance 0.02
  expect 1 "^link3.stl +link5.stl +clearance +0.0178" -- "$B" check "$T/q3b" $ADJ --ignore link5.stl,link7.stl --clearance 0.02
  "$B" check "$T/q3c" $ADJ --json >"$T/q3c.json"
  ok "[ $? = 1 ]" "Puma folded: exit status 1"
  ok 'grep -q "\"counts\": {\"interference\": 5, \"inside\": 2, \"clearance\": 0" "$T/q3c.json"' "Puma folded: 5 interfering, 2 inside"
  # Against every pair measured alone (px_model_distance and collide, no
  # scene): the same pairs found.
  for i in 1 2 3 4 5 6 7; do
    for j in 1 2 3 4 5 6 7; do
      [ "$i" -lt "$j" ] || continue
      [ "$j" -gt $((i + 1)) ] || continue
      if "$B" distance "$T/q3c/link$i.stl" "$T/q3c/link$j.stl" | grep -qE "collide: +yes"; then
        echo "$((i - 1)) $((j - 1))"
      fi
    done
  done >"$T/q3c.pairs"
  findings "$T/q3c.json" | sed -E 's/^    \{"a": ([0-9]+), "b": ([0-9]+),.*/\1 \2/' >"$T/q3c.found"
  ok 'cmp -s "$T/q3c.pairs" "$T/q3c.found"' "Puma folded: check finds $(tr '\n' ' ' <"$T/q3c.found"), pairs alone $(tr '\n' ' ' <"$T/q3c.pairs")"
fi
echo "check_cli: $pass passed, $fail failed"
[ "$fail" = 0 ]
