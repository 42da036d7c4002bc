# shellcheck shell=bash
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

# Compares the pictures queued in the array `compare` (oiiotool arguments:
# `--echo "== LABEL" GOLDEN NEW --diff` per picture) by the course-parity rule
# (at most 0.5 % of pixels over 2/255), in one oiiotool process; prints a
# PASS/FAIL line per picture, the details of failures and a summary line.
# Arguments: the number of pictures queued, the failures counted before, a
# scratch folder. Returns non-zero when anything failed.
compare_with_goldens() {
  local n=$1 failn=$2 tmp=$3 rc bad
  [ "$n" -gt 0 ] || { echo "FAIL: nothing to compare"; return 1; }
  # shellcheck disable=SC2154  # compare: the caller's array
  oiiotool --fail 0.0079 --failpercent 0.5 "${compare[@]}" >"$tmp/diff.log" 2>&1; rc=$?
  awk '/^== /{label=substr($0, 4)} /^PASS/{print "PASS " label} /WARNING/{print "PASS (warning) " label}
       /FAILURE/{print "FAIL " label}' "$tmp/diff.log"
  bad=$(grep -c 'FAILURE' "$tmp/diff.log")
  if [ "$bad" -ne 0 ] || [ $rc -ne 0 ]; then
    echo "details:"; sed 's/^/    /' "$tmp/diff.log"; failn=$((failn + bad))
  fi
  echo "$((n - bad)) of $n pictures match their golden picture"
  [ "$failn" -eq 0 ] && [ "$rc" -eq 0 ]
}

# Finds the npm test tools (scripts/install-node-tools): the first of
# $RAYFORM_NODE_TOOLS, the build folder's node/ and ~/.cache/rayform/node that
# holds every path given (relative to the folder, e.g.
# node_modules/.bin/gltfpack), else installs them into the last. Sets and
# exports RAYFORM_NODE_TOOLS; exits 77 (skipped) without node or when the
# install fails (offline).
find_node_tools() {
  local d p ok build_dir
  command -v node >/dev/null || { echo "SKIPPED: node not found (apt-get install nodejs npm)"; exit 77; }
  has_node_tools() { for p in "${@:2}"; do [ -e "$1/$p" ] || return 1; done; }
  build_dir=$(cd "$(dirname "$RAYFORM_BIN")/.." && pwd)
  for d in ${RAYFORM_NODE_TOOLS:-} "$build_dir/node" "$HOME/.cache/rayform/node"; do
    if has_node_tools "$d" "$@"; then export RAYFORM_NODE_TOOLS=$d; return 0; fi
  done
  d="$HOME/.cache/rayform/node"
  ok=0
  "$RAYFORM_SOURCE_DIR/scripts/install-node-tools" "$d" >/dev/null 2>&1 && has_node_tools "$d" "$@" && ok=1
  [ $ok = 1 ] || { echo "SKIPPED: node tools ($*) not installed and scripts/install-node-tools failed (offline?)"; exit 77; }
  export RAYFORM_NODE_TOOLS=$d
}

# run_node_tools JOBS LIMIT [CALL_LIMIT]: makes the npm tool calls queued in
# the file JOBS (one a line: FOLDER<TAB>LOG<TAB>TOOL<TAB>ARGUMENT..., TOOL
# gltf-transform, gltfpack or obj2gltf; see tests/tools/run_node_tools.mjs) in
# one node process, for at most LIMIT seconds in all, instead of a node process
# per call (about 1 s of start-up each). A call that process did not finish
# (it died, ran out of time, or stopped at a failure) is then made with the
# tool's own command in FOLDER, for at most CALL_LIMIT (default LIMIT)
# seconds. Writes "STATUS<TAB>LOG" per call (0: the tool
# succeeded) to JOBS.status; each call's output is in its LOG. Needs
# RAYFORM_NODE_TOOLS (find_node_tools).
run_node_tools() {
  local jobs=$1 limit=$2 call_limit=${3:-$2} log
  local -a job
  local -A finished=()
  timeout "$limit" node "$RAYFORM_SOURCE_DIR/tests/tools/run_node_tools.mjs" "$RAYFORM_NODE_TOOLS" "$jobs" \
    >"$jobs.status" 2>"$jobs.log" </dev/null
  while IFS=$'\t' read -r _ log; do finished[$log]=1; done <"$jobs.status"
  while IFS=$'\t' read -r -a job; do
    [ -z "${finished[${job[1]}]:-}" ] || continue
    (cd "${job[0]}" && timeout "$call_limit" "$RAYFORM_NODE_TOOLS/node_modules/.bin/${job[2]}" "${job[@]:3}") \
      >"${job[1]}" 2>&1 </dev/null
    printf '%s\t%s\n' $? "${job[1]}" >>"$jobs.status"
  done <"$jobs"
}

