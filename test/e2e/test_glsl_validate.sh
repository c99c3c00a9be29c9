#!/usr/bin/env bash
# The build-time shader check rejects a shader that does not compile (so a
# broken shader fails the build and the tests) and accepts a good one,
# includes and injected defines resolved as at run time.
#   test_glsl_validate.sh VALIDATE_SH DIRT_GLSL_PP GLSLANG
set -u
validate=$1 pp=$2 glslang=$3
tmp=$(mktemp -d /tmp/dirt-glsl-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/root/common"
printf 'float helper(float x) { return x * SCALE; }\n' > "$tmp/root/common/h.glsl"
printf '#version 450 core\n#include "common/h.glsl"\nlayout(local_size_x = 1) in;\nlayout(std430, binding = 0) buffer B { float v[]; };\nvoid main() { v[0] = helper(v[0]); }\n' > "$tmp/root/good.comp"
printf '#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() { undefined_function(); }\n' > "$tmp/root/bad.comp"
fails=0
if ! "$validate" "$pp" "$glslang" "$tmp/root" good.comp "$tmp/good.ok" SCALE=2.0; then
  echo "FAIL: a good shader was rejected" >&2; fails=$((fails + 1))
fi
if "$validate" "$pp" "$glslang" "$tmp/root" good.comp "$tmp/nodef.ok" 2>/dev/null; then
  echo "FAIL: a shader using an undefined macro was accepted" >&2; fails=$((fails + 1))
fi
if "$validate" "$pp" "$glslang" "$tmp/root" bad.comp "$tmp/bad.ok" 2>"$tmp/err"; then
  echo "FAIL: a broken shader was accepted" >&2; fails=$((fails + 1))
elif [ -e "$tmp/bad.ok" ]; then
  echo "FAIL: a broken shader left its stamp" >&2; fails=$((fails + 1))
elif ! grep -q "undefined_function" "$tmp/err"; then
  echo "FAIL: the rejection does not show the compiler's message" >&2; fails=$((fails + 1))
fi
echo "$((3 - fails)) passed, $fails failed"
[ $fails -eq 0 ]
