#!/bin/sh
# Runs the window test under a virtual X server (skip when there is none).
command -v xvfb-run >/dev/null 2>&1 || { echo "xvfb-run missing: skipping"; exit 77; }
exec xvfb-run -a "$1"
