#!/usr/bin/python3
"""Prints the points of a .vtu piece of the program's output with the
values of named point fields, one point per line: x y z value..., for the
tests that check a field where the program writes it (deal.II's binary
appended-inline format: each DataArray a base64 header of uint32 block
sizes, then the base64 of the zlib-compressed blocks).

    tests/vtu_points.py FILE.vtu FIELD [FIELD...]
"""
import base64
import re
import struct
import sys
import zlib


def decode(text, kind):
    """The values of a binary DataArray's text."""
    text = "".join(text.split())
    # The header: number of blocks, block size, last block size, and the
    # compressed size of each block, as uint32.
    first = base64.b64decode(text[:8])
    n_blocks = struct.unpack("<I", first[:4])[0]
    header_length = 4 * (3 + n_blocks)
    encoded_header = 4 * ((header_length + 2) // 3)
    header = struct.unpack("<%dI" % (3 + n_blocks),
                           base64.b64decode(text[:encoded_header]))
    data = base64.b64decode(text[encoded_header:])
    raw, offset = b"", 0
    for size in header[3:]:
        raw += zlib.decompress(data[offset:offset + size])
        offset += size
    code = {"Float32": "f", "Float64": "d", "Int32": "i", "UInt8": "B"}[kind]
    return struct.unpack("<%d%s" % (len(raw) // struct.calcsize(code), code), raw)


def arrays(xml):
    found = {}
    for match in re.finditer(r'<DataArray type="(\w+)"([^>]*)>(.*?)</DataArray>', xml, re.S):
        kind, attributes, text = match.groups()
        name = re.search(r'Name="([^"]*)"', attributes)
        if 'format="binary"' in attributes:
            found[name.group(1) if name else "Points"] = decode(text, kind)
    return found


def main():
    with open(sys.argv[1]) as f:
        data = arrays(f.read())
    points = data["Points"]
    fields = [data[name] for name in sys.argv[2:]]
    for k in range(len(points) // 3):
        print(" ".join("%.9g" % v for v in points[3 * k:3 * k + 3])
              + "".join(" %.9g" % field[k] for field in fields))


if __name__ == "__main__":
    main()
