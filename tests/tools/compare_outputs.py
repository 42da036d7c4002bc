#!/usr/bin/env python3
"""Renders and converts every scene and asset of the shared data with two
rayform binaries and compares the outputs byte for byte.

usage: tests/tools/compare_outputs.py [--jobs N] [--size WxH] [--only REGEX] REF_BIN NEW_BIN OUT_DIR
       tests/tools/compare_outputs.py [--jobs N] [--size WxH] [--only REGEX] --ref-dir DIR [REF_BIN] NEW_BIN OUT_DIR

REF_BIN is a rayform binary built before a change, NEW_BIN one built after it
(each finds its plugins in ../lib/rayform beside it). The data is read from
$RAYFORM_SHARED (default: ../shared beside the repository, or beside the main
checkout from a git worktree). Writes OUT_DIR/ref (REF_BIN's outputs) and
OUT_DIR/new (NEW_BIN's), each emptied first; --ref-dir DIR instead reuses the
ref folder of an earlier run (made with the same --size) and runs NEW_BIN only
(REF_BIN, if given, is not run). --only REGEX limits the inputs to those whose
path under the data folder matches. --jobs N: runs at once (default: nproc;
each render uses every core).

The inputs: every course scene (course/*/*.txt but README.txt, the dialect
detected by rayform, at its own size: 200x200) and every .obj, .gltf and .glb
under assets/ (the Khronos samples included), in --size (default 512x512, the
renderer's own default for OBJ and glTF; 256x256 is a quicker check with a
quarter of the pixels). Per input and binary:
  info      `rayform info --json IN`
  render    plain, and again with --shadows --bounces 3 --spp 4:
            `rayform render IN -o color.png --depth MIN:MAX:depth.png
             --normals normals.png --albedo albedo.png`; the depth range is the
            one of the course's reference MANIFEST.txt where it lists the
            scene, else 0 to 4 times the diagonal of the scene's bounds (from
            REF_BIN's info)
  convert   `rayform convert IN OUT` to .glb, .gltf, .obj and .txt, OUT named
            after IN, each in its own folder (side files compared as a folder)
Every run happens in its own (empty) folder. An output is a file a run wrote,
or the run's exit status with its stdout and stderr (in which the output
folder, the data folder and the binary's path are replaced by @OUT@, @SHARED@
and "rayform"): a run that fails must fail the same way with both binaries.

Prints one line per output that differs (or exists on one side only) and the
summary "N outputs compared, N identical, N differ" after the number of runs
of each kind (and of those that failed with NEW_BIN).
Exit status: 0 when every output is identical, 1 when any differs, 2 on a
usage or setup error. Python 3 standard library only.
"""
import argparse
import concurrent.futures
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

SHADED = ["--shadows", "--bounces", "3", "--spp", "4"]
RENDER_VARIANTS = {"plain": [], "shaded": SHADED}
CONVERT_FORMATS = ["glb", "gltf", "obj", "txt"]
ASSET_SUFFIXES = (".obj", ".gltf", ".glb")
RUN_TIMEOUT_S = 900
LOG_FILES = ("exit", "stdout", "stderr")  # beside each run's out/ folder


