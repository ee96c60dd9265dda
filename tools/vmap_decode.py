#!/usr/bin/env python3
"""Decodes a fleetmap .vmap file (format fleetmap-vmap/5, tile layout 5) into JSON.

Written from docs/file-formats.md ("Vector maps: .vmap", "CDR in brief", "VectorTile, field by
field") and the .idl files in idl/fleetmap_msgs/msg/, independently of the C++ codec: it is the
proof (issue 17) that a client without fleetmap's code or a DDS stack can read the plain layout.
Python 3 standard library only; a tile whose geometry is zstd-compressed (compression 1) is
decompressed by the `zstd` command line tool (Debian package zstd).

Output (stdout, or the file given with -o):
  {"format", "frame_id", "tile_size", "epsilon", "resolution",
   "tiles": [{"tile_x", "tile_y", "revision", "quantum", "lattice_x", "lattice_y",
              "obstacles": [{"closed", "half_width", "points": [[x, y], ...]}, ...],
              "free_space": [{"outer": [[x, y], ...], "holes": [[[x, y], ...], ...]}, ...]}]}
Coordinates and half widths are in metres in the map's frame (frame_id). Obstacles come in the
order of the geometry: the polylines, then the point obstacles (each a one-point, open obstacle).
Float32 fields are printed as the float64 they widen to.

It checks what the page says a reader checks (the CDR lengths and every count against the bytes
left, layout_version 5, compression 0 or 1, the tile size, the geometry's lattice, varints of
at most 64 bits, vertices within a 16th of the tile side of their tile, closed polylines of >= 3
vertices, rings and polygons not empty, the string used up exactly, the zstd content size at most
4 MiB and stated before inflating, no duplicate tile), and that strings end with their NUL and
nothing follows the last tile.

Exit status: 0 decoded; 1 could not decode for a reason outside the file (zstd not installed,
--no-zstd and a compressed tile, output not writable); 2 the file is unreadable or malformed
(the message names the file and what is wrong); 3 a bug in this decoder.
"""

import argparse
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile

FORMAT = "fleetmap-vmap/5"
FORMAT_PREFIX = "fleetmap-vmap/"
LAYOUT_VERSION = 5
HALF_WIDTH_STEPS_PER_EPSILON = 254
MAX_FILE_BYTES = 1 << 30  # the docs' limit: a larger file is refused before it is read
MAX_GEOMETRY_BYTES = 4 << 20  # the content size a zstd frame of geometry may state
MAX_VARINT_BYTES = 10  # a varint holds at most 64 bits
MAX_STEPS_PER_SIDE = 1 << 20  # tile_size / quantum must be 1 to 2^20
VERTEX_SLACK = 1 / 16  # a vertex lies within a 16th of the tile side of its tile
ZSTD_MAGIC = b"\x28\xb5\x2f\xfd"


class Malformed(Exception):
    """The input is not a valid .vmap; the message says what is wrong (exit 2)."""


class CannotDecode(Exception):
    """The input may be fine but this run cannot decode it (exit 1)."""


class CdrReader:
    """Plain CDR (XCDR1) of @final structs: every primitive aligned to its size, with offsets
    counted from the first byte after the 4-byte encapsulation header."""

    def __init__(self, data, origin, little_endian):
        self.data = data
        self.origin = origin  # index of offset 0 (after the encapsulation header)
        self.pos = origin
        self.order = "<" if little_endian else ">"

    def offset(self):
        return self.pos - self.origin

    def remaining(self):
        return len(self.data) - self.pos

    def _take(self, count, what):
        if count > self.remaining():
            raise Malformed(
                f"{what} at offset {self.offset()} needs {count} bytes but only "
                f"{self.remaining()} are left (the file is truncated or corrupt)")
        start = self.pos
        self.pos += count
        return self.data[start:self.pos]

    def _align(self, size, what):
        padding = -self.offset() % size
        self._take(padding, f"padding before {what}")

    def _primitive(self, code, size, what):
        self._align(size, what)
        return struct.unpack(self.order + code, self._take(size, what))[0]

    def uint8(self, what):
        return self._primitive("B", 1, what)

    def int32(self, what):
        return self._primitive("i", 4, what)

    def uint32(self, what):
        return self._primitive("I", 4, what)

    def float32(self, what):
        return self._primitive("f", 4, what)  # widened to float64 by struct

    def float64(self, what):
        return self._primitive("d", 8, what)

    def string(self, what):
        length = self.uint32(f"{what} length")
        if length == 0:
            raise Malformed(f"{what} has length 0 (a CDR string's length counts its NUL)")
        raw = self._take(length, what)
        if raw[-1] != 0:
            raise Malformed(f"{what} does not end with a NUL")
        text = raw[:-1]
        if 0 in text:
            raise Malformed(f"{what} has a NUL inside it")
        try:
            return text.decode("utf-8")
        except UnicodeDecodeError:
            raise Malformed(f"{what} is not UTF-8") from None

    def sequence_length(self, what, min_element_bytes):
        count = self.uint32(f"{what} count")
        if count * min_element_bytes > self.remaining():
            raise Malformed(
                f"{what} has {count} elements, more than the {self.remaining()} bytes left "
                "can hold (the file is truncated or corrupt)")
        return count

    def octets(self, what):
        count = self.sequence_length(what, 1)
        return self._take(count, what)


