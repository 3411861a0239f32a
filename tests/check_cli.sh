#!/bin/bash
# The proxima command: every subcommand on shipped models, its errors and
# exit codes. Usage: check_cli.sh PROXIMA MODELS_DIR
set -u
B=$1
M=$2
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
echo "check_cli: $pass passed, $fail failed"
[ "$fail" = 0 ]
