#!/usr/bin/env bash
# The generated scenes nobody tuned for (issue 25), written into DIR with a
# fixed seed (the same files on every machine):
#   room69k.gltf    a closed room with a 69k-triangle bumpy sphere
#                   (perf/make-room.py: dense geometry in a closed room)
#   mirror69k.glb   88 objects, 69k triangles, over a mirror floor
#                   (perf/make-scale-scene.py --kind mirror)
#   slats69k.glb    88 thin slats, 69k triangles, most seen nearly edge-on
#                   (perf/make-scale-scene.py --kind slats: thin geometry at
#                   grazing angles)
# Used by perf/bench-work.sh and perf/bench-sort.sh; run it to get the
# files for dirt-compare or dirt-render. Needs python3-numpy ($PYTHON, by
# default Debian's /usr/bin/python3).
#
#   perf/gen-scenes.sh DIR
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: perf/gen-scenes.sh DIR" >&2; exit 2; }
dir=$1
here=$(dirname "$0")
py=${PYTHON:-/usr/bin/python3}
mkdir -p "$dir"
"$py" "$here/make-room.py" "$dir/room69k.gltf" 69000
"$py" "$here/make-scale-scene.py" "$dir/mirror69k.glb" 69000 --kind mirror
"$py" "$here/make-scale-scene.py" "$dir/slats69k.glb" 69000 --kind slats
