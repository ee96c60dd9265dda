#!/usr/bin/env python3
"""Writes a map_server map rotated by DEG degrees about its centre (nearest cell, unknown outside).

Usage: rotate_map.py MAP.yaml OUT_DIR DEG   (python3, standard library only; 8-bit P5 PGM maps)
Used to test fleetmap on walls at angles the shared maps do not have (docs/results.md, "The general
case"). The output is named <map>_rot<DEG>.yaml / .pgm.
"""
import math
import os

from map_file import load_map, parse_args, save_map


def main():
    source, out_dir, degrees = parse_args("rotate_map.py MAP.yaml OUT_DIR DEG", float)
    meta, width, height, pixels = load_map(source)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    out_w = int(abs(width * c) + abs(height * s)) + 2
    out_h = int(abs(width * s) + abs(height * c)) + 2
    out = bytearray([205]) * (out_w * out_h)
    for y in range(out_h):
        dy = y + 0.5 - out_h / 2
        for x in range(out_w):
            dx = x + 0.5 - out_w / 2
            sx = math.floor(c * dx + s * dy + width / 2)
            sy = math.floor(-s * dx + c * dy + height / 2)
            if 0 <= sx < width and 0 <= sy < height:
                out[y * out_w + x] = pixels[sy * width + sx]
    name = os.path.basename(source)[:-len(".yaml")] + "_rot%d" % int(degrees)
    save_map(out_dir, name, meta, out_w, out_h, out, meta["resolution"])


if __name__ == "__main__":
    main()