# Writes a small course scene to the file $1: one lit sphere, quick to render.
write_sphere_scene() {
  cat >"$1" <<'EOF'
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Lights { numLights 1 DirectionalLight { direction -0.3 -0.5 -1 color 0.9 0.9 0.9 } }
Background { color 0.1 0.2 0.3 ambientLight 0.1 0.1 0.1 }
Materials { numMaterials 1 Material { diffuseColor 0.8 0.3 0.2 } }
Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 1.5 } }
EOF
}

# For the MPI tests (mpi_*.sh): skips (77) unless mpirun is installed and
# rayform was built with MPI (RAYFORM_MPI; `rayform --version` says so).
# Sets the OpenMPI environment a sandbox or CI container needs: shared memory
# and loopback transports only (no network interfaces to probe), no ssh/rsh
# agent (every rank is local), ranks allowed to outnumber cores, root allowed.
require_mpi() {
  command -v mpirun >/dev/null || { echo "SKIPPED: mpirun not found (apt-get install openmpi-bin libopenmpi-dev)"; exit 77; }
  "$RAYFORM_BIN" --version | grep -q MPI || { echo "SKIPPED: rayform built without MPI (RAYFORM_MPI=OFF)"; exit 77; }
  export OMPI_MCA_btl=self,vader OMPI_MCA_plm_rsh_agent= OMPI_MCA_rmaps_base_oversubscribe=1
  # Shared memory only: OpenMPI's default UCX layer probes for network devices
  # at start (about 0.2 s a job here) for nothing on one machine.
  export OMPI_MCA_pml=ob1
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
}

# mpi_run N ARGS...: rayform ARGS... as N ranks.
mpi_run() {
  local n=$1; shift
  mpirun --allow-run-as-root --oversubscribe -np "$n" "$RAYFORM_BIN" "$@"
}

# The errors of a rendered picture against a path-traced reference
# (reference_pbr.sh, scripts/bench-pbr-accuracy): the mean absolute
# difference of the sRGB encodings (clamped to 0..1, oiiotool --tocolorspace
# sRGB) over the image, and over the model's pixels (the mask's alpha as
# weight). Prints "IMAGE MODEL". Arguments: OURS.exr REFERENCE.exr MASK.exr SCRATCH.exr
reference_errors() {
  local mean='s/.*Stats Avg: *\([^ ]*\) \([^ ]*\) \([^ ]*\).*/\1 \2 \3/p' image weighted coverage
  oiiotool "$1" --ch R,G,B --clamp:min=0:max=1 --tocolorspace sRGB "$2" --ch R,G,B --clamp:min=0:max=1 \
    --tocolorspace sRGB --absdiff -o "$4" || return 1
  image=$(oiiotool "$4" --printstats 2>&1 | sed -n "$mean" | awk '{print ($1 + $2 + $3) / 3}')
  weighted=$(oiiotool "$4" "$3" --ch A,A,A --mul --printstats 2>&1 | sed -n "$mean" | awk '{print ($1 + $2 + $3) / 3}')
  coverage=$(oiiotool "$3" --ch A,A,A --printstats 2>&1 | sed -n "$mean" | awk '{print ($1 + $2 + $3) / 3}')
  awk -v i="$image" -v w="$weighted" -v c="$coverage" 'BEGIN { printf "%.6f %.6f\n", i, (c > 0 ? w / c : 0) }'
}
