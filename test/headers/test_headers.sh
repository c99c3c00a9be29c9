#!/usr/bin/env bash
# Every public header (src/include/dirt/*.h) compiles alone, as C11 and as
# C++: it includes what it uses and has C linkage guards.
# usage: test_headers.sh SOURCE_ROOT CC CXX
set -u
root=$1 cc=$2 cxx=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passes=0 fails=0
for h in "$root"/src/include/dirt/*.h; do
  name=dirt/$(basename "$h")
  printf '#include "%s"\n#include "%s"\n' "$name" "$name" >"$tmp/one.c"
  if $cc -std=c11 -Wall -Wextra -Werror -pedantic -fsyntax-only -I"$root/src/include" \
      -I"$root/glsl" "$tmp/one.c" 2>"$tmp/err"; then passes=$((passes + 1)); else
    fails=$((fails + 1)); echo "FAIL (C11): $name"; cat "$tmp/err"; fi
  cp "$tmp/one.c" "$tmp/one.cpp"
  if $cxx -std=c++14 -Wall -Wextra -Werror -fsyntax-only -I"$root/src/include" \
      -I"$root/glsl" "$tmp/one.cpp" 2>"$tmp/err"; then passes=$((passes + 1)); else
    fails=$((fails + 1)); echo "FAIL (C++): $name"; cat "$tmp/err"; fi
  # A header that declares functions gives them C linkage for C++ callers.
  if grep -qE '^[a-z].*\($|^[a-z].*\);$' "$h" && ! grep -q 'extern "C"' "$h"; then
    fails=$((fails + 1)); echo "FAIL: $name declares functions without extern \"C\""
  else
    passes=$((passes + 1))
  fi
done
[ $passes -gt 0 ] || { echo "no headers found under $root/src/include/dirt"; exit 1; }
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
