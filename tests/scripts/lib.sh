# Shared by the script tests: locations and the skip rule (exit 77 = skipped).
set -uo pipefail
: "${RAYFORM_BIN:?RAYFORM_BIN must name the rayform binary}"
: "${RAYFORM_SOURCE_DIR:?}"
RAYFORM_SHARED=${RAYFORM_SHARED:-$RAYFORM_SOURCE_DIR/../shared}

require_shared() {
  if [ ! -d "$RAYFORM_SHARED/course" ]; then
    if [ -n "${CI:-}" ]; then echo "FAIL: third-party data not found at $RAYFORM_SHARED (required in CI)"; exit 1; fi
    echo "SKIPPED: third-party data not found at $RAYFORM_SHARED (set RAYFORM_SHARED)"; exit 77
  fi
  command -v idiff >/dev/null || { echo "FAIL: idiff not found (apt-get install openimageio-tools)"; exit 1; }
}
