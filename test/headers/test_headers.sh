#!/usr/bin/env bash
# The consumer headers, exactly the set meson installs under include/dirt/,
# are self-contained: each compiles alone, as C11 and as C++, from a copy of
# the installed set with nothing else on the include path (no src/, no
# glsl/), and gives its functions C linkage. src/include/dirt/ holds no
# header that is not installed.
# usage: test_headers.sh SOURCE_ROOT CC CXX INSTALLED_HEADER...
set -u
root=$1 cc=$2 cxx=$3
shift 3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passes=0 fails=0
mkdir -p "$tmp/include/dirt"
for h in "$@"; do cp "$h" "$tmp/include/dirt/"; done
installed=$(cd "$tmp/include/dirt" && ls | sort)
present=$(cd "$root/src/include/dirt" && ls | sort)
if [ "$installed" != "$present" ]; then
  fails=$((fails + 1))
  echo "FAIL: src/include/dirt/ and the installed headers differ:"
  diff <(echo "$present") <(echo "$installed") | sed 's/^/  /'
else
  passes=$((passes + 1))
fi
for h in "$tmp"/include/dirt/*.h; do
  name=dirt/$(basename "$h")
  # (the typedef: a header of macros only still makes a translation unit)
  printf '#include "%s"\n#include "%s"\ntypedef int one_t;\n' "$name" "$name" >"$tmp/one.c"
  if $cc -std=c11 -Wall -Wextra -Werror -pedantic -fsyntax-only -I"$tmp/include" \
      "$tmp/one.c" 2>"$tmp/err"; then passes=$((passes + 1)); else
    fails=$((fails + 1)); echo "FAIL (C11): $name"; cat "$tmp/err"; fi
  cp "$tmp/one.c" "$tmp/one.cpp"
  if $cxx -std=c++14 -Wall -Wextra -Werror -fsyntax-only -I"$tmp/include" \
      "$tmp/one.cpp" 2>"$tmp/err"; then passes=$((passes + 1)); else
    fails=$((fails + 1)); echo "FAIL (C++): $name"; cat "$tmp/err"; fi
  # A header that declares functions gives them C linkage for C++ callers.
  if grep -q '^DIRT_API' "$h" && ! grep -q 'extern "C"' "$h"; then
    fails=$((fails + 1)); echo "FAIL: $name declares functions without extern \"C\""
  else
    passes=$((passes + 1))
  fi
done
[ $# -gt 0 ] || { echo "no installed headers given"; exit 1; }
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