class GeometryReader:
    """The geometry byte string: unsigned LEB128 varints, zigzag varints and plain bytes."""

    def __init__(self, data):
        self.data = data
        self.pos = 0

    def remaining(self):
        return len(self.data) - self.pos

    def byte(self, what):
        if self.pos >= len(self.data):
            raise Malformed(f"geometry ends at byte {self.pos} where {what} was expected")
        value = self.data[self.pos]
        self.pos += 1
        return value

    def float64(self, what):
        """Eight bytes, an IEEE 754 binary64 value, little-endian."""
        if self.remaining() < 8:
            raise Malformed(f"geometry ends at byte {len(self.data)} inside {what}")
        value = struct.unpack_from("<d", self.data, self.pos)[0]
        self.pos += 8
        return value

    def varint(self, what):
        start = self.pos
        value = 0
        for index in range(MAX_VARINT_BYTES):
            if self.pos >= len(self.data):
                raise Malformed(f"geometry ends inside {what} (a varint from byte {start})")
            b = self.data[self.pos]
            self.pos += 1
            value |= (b & 0x7F) << (7 * index)
            if not b & 0x80:
                if value >= 1 << 64:
                    break
                return value
        raise Malformed(f"{what} at geometry byte {start} is a varint of more than 64 bits")

    def zigzag(self, what):
        z = self.varint(what)
        return (z >> 1) ^ -(z & 1)

    def count(self, what, min_bytes_each):
        """A varint count whose elements take at least min_bytes_each bytes each."""
        start = self.pos
        n = self.varint(what)
        if n * min_bytes_each > self.remaining():
            raise Malformed(
                f"{what} at geometry byte {start} is {n}, more than the "
                f"{self.remaining()} bytes left can hold")
        return n


def finite_positive(value, what):
    if not (math.isfinite(value) and value > 0):
        raise Malformed(f"{what} is {value!r}, not a finite number > 0")
    return value


def zstd_content_size(frame):
    """The content size a zstd frame's header states (RFC 8878, 3.1.1), or None if it states
    none; raises Malformed if the bytes do not start with a zstd frame header."""
    if len(frame) < 5 or frame[:4] != ZSTD_MAGIC:
        raise Malformed("its geometry is not a zstd frame (no zstd magic number)")
    descriptor = frame[4]
    fcs_flag, single_segment = descriptor >> 6, (descriptor >> 5) & 1
    dictionary_flag = descriptor & 3
    if descriptor & 0x08:
        raise Malformed("its geometry is not a valid zstd frame (reserved header bit set)")
    position = 5 + (0 if single_segment else 1) + (0, 1, 2, 4)[dictionary_flag]
    fcs_bytes = (1 if single_segment else 0, 2, 4, 8)[fcs_flag]
    if fcs_bytes == 0:
        return None
    if len(frame) < position + fcs_bytes:
        raise Malformed("its geometry's zstd frame header is cut off")
    size = int.from_bytes(frame[position:position + fcs_bytes], "little")
    return size + 256 if fcs_bytes == 2 else size


