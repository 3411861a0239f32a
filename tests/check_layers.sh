#!/usr/bin/env bash
# Arrows point down only (ARCHITECTURE.md, "Layers"): checks the library's
# real call graph and its includes.
#
# usage: check_layers.sh SRC_DIR OBJECT...
#   SRC_DIR  the repository's src/ (for the #include check)
#   OBJECT   the library's compiled objects under .../src/<layer>/<file>.c.o
#
# Calls come from the objects themselves (nm: what each defines and what it
# leaves undefined), so macros, inlines and indirect includes cannot hide a
# call. Rules:
#   1. no cycle between files (tsort finds one if there is);
#   2. a file calls only files of a lower rank, or of its own rank outside
#      the narrow-phase methods (a method never calls another method);
#   3. query.c is the only file that calls more than one method;
#   4. a file includes only internal headers of its own layer or a lower
#      one (the public headers, include/proxima/, are read by every layer).
set -euo pipefail
src=$1
shift
# ctest passes $<TARGET_OBJECTS:...> as one ;-separated argument
objects=()
for arg in "$@"; do
  IFS=';' read -r -a part <<< "$arg"
  objects+=("${part[@]}")
done
set -- "${objects[@]}"

# Rank of a source file (path relative to src/).
rank() {
  case $1 in
    core/*) echo 0 ;;
    math/*) echo 1 ;;
    convex/* | mesh/*) echo 2 ;;
    narrow/tolerance.* | narrow/simplex.* | narrow/closest.* | narrow/feature.*) echo 3 ;;
    narrow/lin_canny.* | narrow/gjk.* | narrow/hybrid.* | narrow/epa.* | narrow/raycast.*) echo 4 ;;
    narrow/advance.*) echo 5 ;;
    narrow/query.* | narrow/narrow.h) echo 6 ;;
    model/*) echo 7 ;;
    scene/*) echo 8 ;;
    io/*) echo 8 ;;
    *) echo 99 ;;
  esac
}
is_method() { [ "$(rank "$1")" = 4 ]; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

# symbol -> defining file
for o in "$@"; do
  f=${o##*/src/}
  f=${f%.o}
  case $f in *.c) ;; *) continue ;; esac
  nm --defined-only -g "$o" | awk -v f="$f" 'NF == 3 { print $3, f }' >> "$tmp/defs"
  nm -u "$o" | awk -v f="$f" '{ print $NF, f }' >> "$tmp/uses"
done
sort -u "$tmp/defs" -o "$tmp/defs"
sort -u "$tmp/uses" -o "$tmp/uses"
# caller callee pairs between different files
join "$tmp/uses" "$tmp/defs" | awk '$2 != $3 { print $2, $3 }' | sort -u > "$tmp/edges"
ncalls=$(wc -l < "$tmp/edges")
if [ "$ncalls" -lt 10 ]; then
  echo "check_layers: only $ncalls cross-file calls found: wrong object list?" >&2
  exit 1
fi

# 1. cycles
if ! tsort "$tmp/edges" > /dev/null 2> "$tmp/tsort"; then
  echo "check_layers: a cycle between files:" >&2
  cat "$tmp/tsort" >&2
  fail=1
fi

# 2. and 3.
while read -r from to; do
  rf=$(rank "$from")
  rt=$(rank "$to")
  if [ "$rt" -gt "$rf" ] || { [ "$rt" = "$rf" ] && is_method "$from"; }; then
    echo "check_layers: $from (rank $rf) calls $to (rank $rt)" >&2
    fail=1
  fi
done < "$tmp/edges"
awk '{ print $1, $2 }' "$tmp/edges" | while read -r from to; do
  if is_method "$to"; then echo "$from $to"; fi
done | awk '{ n[$1]++ } END { for (f in n) if (n[f] > 1) print f, n[f] }' > "$tmp/multi"
while read -r f n; do
  if [ "$f" != narrow/query.c ]; then
    echo "check_layers: $f calls $n methods (only narrow/query.c may call more than one)" >&2
    fail=1
  fi
done < "$tmp/multi"

# 4. includes ("layer/file.h" paths, relative to src/)
nincl=0
while IFS=: read -r file line; do
  rel=${file#"$src"/}
  inc=$(sed -n 's/^#include "\([a-z_]*\/[a-z_]*\.h\)".*/\1/p' <<< "$line")
  [ -n "$inc" ] || continue
  case $inc in proxima/*) continue ;; esac # the public API, readable by every layer
  nincl=$((nincl + 1))
  rf=$(rank "$rel")
  ri=$(rank "$inc")
  # a file's own header, and the narrow phase's shared declarations, are
  # read by the layer's files at any rank
  if [ "$ri" -gt "$rf" ] && [ "$inc" != narrow/narrow.h ] && [ "${inc%.h}" != "${rel%.c}" ]; then
    echo "check_layers: $rel (rank $rf) includes $inc (rank $ri)" >&2
    fail=1
  fi
done < <(grep -rn '^#include "' "$src" --include='*.c' --include='*.h' | sed 's/:[0-9]*:/:/')

if [ "$fail" = 0 ]; then
  echo "check_layers: $ncalls cross-file calls and $nincl includes, no cycle, every arrow points down"
fi
exit $fail
