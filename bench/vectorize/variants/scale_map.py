#!/usr/bin/env python3
"""Writes a map_server map at K times finer cells: every cell becomes K x K cells, so walls are K
times as many cells thick, as in a map built at a finer resolution.

Usage: scale_map.py MAP.yaml OUT_DIR K   (python3, standard library only; 8-bit P5 PGM maps)
The output is named <map>_up<K>.yaml / .pgm (docs/results.md, "The general case").
"""
import os

from map_file import load_map, parse_args, save_map


def main():
    source, out_dir, k = parse_args("scale_map.py MAP.yaml OUT_DIR K", int)
    if k < 1:
        raise SystemExit("K must be >= 1, got %d" % k)
    meta, width, height, pixels = load_map(source)
    out_w, out_h = width * k, height * k
    out = bytearray(out_w * out_h)
    for y in range(out_h):
        row = pixels[(y // k) * width:(y // k + 1) * width]
        out[y * out_w:(y + 1) * out_w] = bytes(v for v in row for _ in range(k))
    name = os.path.basename(source)[:-len(".yaml")] + "_up%d" % k
    save_map(out_dir, name, meta, out_w, out_h, out, float(meta["resolution"]) / k)


if __name__ == "__main__":
    main()
