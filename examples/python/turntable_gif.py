#!/usr/bin/env python3
"""A turntable of a model into an animated GIF: one prepare, then one render
per frame around the model (the meshes' BVHs are built once).

  PYTHONPATH=build/python python3 examples/python/turntable_gif.py model.glb turntable.gif --frames 36
"""
import argparse

import rayform
from PIL import Image


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("model", help="a .glb, .gltf, .obj or course .txt file")
    p.add_argument("gif", help="the GIF to write")
    p.add_argument("--frames", type=int, default=36)
    p.add_argument("--size", type=int, default=256, help="width and height in pixels")
    p.add_argument("--elevation", type=float, default=20.0, help="degrees above the horizontal")
    p.add_argument("--spp", type=int, default=4)
    a = p.parse_args()
    prepared = rayform.prepare(a.model)
    for note in prepared.scene.warnings:
        print("warning:", note)
    frames = []
    for k in range(a.frames):
        r = prepared.render(size=(a.size, a.size), orbit=(360.0 * k / a.frames, a.elevation), spp=a.spp,
                            color=False, color8=True)
        frames.append(Image.fromarray(r["color8"]))
    frames[0].save(a.gif, save_all=True, append_images=frames[1:], duration=1000 // 25, loop=0)
    print(f"wrote {a.gif}: {a.frames} frames of {a.size}x{a.size}")


if __name__ == "__main__":
    main()
