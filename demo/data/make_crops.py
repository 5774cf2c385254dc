#!/usr/bin/env python3
"""Cuts the small crops bundled in demo/data from the real data sets in ../shared/data.

Run from anywhere: python3 demo/data/make_crops.py. Needs the zstd command.
The crops are committed; this script documents exactly how they were made
(see SOURCES.md for the origin and licence of each data set).
"""
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data"))

# (output name, source file, source dims (x, y, z), sample bytes, crop origin, crop size)
CROPS = [
    ("mt_fuji_summit_128x128_int16le.raw",
     "terrain/srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", (1201, 1201, 1), 2,
     (809, 703, 0), (128, 128, 1)),
    ("mt_st_helens_128x128_int16le.raw",
     "terrain/mt_st_helens_317x460_int16le.raw.zst", (317, 460, 1), 2,
     (94, 166, 0), (128, 128, 1)),
    ("ct_head_64x64x32_uint8.raw",
     "volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst", (256, 256, 99), 1,
     (96, 96, 40), (64, 64, 32)),
    ("ct_headsq_16x16x8_uint16le.raw",
     "volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst", (64, 64, 93), 2,
     (24, 24, 40), (16, 16, 8)),
]


# Whole small models, copied as they are.
COPIES = [("cow_viewpoint_2903v_5804tri.obj", "surface/cow_viewpoint_2903v_5804tri.obj")]


def main():
    for name, source in COPIES:
        shutil.copyfile(os.path.join(SHARED, source), os.path.join(HERE, name))
        print(f"{name}: copied")
    for name, source, dims, size, origin, crop in CROPS:
        data = subprocess.run(["zstd", "-dc", os.path.join(SHARED, source)], check=True,
                              capture_output=True).stdout
        if len(data) != dims[0] * dims[1] * dims[2] * size:
            sys.exit(f"{source}: unexpected size {len(data)}")
        out = bytearray()
        for z in range(origin[2], origin[2] + crop[2]):
            for y in range(origin[1], origin[1] + crop[1]):
                start = ((z * dims[1] + y) * dims[0] + origin[0]) * size
                out += data[start:start + crop[0] * size]
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(out)
        print(f"{name}: {len(out)} bytes")


if __name__ == "__main__":
    main()