def zstd_decompress(frame):
    """The string a zstd frame holds, checked against the content size its header states (which
    must be there and at most MAX_GEOMETRY_BYTES) before anything is inflated."""
    declared = zstd_content_size(frame)
    if declared is None:
        raise Malformed("its geometry is a zstd frame that does not state its content size")
    if declared > MAX_GEOMETRY_BYTES:
        raise Malformed(f"its geometry's zstd frame states {declared} bytes, more than the "
                        f"{MAX_GEOMETRY_BYTES} allowed")
    zstd = shutil.which("zstd")
    if zstd is None:
        raise CannotDecode("its geometry is zstd-compressed and the zstd command is not "
                           "installed (Debian: apt-get install zstd)")
    with tempfile.TemporaryFile() as source:
        source.write(frame)
        source.seek(0)
        with subprocess.Popen([zstd, "-dc", "-q"], stdin=source, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE) as child:
            # One byte more than stated is enough to tell a lying frame: stop reading there.
            content = child.stdout.read(declared + 1)
            if len(content) > declared:
                child.kill()
            _, errors = child.communicate()
            status = child.wait()
    if len(content) > declared:
        raise Malformed(f"its geometry's zstd frame holds more than the {declared} bytes it "
                        "states")
    if status != 0:
        reason = errors.decode("utf-8", "replace").strip() or f"zstd exit status {status}"
        raise Malformed(f"its geometry is not a valid zstd frame ({reason})")
    if len(content) != declared:
        raise Malformed(f"its geometry's zstd frame holds {len(content)} bytes, not the "
                        f"{declared} it states")
    return content


def read_lattice(reader, tile):
    """The lattice at the start of the geometry: the quantum, then a flag byte (1: the origin's
    two float64 follow; 0: the origin is (0, 0))."""
    quantum = finite_positive(reader.float64("the lattice quantum"), "the lattice quantum")
    steps_per_side = tile["_tile_size"] / quantum
    if not 1 <= steps_per_side <= MAX_STEPS_PER_SIDE:
        raise Malformed(f"quantum {quantum!r} m makes {steps_per_side!r} steps of the tile side, "
                        f"not 1 to {MAX_STEPS_PER_SIDE}")
    flag = reader.byte("the lattice origin flag")
    if flag not in (0, 1):
        raise Malformed(f"the lattice origin flag is {flag}, neither 0 nor 1")
    origin = [0.0, 0.0]
    if flag == 1:
        origin = [reader.float64("the lattice origin x"), reader.float64("the lattice origin y")]
        for value in origin:
            if not 0.0 <= value < quantum:  # also false for NaN
                raise Malformed(f"the lattice origin {value!r} is not in [0, quantum {quantum!r})")
    tile["quantum"], tile["lattice_x"], tile["lattice_y"] = quantum, origin[0], origin[1]
    return quantum, origin[0], origin[1]


