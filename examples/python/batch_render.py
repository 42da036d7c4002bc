#!/usr/bin/env python3
"""Renders every model of a folder (.glb, .gltf, .obj, .txt, searched
recursively) into PNG thumbnails with a thread pool: rayform releases the
GIL while it renders, so the threads render at once. A progress bar with
tqdm where it is installed, else one line.

  PYTHONPATH=build/python python3 examples/python/batch_render.py models/ thumbs/ --threads 2
"""
import argparse
import concurrent.futures
import pathlib
import sys

import rayform

try:
    from tqdm import tqdm
except ImportError:
    tqdm = None

MODELS = {".glb", ".gltf", ".obj", ".txt"}


def render_one(model, folder, out_dir, size):
    # models/cars/a.glb -> cars_a_glb.png: models of one name in other folders or formats stay apart.
    out = out_dir / ("_".join(model.relative_to(folder).with_suffix("").parts) + "_" + model.suffix[1:] + ".png")
    # One prepare per model (as a program rendering several views would);
    # each render uses one thread, the pool provides the parallelism.
    prepared = rayform.prepare(model)
    r = prepared.render(size=(size, size), color=False, color8=True, threads=1)
    rayform.write_image(out, r["color8"])
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("folder", type=pathlib.Path)
    p.add_argument("out", type=pathlib.Path)
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--threads", type=int, default=2)
    a = p.parse_args()
    models = sorted(f for f in a.folder.rglob("*") if f.suffix.lower() in MODELS)
    a.out.mkdir(parents=True, exist_ok=True)
    failed = 0
    bar = tqdm(total=len(models), unit="model") if tqdm else None
    with concurrent.futures.ThreadPoolExecutor(a.threads) as pool:
        futures = {pool.submit(render_one, m, a.folder, a.out, a.size): m for m in models}
        for done, f in enumerate(concurrent.futures.as_completed(futures), 1):
            try:
                f.result()
            except rayform.Error as e:  # one line naming the file; the others go on
                failed += 1
                print(f"error: {e}", file=sys.stderr)
            if bar:
                bar.update(1)
            else:
                print(f"\r{done}/{len(models)} models", end="", file=sys.stderr, flush=True)
    if bar:
        bar.close()
    else:
        print(file=sys.stderr)
    print(f"rendered {len(models) - failed} of {len(models)} models into {a.out}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
