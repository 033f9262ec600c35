#!/usr/bin/env python3
"""Hash of the node positions in an invfree OBJ file, as Determinism.StoredRunHash computes
it in C++: FNV-1a 64 over x0 y0 x1 y1 ... packed as little-endian doubles. invfree writes
17 significant digits, so parsing the text gives back the exact doubles."""
import struct
import sys

FNV_OFFSET, FNV_PRIME = 0xCBF29CE484222325, 0x100000001B3


def fnv1a64(data: bytes) -> int:
    h = FNV_OFFSET
    for b in data:
        h = ((h ^ b) * FNV_PRIME) & 0xFFFFFFFFFFFFFFFF
    return h


def main() -> None:
    values = []
    with open(sys.argv[1], encoding="ascii") as f:
        for line in f:
            if line.startswith("v "):
                _, x, y, _z = line.split()
                values += [float(x), float(y)]
    print(f"0x{fnv1a64(struct.pack('<%dd' % len(values), *values)):016x}  ({len(values) // 2} nodes)")


if __name__ == "__main__":
    main()
