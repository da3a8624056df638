#!/usr/bin/env python3
"""Writes test/data/synthetic_64x48.raw16, the committed Bumblebee-2 Format7 RAW16 test frame: a blocky
colour texture whose right view is the left one shifted 4 px to the left (disparity +4), both
GRBG-mosaicked, the left sensor in the even bytes. Deterministic (seeded); pure Python."""
import random
import sys

W, H, D, BLOCK = 64, 48, 4, 4


def main(path):
    rng = random.Random(7)
    cols = (W + D) // BLOCK + 2
    rows = H // BLOCK + 2
    texture = [[[rng.randint(30, 220) for _ in range(3)] for _ in range(cols)] for _ in range(rows)]

    def colour(x, y):  # BGR of the wide scene at column x
        return texture[y // BLOCK][x // BLOCK]

    def mosaic(x, y, offset):  # GRBG: row 0 G R, row 1 B G
        b, g, r = colour(x + offset, y)
        if y % 2 == 0:
            return g if x % 2 == 0 else r
        return b if x % 2 == 0 else g

    out = bytearray()
    for y in range(H):
        for x in range(W):
            out.append(mosaic(x, y, D))  # left: x_left = x_right + D
            out.append(mosaic(x, y, 0))  # right
    with open(path, "wb") as f:
        f.write(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "test/data/synthetic_64x48.raw16")
