#!/usr/bin/env bash
# Builds fmusim, the FMI Reference FMUs' FMU simulator (BSD-2), for the FMU conformance tests
# (fmusim_conformance_test.cpp), with the build.sh beside its source (it installs its Debian
# packages when missing: gcc libxml2-dev zlib1g-dev libminizip-dev libsundials-dev).
#   usage: build_fmusim.sh SOURCE_DIR OUT_DIR  -> OUT_DIR/fmusim
# SOURCE_DIR is tests/third_party/fmusim, vendored (CMake's RHEO_FMUSIM_SOURCE). Where it is
# absent the tests are skipped (exit 77, ctest's SKIP_RETURN_CODE), except under CI=true, where
# every tool a test needs must be there: then this fails.
set -euo pipefail
src=$1
out=$2
if [ ! -x "$src/build.sh" ]; then
  if [ "${CI:-}" = true ]; then
    echo "fmusim's source is not at $src (tests/third_party/fmusim in the repository): CI needs it for the FMU conformance tests" >&2
    exit 1
  fi
  echo "SKIPPED: fmusim's source is not at $src (tests/third_party/fmusim in the repository); the FMU conformance tests are skipped"
  exit 77
fi
"$src/build.sh" "$out"