def decode_geometry(geometry, tile):
    """The lattice, obstacles and free polygons of one tile's (plain) geometry string."""
    reader = GeometryReader(geometry)
    quantum, lattice_x, lattice_y = read_lattice(reader, tile)
    tile_size = tile["_tile_size"]
    slack = VERTEX_SLACK * tile_size
    x_range = (tile["tile_x"] * tile_size - slack, (tile["tile_x"] + 1) * tile_size + slack)
    y_range = (tile["tile_y"] * tile_size - slack, (tile["tile_y"] + 1) * tile_size + slack)
    epsilon = tile["_epsilon"]  # the tile's float32, widened
    i = j = 0  # lattice coordinates of the previous vertex; the first one steps from (0, 0)

    def half_width(steps):
        return steps * (epsilon / HALF_WIDTH_STEPS_PER_EPSILON)

    def vertex(what):
        nonlocal i, j
        i += reader.zigzag(f"{what} dx")
        j += reader.zigzag(f"{what} dy")
        try:
            point = [i * quantum + lattice_x, j * quantum + lattice_y]
        except OverflowError:
            point = [math.inf, math.inf]
        if not (x_range[0] <= point[0] <= x_range[1] and y_range[0] <= point[1] <= y_range[1]):
            raise Malformed(f"{what} (ending at geometry byte {reader.pos}) lies at ({i}, {j}) "
                            "lattice steps, farther than a 16th of the tile side outside its tile")
        return point

    obstacles = []
    # A polyline takes at least 1 (h) + 1 (width) + 2 vertices of 2 bytes each.
    for k in range(reader.count("the number of obstacle polylines", 6)):
        h = reader.varint(f"polyline {k}'s size")
        n, closed = (h >> 1) + 2, bool(h & 1)
        if closed and n < 3:
            raise Malformed(f"polyline {k} is closed with {n} vertices (a closed one has >= 3)")
        steps = reader.byte(f"polyline {k}'s half width")
        if n * 2 > reader.remaining():
            raise Malformed(f"polyline {k} has {n} vertices, more than the "
                            f"{reader.remaining()} bytes left can hold")
        points = [vertex(f"polyline {k} vertex {v}") for v in range(n)]
        obstacles.append({"closed": closed, "half_width": half_width(steps), "points": points})
    for k in range(reader.count("the number of point obstacles", 3)):
        steps = reader.byte(f"point obstacle {k}'s half width")
        obstacles.append({"closed": False, "half_width": half_width(steps),
                          "points": [vertex(f"point obstacle {k}")]})
    free_space = []
    # A polygon takes at least 1 (R) + 1 (m) + one vertex of 2 bytes.
    for k in range(reader.count("the number of free polygons", 4)):
        ring_count = reader.count(f"free polygon {k}'s number of rings", 3)
        if ring_count < 1:
            raise Malformed(f"free polygon {k} has no rings (at least the outer one is needed)")
        rings = []
        for r in range(ring_count):
            m = reader.count(f"free polygon {k} ring {r}'s number of vertices", 2)
            if m < 1:
                raise Malformed(f"free polygon {k} ring {r} has no vertices")
            rings.append([vertex(f"free polygon {k} ring {r} vertex {v}") for v in range(m)])
        free_space.append({"outer": rings[0], "holes": rings[1:]})
    if reader.remaining() != 0:
        raise Malformed(
            f"the geometry has {reader.remaining()} bytes left over after its last free polygon "
            f"(byte {reader.pos} of {len(geometry)})")
    return obstacles, free_space


def decode_tile(cdr, index, allow_zstd, tile_size):
    robot_id = cdr.string(f"tile {index} robot_id")
    del robot_id  # empty in .vmap files; not part of the output
    tile_x = cdr.int32(f"tile {index} tile_x")
    tile_y = cdr.int32(f"tile {index} tile_y")
    name = f"tile {index} ({tile_x}, {tile_y})"
    cdr.int32(f"{name} stamp.sec")
    cdr.uint32(f"{name} stamp.nanosec")
    layout = cdr.uint8(f"{name} layout_version")
    if layout != LAYOUT_VERSION:
        raise Malformed(f"{name}: layout_version is {layout}, this decoder reads "
                        f"{LAYOUT_VERSION}: the tile comes from another fleetmap version")
    compression = cdr.uint8(f"{name} compression")
    if compression not in (0, 1):
        raise Malformed(f"{name}: compression is {compression}, not 0 (plain) or 1 (zstd)")
    revision = cdr.uint32(f"{name} revision")
    tile_size_mm = cdr.uint32(f"{name} tile_size_mm")
    if tile_size_mm / 1000 != tile_size:
        raise Malformed(f"{name}: tile_size_mm is {tile_size_mm}, but the map's tile_size is "
                        f"{tile_size!r} m (the same for every tile)")
    epsilon = finite_positive(cdr.float32(f"{name} epsilon"), f"{name} epsilon")
    finite_positive(cdr.float32(f"{name} resolution"), f"{name} resolution")
    geometry = cdr.octets(f"{name} geometry")
    tile = {"tile_x": tile_x, "tile_y": tile_y, "revision": revision, "quantum": None,
            "lattice_x": None, "lattice_y": None, "_epsilon": epsilon,
            "_tile_size": tile_size_mm / 1000}
    try:
        if compression == 1:
            if not allow_zstd:
                raise CannotDecode("its geometry is zstd-compressed (compression 1) and "
                                   "--no-zstd was given")
            geometry = zstd_decompress(geometry)
        tile["obstacles"], tile["free_space"] = decode_geometry(geometry, tile)
    except Malformed as error:
        raise Malformed(f"{name}: {error}") from None
    except CannotDecode as error:
        raise CannotDecode(f"{name}: {error}") from None
    del tile["_epsilon"], tile["_tile_size"]
    return tile