def parse_args():
    usage = "%(prog)s [options] REF_BIN NEW_BIN OUT_DIR\n       %(prog)s [options] --ref-dir DIR [REF_BIN] NEW_BIN OUT_DIR"
    p = argparse.ArgumentParser(usage=usage, description=__doc__.split("\n\n", 2)[2],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--jobs", type=int, default=len(os.sched_getaffinity(0)), help="runs at once (default: nproc)")
    p.add_argument("--size", default="512x512", help="image size of the assets (default 512x512)")
    p.add_argument("--ref-dir", help="reuse this earlier ref folder instead of running REF_BIN")
    p.add_argument("--only", metavar="REGEX", help="only the inputs whose path under the data folder matches")
    p.add_argument("binaries_and_out", nargs="+", metavar="REF_BIN NEW_BIN OUT_DIR", help=argparse.SUPPRESS)
    a = p.parse_args()
    if len(a.binaries_and_out) != 3 and not (a.ref_dir and len(a.binaries_and_out) == 2):
        p.error("give REF_BIN NEW_BIN OUT_DIR, or --ref-dir DIR [REF_BIN] NEW_BIN OUT_DIR")
    if not re.fullmatch(r"[1-9][0-9]*x[1-9][0-9]*", a.size):
        p.error("--size takes WIDTHxHEIGHT, e.g. 256x256")
    if a.jobs < 1:
        p.error("--jobs must be at least 1")
    a.ref_bin = None if a.ref_dir else a.binaries_and_out[0]
    a.new_bin, a.out_dir = a.binaries_and_out[-2:]
    return a


def fail(message):
    print(f"compare_outputs: {message}", file=sys.stderr)
    sys.exit(2)


def default_shared():
    """../shared beside the repository, or beside the main checkout when this
    is a git worktree."""
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    candidates = [os.path.join(repo, "..", "shared")]
    git = subprocess.run(["git", "-C", repo, "rev-parse", "--path-format=absolute", "--git-common-dir"],
                         capture_output=True, text=True)
    if git.returncode == 0:
        candidates.append(os.path.join(os.path.dirname(git.stdout.strip()), "..", "shared"))
    return next((c for c in candidates if os.path.isdir(c)), candidates[0])


def find_inputs(shared):
    """The inputs as paths relative to the data folder, sorted."""
    found = []
    course = os.path.join(shared, "course")
    for dialect in sorted(os.listdir(course)):
        folder = os.path.join(course, dialect)
        if os.path.isdir(folder):
            found += [f"course/{dialect}/{n}" for n in sorted(os.listdir(folder))
                      if n.endswith(".txt") and n != "README.txt"]
    for root, dirs, files in os.walk(os.path.join(shared, "assets")):
        dirs.sort()
        found += [os.path.relpath(os.path.join(root, n), shared) for n in sorted(files) if n.endswith(ASSET_SUFFIXES)]
    return found


def manifest_depth_ranges(shared):
    """{input: "MIN:MAX"} from the course's reference/MANIFEST.txt lines
    (NAME WxH [flags...] depth MIN MAX)."""
    ranges = {}
    course = os.path.join(shared, "course")
    for dialect in os.listdir(course):
        manifest = os.path.join(course, dialect, "reference", "MANIFEST.txt")
        if not os.path.isfile(manifest):
            continue
        with open(manifest) as f:
            for line in f:
                words = line.split()
                if len(words) >= 3 and words[-3] == "depth":
                    ranges[f"course/{dialect}/{words[0]}.txt"] = f"{words[-2]}:{words[-1]}"
    return ranges


def bounds_depth_range(info_stdout):
    """0 to 4 times the diagonal of the bounds in `info --json` output (0:1
    when there are none): the scene's depths whatever the camera's distance."""
    try:
        bounds = json.loads(info_stdout)["bounds"]
        diagonal = math.dist(bounds["min"], bounds["max"])
    except (ValueError, KeyError, TypeError):
        return "0:1"
    return f"0:{4 * diagonal:.6g}" if math.isfinite(diagonal) and diagonal > 0 else "0:1"


def depth_ranges(shared, ref_root, inputs):
    """{input: "MIN:MAX"}: the course reference's range, else from the
    bounds in REF_BIN's info output."""
    ranges = manifest_depth_ranges(shared)
    for i in inputs:
        if i not in ranges:
            try:
                with open(os.path.join(ref_root, "info", i, "stdout")) as f:
                    ranges[i] = bounds_depth_range(f.read())
            except OSError:
                ranges[i] = "0:1"
    return ranges


class Run:
    """One rayform command: its id (the folder under a side's root) and its
    arguments after the binary, the input given relative to the data folder."""

    def __init__(self, kind, run_id, source, args):
        self.kind, self.id, self.source, self.args = kind, run_id, source, args


def info_runs(inputs):
    return [Run("info", f"info/{i}", i, ["info", "--json", "@SHARED@/" + i]) for i in inputs]


def render_and_convert_runs(inputs, size, depth_range):
    runs = []
    for variant, flags in RENDER_VARIANTS.items():
        for i in inputs:
            args = ["render", "@SHARED@/" + i, "-o", "color.png", "--depth", f"{depth_range[i]}:depth.png",
                    "--normals", "normals.png", "--albedo", "albedo.png"] + flags
            if not i.startswith("course/"):
                args += ["--size", size]
            runs.append(Run("render", f"render/{i}/{variant}", i, args))
    for fmt in CONVERT_FORMATS:
        for i in inputs:
            stem = os.path.splitext(os.path.basename(i))[0]
            runs.append(Run("convert", f"convert/{i}/{fmt}", i, ["convert", "@SHARED@/" + i, f"{stem}.{fmt}"]))
    return runs


def execute(binary, side_root, shared, run):
    """Runs `run` with `binary` in side_root/ID/out and writes the exit status,
    stdout and stderr (paths replaced) beside that folder."""
    folder = os.path.join(side_root, run.id)
    out = os.path.join(folder, "out")
    os.makedirs(out)
    args = [binary] + [a.replace("@SHARED@", shared) for a in run.args]
    try:
        p = subprocess.run(args, cwd=out, capture_output=True, timeout=RUN_TIMEOUT_S, stdin=subprocess.DEVNULL)
        status, stdout, stderr = str(p.returncode), p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        status, stdout, stderr = f"timeout after {RUN_TIMEOUT_S} s", e.stdout or b"", e.stderr or b""
    for name, text in zip(LOG_FILES, (status.encode() + b"\n", stdout, stderr)):
        for path, placeholder in ((side_root, "@OUT@"), (shared, "@SHARED@"), (binary, "rayform")):
            text = text.replace(os.fsencode(path), os.fsencode(placeholder))
        with open(os.path.join(folder, name), "wb") as f:
            f.write(text)
    return status != "0"


def run_all(pool, sides, shared, runs):
    """Runs every run with every (binary, root) of `sides`, the last side
    being NEW_BIN's; returns {kind: runs that failed with NEW_BIN}."""
    futures = [(r, pool.submit(execute, binary, root, shared, r)) for r in runs for binary, root in sides]
    failed = {}
    for n, (r, f) in enumerate(futures):
        failed[r.kind] = failed.get(r.kind, 0) + (f.result() and n % len(sides) == len(sides) - 1)
    return failed


def files_under(folder):
    found = set()
    for root, _, files in os.walk(folder):
        found |= {os.path.relpath(os.path.join(root, n), folder) for n in files}
    return found


def same_bytes(a, b):
    if not (os.path.isfile(a) and os.path.isfile(b)) or os.path.getsize(a) != os.path.getsize(b):
        return False
    with open(a, "rb") as fa, open(b, "rb") as fb:
        while True:
            ca, cb = fa.read(1 << 20), fb.read(1 << 20)
            if ca != cb:
                return False
            if not ca:
                return True


def lines_of(path):
    if not os.path.isfile(path):
        return ["<no file>"]
    with open(path, "rb") as f:
        return f.read().decode(errors="replace").splitlines()


def first_line_difference(a, b):
    la, lb = lines_of(a), lines_of(b)
    for n, (x, y) in enumerate(zip(la + ["<end>"], lb + ["<end>"]), 1):
        if x != y:
            return f"line {n}: ref {x[:160]!r}, new {y[:160]!r}"
    return "same lines, different line ends"


def compare_run(ref_root, new_root, run):
    """Returns (outputs compared, lines describing the differences)."""
    ref, new = os.path.join(ref_root, run.id), os.path.join(new_root, run.id)
    if not os.path.isdir(ref):
        return 1, [f"{run.id}: not in the reference folder (made with other data or an older script?)"]
    lines = []
    logs_differ = [n for n in LOG_FILES if not same_bytes(os.path.join(ref, n), os.path.join(new, n))]
    if logs_differ:
        lines.append(f"{run.id}: " + "; ".join(
            f"{n} {first_line_difference(os.path.join(ref, n), os.path.join(new, n))}" for n in logs_differ))
    ref_files, new_files = files_under(os.path.join(ref, "out")), files_under(os.path.join(new, "out"))
    for f in sorted(ref_files | new_files):
        if f not in new_files or f not in ref_files:
            lines.append(f"{run.id}/{f}: written by {'ref' if f in ref_files else 'new'} only")
        elif not same_bytes(os.path.join(ref, "out", f), os.path.join(new, "out", f)):
            lines.append(f"{run.id}/{f}: differs")
    return 1 + len(ref_files | new_files), lines


def start_side(root, settings):
    if os.path.exists(root):
        shutil.rmtree(root)
    os.makedirs(root)
    with open(os.path.join(root, "settings.json"), "w") as f:
        json.dump(settings, f, indent=1, sort_keys=True)


def main():
    a = parse_args()
    start = time.monotonic()
    shared = os.path.abspath(os.environ.get("RAYFORM_SHARED") or default_shared())
    if not os.path.isdir(os.path.join(shared, "course")) or not os.path.isdir(os.path.join(shared, "assets")):
        fail(f"no course/ and assets/ in {shared} (set RAYFORM_SHARED)")
    for b in filter(None, (a.ref_bin, a.new_bin)):
        if not os.access(b, os.X_OK):
            fail(f"{b} is not an executable")
    out_dir = os.path.abspath(a.out_dir)
    new_root = os.path.join(out_dir, "new")
    ref_root = os.path.abspath(a.ref_dir) if a.ref_dir else os.path.join(out_dir, "ref")
    settings = {"size": a.size, "render_variants": RENDER_VARIANTS, "convert_formats": CONVERT_FORMATS}
    if a.ref_dir:
        try:
            with open(os.path.join(ref_root, "settings.json")) as f:
                ref_settings = json.load(f)
        except OSError as e:
            fail(f"--ref-dir: {e}")
        if ref_settings != settings:
            fail(f"{ref_root} was made with other settings: {ref_settings}, not {settings}")
        if os.path.realpath(ref_root) == os.path.realpath(new_root):
            fail("--ref-dir is OUT_DIR/new, which this run empties")
    sides = [(os.path.abspath(a.new_bin), new_root)]
    if not a.ref_dir:
        sides.insert(0, (os.path.abspath(a.ref_bin), ref_root))
    for _, root in sides:
        start_side(root, settings)

    inputs = [i for i in find_inputs(shared) if not a.only or re.search(a.only, i)]
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        infos = info_runs(inputs)
        failed = run_all(pool, sides, shared, infos)
        # After the infos: the depth ranges come from REF_BIN's.
        others = render_and_convert_runs(inputs, a.size, depth_ranges(shared, ref_root, inputs))
        # The shaded renders of the largest files first: fewer runs left alone at the end.
        file_size = {i: os.path.getsize(os.path.join(shared, i)) for i in inputs}
        others.sort(key=lambda r: (r.id.endswith("/shaded"), file_size[r.source]), reverse=True)
        failed.update(run_all(pool, sides, shared, others))
        results = list(pool.map(lambda r: compare_run(ref_root, new_root, r), infos + others))

    for line in sorted(line for _, lines in results for line in lines):
        print("DIFFERS", line)
    runs = ", ".join(f"{sum(r.kind == k for r in infos + others)} {k}s ({failed.get(k, 0)} failed)"
                     for k in ("render", "convert", "info"))
    print(f"{runs} run with {'NEW_BIN' if a.ref_dir else 'each binary'} in {time.monotonic() - start:.0f} s;"
          f" reference: {ref_root}")
    compared, differ = sum(n for n, _ in results), sum(len(lines) for _, lines in results)
    print(f"{compared} outputs compared, {compared - differ} identical, {differ} differ")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
