#!/usr/bin/env bash
# What `meson install` gives an outside user, with the source tree gone:
#   1. a copy of the source tree (git ls-files: tracked and untracked files
#      that are not ignored) is configured with a temporary --prefix and
#      -Dtests=false -Dperf=false, built and installed;
#   2. the copied source and build trees are deleted, so nothing installed
#      can lean on them (shaders, the default scene, headers);
#   3. examples/render.c builds with nothing but `pkg-config --cflags --libs
#      dirt` and renders the default scene with the dirt and the embree
#      engine; the installed dirt-render renders the same;
#   4. the images agree: the DIRT images of the example and of dirt-render
#      are identical (the same session, the same seed), and each engine's
#      DIRT image equals the Embree one to relMSE <= 1e-6 (the same paths);
#   5. the installed Python module passes test/python/test_dirt.py (DIRT =
#      Embree from Python, progressive = one render, error ids);
#   6. the installed include/dirt/ holds exactly the consumer headers and
#      the library's soname is libdirt.so.MAJOR.
# usage: test_install.sh SOURCE_ROOT EXR_COMPARE PYTHON3 HEADER...
set -euo pipefail
root=$1 exr_compare=$2 python=$3
shift 3
start=$(date +%s)
tmp=$(mktemp -d /tmp/dirt-install-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
step() { echo "== $* ($(( $(date +%s) - start )) s)"; }
unset DIRT_GLSL_DIR

step "copy of the source tree"
mkdir -p "$tmp/src" "$tmp/outside"
if git -C "$root" rev-parse --show-toplevel >/dev/null 2>&1; then
  (cd "$root" && git ls-files -z --cached --others --exclude-standard |
     while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
     xargs -0 cp --parents -t "$tmp/src")
else
  (cd "$root" && tar --exclude='./build*' --exclude='./out' -cf - .) | (cd "$tmp/src" && tar xf -)
fi
cp "$root/examples/render.c" "$tmp/outside/"

step "configure, build, install into $tmp/prefix"
prefix=$tmp/prefix
meson setup "$tmp/build" "$tmp/src" --prefix "$prefix" -Dtests=false -Dperf=false \
  >"$tmp/setup.log" 2>&1 || { cat "$tmp/setup.log"; fail "meson setup"; }
ninja -C "$tmp/build" >"$tmp/build.log" 2>&1 || { tail -50 "$tmp/build.log"; fail "build"; }
meson install -C "$tmp/build" >"$tmp/install.log" 2>&1 || { cat "$tmp/install.log"; fail "install"; }
rm -rf "$tmp/src" "$tmp/build"
[ ! -e "$tmp/src" ] && [ ! -e "$tmp/build" ] || fail "the copied trees are still there"

step "installed files"
pc=$(find "$prefix" -name dirt.pc)
[ -n "$pc" ] || fail "no dirt.pc under $prefix"
export PKG_CONFIG_PATH=$(dirname "$pc")
libdir=$(pkg-config --variable=libdir dirt)
major=$(grep -o 'DIRT_VERSION_MAJOR [0-9]*' "$prefix/include/dirt/version.h" | cut -d' ' -f2)
[ -e "$libdir/libdirt.so.$major" ] || fail "no $libdir/libdirt.so.$major"
soname=$(readelf -d "$libdir/libdirt.so.$major" | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
[ "$soname" = "libdirt.so.$major" ] || fail "soname '$soname', not libdirt.so.$major"
want=$(for h in "$@"; do basename "$h"; done | sort)
have=$(ls "$prefix/include/dirt" | sort)
[ "$want" = "$have" ] || fail "include/dirt/ holds: $have"
for p in dirt-render dirt-compare dirt-view; do
  [ -x "$prefix/bin/$p" ] || fail "no $prefix/bin/$p"
done
if grep -rl "$root/glsl\|$tmp/src" "$prefix/bin" "$libdir"/libdirt.so.* >/dev/null 2>&1; then
  fail "installed binaries name a source tree"
fi

step "examples/render.c with pkg-config only"
cd "$tmp/outside"
flags=$(pkg-config --cflags --libs dirt)
echo "pkg-config --cflags --libs dirt: $flags"
case "$flags" in *glsl*|*/src*) fail "pkg-config flags name source paths: $flags" ;; esac
cc -std=c11 -Wall -Wextra -Werror render.c $flags -o render || fail "the example does not build"
args=(-W 64 -H 48 --spp 4 --seed 3 --bounces 2)
LD_LIBRARY_PATH=$libdir ./render "${args[@]}" -o ex_dirt.exr || fail "the example (dirt)"
LD_LIBRARY_PATH=$libdir ./render --engine embree "${args[@]}" -o ex_embree.exr ||
  fail "the example (embree)"

step "the installed dirt-render"
"$prefix/bin/dirt-render" "${args[@]}" -q -o r_dirt.exr || fail "dirt-render (dirt)"
"$prefix/bin/dirt-render" --engine embree "${args[@]}" -q -o r_embree.exr ||
  fail "dirt-render (embree)"
"$prefix/bin/dirt-render" -o x.exr -W 32 --spp 1 -q || fail "dirt-render -o x.exr"
"$exr_compare" --not-black x.exr 0.01 || fail "dirt-render -o x.exr is black"
"$prefix/bin/dirt-view" --help >/dev/null || fail "dirt-view --help"

step "images"
"$exr_compare" ex_dirt.exr r_dirt.exr 0 || fail "the example's image differs from dirt-render's"
"$exr_compare" ex_dirt.exr ex_embree.exr 1e-6 || fail "example: DIRT differs from Embree"
"$exr_compare" r_dirt.exr r_embree.exr 1e-6 || fail "dirt-render: DIRT differs from Embree"
"$exr_compare" --not-black r_dirt.exr 0.05 || fail "the image is black"

step "the installed Python module"
pypath=$(dirname "$(find "$prefix" -name __init__.py -path '*/dirt/*' | head -1)")
[ -n "$pypath" ] && [ -f "$pypath/_cdef.h" ] || fail "no Python package dirt under $prefix"
cp "$root/test/python/test_dirt.py" .
PYTHONPATH=$(dirname "$pypath") PYTHONDONTWRITEBYTECODE=1 "$python" -c \
  'import dirt, sys; assert dirt.__file__.startswith(sys.argv[1]), dirt.__file__' "$prefix" ||
  fail "import dirt does not find the installed module"
PYTHONPATH=$(dirname "$pypath") PYTHONDONTWRITEBYTECODE=1 "$python" -m pytest -q \
  -p no:cacheprovider test_dirt.py || fail "the installed Python module"

step "done"
echo "1 passed, 0 failed"
