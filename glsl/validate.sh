#!/bin/sh
# Build-time shader check: assemble one shader exactly as the engine loads it
# (includes, defines) and compile it with glslangValidator.
#   validate.sh PP GLSLANG ROOT SHADER STAMP [NAME=VALUE ...]
set -eu
pp=$1 glslang=$2 root=$3 shader=$4 stamp=$5
shift 5
ext=${shader##*.}
out=${stamp%.ok}.$ext
"$pp" "$root" "$shader" "$out" "$@"
if ! "$glslang" "$out" > "$out.log" 2>&1; then
    echo "glsl/$shader: glslangValidator rejected it:" >&2
    cat "$out.log" >&2
    exit 1
fi
touch "$stamp"
