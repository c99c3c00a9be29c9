#!/usr/bin/env bash
# Collects the shared libraries the built programs, tests and benches need
# (beyond libc and the GL/EGL loaders, which the device machine's driver or
# the carried .gl packages provide) into .gpu/lib, for perf/gpu-check.sh on
# a machine without this project's Debian packages. Run from the repo root
# after building; then carry `build`, `.gpu` and `.gl`.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
mkdir -p "$root/.gpu/lib"
grep -qx '/.gpu/' "$root/.git/info/exclude" 2>/dev/null || echo /.gpu/ >>"$root/.git/info/exclude"
skip='^(libc|libm|libdl|libpthread|librt|ld-linux|libGL|libEGL|libGLX|libGLdispatch|libOpenGL|libgcc_s|libstdc\+\+|linux-vdso)'
for exe in "$build"/src/app/dirt-render "$build"/src/app/dirt-compare "$build"/test/gpu/test_* \
           "$build"/perf/bench-* "$build"/perf/gpu-facts; do
  [ -x "$exe" ] && [ -f "$exe" ] || continue
  ldd "$exe" | awk '/=> \//{print $1" "$3}' | while read -r name path; do
    [[ $name =~ $skip ]] && continue
    cp -Lu "$path" "$root/.gpu/lib/$name"
  done
done
du -sh "$root/.gpu" | sed 's/^/packed: /'
