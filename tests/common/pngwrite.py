"""Shared by the Python end-to-end tests: writes greyscale PNGs with the standard library only (zlib +
struct), so tests can make height-map images for `pacifica replay --height-map` without OpenImageIO.
PNG layout per the PNG specification (W3C, 2nd edition): signature, IHDR, one IDAT of filter-0 scanlines,
IEND; each chunk is length, type, data, CRC-32 of type + data."""

import struct
import zlib


def _chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def write_gray_png(path, width, height, value, bit_depth=16):
    """Writes a width x height greyscale PNG; value(x, row) in [0, 1] (row 0 = top) is quantised to
    bit_depth (8 or 16) bits."""
    peak = (1 << bit_depth) - 1
    fmt = ">%dH" % width if bit_depth == 16 else "%dB" % width
    raw = b"".join(b"\x00" + struct.pack(fmt, *(round(min(max(value(x, row), 0.0), 1.0) * peak)
                                                for x in range(width))) for row in range(height))
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, 0, 0, 0, 0)  # greyscale, deflate, no interlace
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", ihdr) + _chunk(b"IDAT", zlib.compress(raw)) +
                _chunk(b"IEND", b""))
    return path