def decode_vmap(data, allow_zstd=True):
    if len(data) < 4:
        raise Malformed(f"{len(data)} bytes, too short for the 4-byte CDR encapsulation header")
    kind = data[0:2]
    if kind == b"\x00\x01":
        little_endian = True
    elif kind == b"\x00\x00":
        little_endian = False
    else:
        raise Malformed(f"encapsulation {data[0]:02x} {data[1]:02x} is not plain CDR "
                        "(00 00 big-endian or 00 01 little-endian)")
    cdr = CdrReader(data, 4, little_endian)
    # The format string first and on its own, so a file of another version is named as such.
    fmt = cdr.string("format")
    if fmt != FORMAT:
        if fmt.startswith(FORMAT_PREFIX):
            raise Malformed(f"format {fmt} is another version of the .vmap format; this decoder "
                            f"reads {FORMAT} only")
        raise Malformed(f"format is {fmt!r}, not {FORMAT!r}: not a fleetmap vector map")
    out = {"format": fmt}
    out["frame_id"] = cdr.string("frame_id")
    out["tile_size"] = finite_positive(cdr.float64("tile_size"), "tile_size")
    out["epsilon"] = cdr.float32("epsilon")
    if not (math.isfinite(out["epsilon"]) and out["epsilon"] >= 0):  # 0 in a map without tiles
        raise Malformed(f"epsilon is {out['epsilon']!r}, not a finite number >= 0")
    out["resolution"] = finite_positive(cdr.float32("resolution"), "resolution")
    # A tile takes at least 4 (robot_id length) + 1 (its NUL) + ... > 8 bytes.
    tile_count = cdr.sequence_length("tiles", 8)
    tiles, seen = [], set()
    for index in range(tile_count):
        tile = decode_tile(cdr, index, allow_zstd, out["tile_size"])
        key = (tile["tile_x"], tile["tile_y"])
        if key in seen:
            raise Malformed(f"tile {index} ({key[0]}, {key[1]}) appears twice")
        seen.add(key)
        tiles.append(tile)
    out["tiles"] = tiles
    if cdr.remaining() != 0:
        raise Malformed(f"{cdr.remaining()} bytes left over after the last tile "
                        f"(offset {cdr.offset()})")
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Decode a fleetmap .vmap file (fleetmap-vmap/5) into JSON, from "
                    "docs/file-formats.md alone (no fleetmap code, no DDS stack).",
        epilog="Exit status: 0 decoded; 1 cannot decode here (zstd missing, --no-zstd with a "
               "compressed tile, output not writable); 2 the file is unreadable or malformed; "
               "3 a bug in this decoder.")
    parser.add_argument("file", metavar="FILE", help="the .vmap file")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write the JSON to OUT instead of stdout")
    parser.add_argument("--no-zstd", action="store_true",
                        help="do not run the zstd tool: refuse tiles with compressed geometry")
    parser.add_argument("--indent", type=int, default=None, metavar="N",
                        help="indent the JSON by N spaces (default: one line)")
    args = parser.parse_args(argv)
    prog = os.path.basename(sys.argv[0]) if argv is None else "vmap_decode.py"

    try:
        size = os.path.getsize(args.file)
        if size > MAX_FILE_BYTES:
            raise Malformed(f"{size} bytes, more than the {MAX_FILE_BYTES} a .vmap may have")
        with open(args.file, "rb") as source:
            data = source.read()
        decoded = decode_vmap(data, allow_zstd=not args.no_zstd)
    except OSError as error:
        print(f"{prog}: {args.file}: cannot read: {error.strerror or error}", file=sys.stderr)
        return 2
    except Malformed as error:
        print(f"{prog}: {args.file}: {error}", file=sys.stderr)
        return 2
    except CannotDecode as error:
        print(f"{prog}: {args.file}: {error}", file=sys.stderr)
        return 1
    except Exception as error:  # a bug here, not in the file: say so without a traceback
        print(f"{prog}: {args.file}: internal error of this decoder ({type(error).__name__}: "
              f"{error}); please report it with the file", file=sys.stderr)
        return 3

    text = json.dumps(decoded, indent=args.indent, allow_nan=False) + "\n"
    if args.output is None:
        sys.stdout.write(text)
        return 0
    try:
        with open(args.output, "w", encoding="utf-8") as sink:
            sink.write(text)
    except OSError as error:
        print(f"{prog}: {args.output}: cannot write: {error.strerror or error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
