"""Reads and writes map_server maps with an 8-bit binary PGM image (enough for these tools)."""
import os
import sys


def parse_args(usage, convert):
    """(map, out_dir, number) from the command line, or exits (status 1) saying what is wrong."""
    if len(sys.argv) != 4:
        raise SystemExit("usage: " + usage)
    try:
        number = convert(sys.argv[3])
    except ValueError:
        raise SystemExit("%s: not a number: %s\nusage: %s" % (sys.argv[0], sys.argv[3], usage))
    if not os.path.isdir(sys.argv[2]):
        raise SystemExit(sys.argv[2] + ": no such directory")
    return sys.argv[1], sys.argv[2], number


def load_map(yaml_path):
    """Returns (metadata dict of strings, width, height, pixel bytes, top row first)."""
    meta = {}
    try:
        return _load(yaml_path, meta)
    except (OSError, KeyError, ValueError, IndexError) as error:
        raise SystemExit("%s: cannot read the map: %s" % (yaml_path, error))


def _load(yaml_path, meta):
    with open(yaml_path) as f:
        for line in f:
            if ":" in line:
                key, value = line.split(":", 1)
                meta[key.strip()] = value.split("#")[0].strip()
    with open(os.path.join(os.path.dirname(yaml_path), meta["image"]), "rb") as f:
        data = f.read()
    fields, i = [], 0
    while len(fields) < 4:  # magic, width, height, maxval
        while data[i:i + 1].isspace():
            i += 1
        if data[i:i + 1] == b"#":
            while data[i:i + 1] != b"\n":
                i += 1
            continue
        j = i
        while not data[j:j + 1].isspace():
            j += 1
        fields.append(data[i:j])
        i = j
    if fields[0] != b"P5" or int(fields[3]) > 255:
        raise SystemExit(yaml_path + ": only 8-bit binary PGM images are supported")
    width, height = int(fields[1]), int(fields[2])
    return meta, width, height, data[i + 1:i + 1 + width * height]


def save_map(out_dir, name, meta, width, height, pixels, resolution):
    with open(os.path.join(out_dir, name + ".pgm"), "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (width, height) + bytes(pixels))
    with open(os.path.join(out_dir, name + ".yaml"), "w") as f:
        f.write("image: %s.pgm\nresolution: %s\norigin: [0.0, 0.0, 0.0]\nnegate: %s\n"
                "occupied_thresh: %s\nfree_thresh: %s\n"
                % (name, resolution, meta.get("negate", "0"), meta["occupied_thresh"],
                   meta["free_thresh"]))
