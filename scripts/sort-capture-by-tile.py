#!/usr/bin/env python3
"""Writes a TRI1 capture's triangles stably sorted by the 64-pixel screen tile of their centroid.

A measuring aid (benchmarks/RESULTS.md decision 35): drawn from the sorted capture, a
tile's triangle setups lie together in memory, while each tile's single-tile triangles keep
their order, so the same depth tests run. The difference in frame time bounds what in-order
setup reads could gain.

usage: scripts/sort-capture-by-tile.py IN.tri OUT.tri
"""
import struct
import sys

TILE = 64
VERTEX_FLOATS = 8  # x, y, z, w, r, g, b, a (see engine/include/tessera/capture.hpp)
TRIANGLE_BYTES = 3 * VERTEX_FLOATS * 4


def main() -> None:
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    raw = open(sys.argv[1], "rb").read()
    if raw[:4] != b"TRI1":
        sys.exit(f"{sys.argv[1]}: not a TRI1 capture")
    width, height, count = struct.unpack_from("<III", raw, 4)
    if len(raw) != 16 + count * TRIANGLE_BYTES:
        sys.exit(f"{sys.argv[1]}: size does not match its header's {count} triangles")
    tiles_x, tiles_y = (width + TILE - 1) // TILE, (height + TILE - 1) // TILE
    keys = []
    for t in range(count):
        f = struct.unpack_from("<24f", raw, 16 + t * TRIANGLE_BYTES)
        cx = sum((f[8 * k] / f[8 * k + 3] + 1) * width / 2 for k in range(3)) / 3
        cy = sum((1 - f[8 * k + 1] / f[8 * k + 3]) * height / 2 for k in range(3)) / 3
        tx = min(max(int(cx // TILE), 0), tiles_x - 1)
        ty = min(max(int(cy // TILE), 0), tiles_y - 1)
        keys.append((ty * tiles_x + tx, t))
    keys.sort()
    out = bytearray(raw[:16])
    for _, t in keys:
        out += raw[16 + t * TRIANGLE_BYTES:16 + (t + 1) * TRIANGLE_BYTES]
    open(sys.argv[2], "wb").write(out)


if __name__ == "__main__":
    main()
