"""Tiled streams (spec 11) and regions (11.5, 8.1 R8.1-3) from Python, against
the CLI's 'mrsv encode --tile', 'mrsv decode' and 'mrsv mesh --region'."""
import subprocess

import numpy as np
import pytest

import mrsv
from conftest import cli


def run(*args):
    subprocess.run([str(cli()), *map(str, args)], check=True, capture_output=True)


@pytest.fixture(scope="module")
def tiled_terrain(tmp_path_factory, st_helens):
    """St Helens in 32 x 32 tiles (16 tiles), lossless, with georeferencing."""
    path = tmp_path_factory.mktemp("tiles") / "dem.mrsv"
    mrsv.encode(st_helens, path, tile=32, threads=2, spacing=(30, 30), origin=(1000, 2000))
    return path


@pytest.fixture(scope="module")
def tiled_head(tmp_path_factory, ct_head):
    """The CT head (64 x 64 x 32) in 16 x 16 x 8 bricks, within 2."""
    path = tmp_path_factory.mktemp("tiles") / "head.mrsv"
    mrsv.encode(ct_head, path, tile=(16, 16, 8), max_error=2)
    return path


def test_tiled_lossless_round_trip(tiled_terrain, st_helens, tiled_head, ct_head):
    samples, info = mrsv.decode(tiled_terrain)
    assert np.array_equal(samples, st_helens)
    assert info["coding"] == "tiled" and info["tile_size"] == (32, 32) and info["tiles_total"] == 16
    assert info["complete"] and info["bytes_used"] == info["bytes"] == tiled_terrain.stat().st_size
    assert info["spacing"] == (30.0, 30.0) and info["origin"] == (1000.0, 2000.0)
    head, info = mrsv.decode(tiled_head, threads=1)
    assert head.shape == ct_head.shape and np.abs(head.astype(int) - ct_head).max() <= 2
    assert info["tile_size"] == (16, 16, 8) and info["tiles_total"] == 4 * 4 * 4


def test_tiled_encode_is_the_cli_stream(st_helens, tmp_path):
    """Tiles of other sizes per axis (x, y order), lossy: the same bytes as
    'mrsv encode --tile 48,32' and the same samples as 'mrsv decode'."""
    raw = tmp_path / "dem.raw"
    st_helens.astype("<i2").tofile(raw)
    run("encode", "--quiet", "--dims", "128,128", "--type", "int16", "--tile", "48,32", "--max-error", "3",
        "--threads", "2", raw, tmp_path / "cli.mrsv")
    report = mrsv.encode(st_helens, tmp_path / "py.mrsv", tile=(48, 32), max_error=3, threads=1)
    assert (tmp_path / "py.mrsv").read_bytes() == (tmp_path / "cli.mrsv").read_bytes()
    assert report["tile_size"] == (48, 32) and report["max_abs_error"] <= 3
    run("decode", "--quiet", tmp_path / "py.mrsv", tmp_path / "out.raw")
    samples, info = mrsv.decode(tmp_path / "py.mrsv")
    assert np.array_equal(samples, np.fromfile(tmp_path / "out.raw", "<i2").reshape(128, 128))
    assert info["tiles_total"] == 3 * 4 and np.abs(samples.astype(int) - st_helens).max() <= 3


def test_precinct_encode_is_the_cli_stream(st_helens, tmp_path):
    """Precincts (spec 5.7.6): the same bytes as 'mrsv encode --precinct 32',
    lossless; a wrong size is a ValueError."""
    raw = tmp_path / "dem.raw"
    st_helens.astype("<i2").tofile(raw)
    run("encode", "--quiet", "--dims", "128,128", "--type", "int16", "--precinct", "32", "--lossless",
        raw, tmp_path / "cli.mrsv")
    mrsv.encode(st_helens, tmp_path / "py.mrsv", precinct=32, lossless=True)
    assert (tmp_path / "py.mrsv").read_bytes() == (tmp_path / "cli.mrsv").read_bytes()
    samples, _ = mrsv.decode(tmp_path / "py.mrsv")
    assert np.array_equal(samples, st_helens)
    with pytest.raises(ValueError, match="power of two"):
        mrsv.encode(st_helens, tmp_path / "bad.mrsv", precinct=48)


@pytest.mark.parametrize("box", [((10, 20), (75, 50)), ((32, 0), (64, 32)), ((0, 0), (128, 128)), ((127, 5), (128, 6))])
def test_region_is_the_crop_2d(box, tiled_terrain, st_helens):
    (x0, y0), (x1, y1) = box
    samples, info = mrsv.decode(tiled_terrain, region=box)
    assert np.array_equal(samples, st_helens[y0:y1, x0:x1])
    assert info["region"] == box and info["shape"] == (128, 128)
    # The region's origin in the whole grid's frame, as 'mrsv decode --region' writes it.
    assert info["origin"] == (1000 + 30 * x0, 2000 + 30 * y0) and info["spacing"] == (30, 30)
    same, _ = mrsv.decode(tiled_terrain.read_bytes(), region=box)
    assert np.array_equal(same, samples)


def test_region_is_the_crop_3d(tiled_head):
    whole, _ = mrsv.decode(tiled_head)
    box = ((5, 10, 3), (40, 30, 20))
    samples, info = mrsv.decode(tiled_head, region=box)
    assert samples.shape == (17, 20, 35)
    assert np.array_equal(samples, whole[3:20, 10:30, 5:40])


def test_region_of_an_untiled_stream(ct_head, tmp_path):
    path = tmp_path / "head.mrsv"
    mrsv.encode(ct_head, path, max_error=1)
    whole, _ = mrsv.decode(path)
    samples, info = mrsv.decode(path, region=((7, 0, 30), (64, 9, 32)))
    assert np.array_equal(samples, whole[30:32, 0:9, 7:64])
    # Read whole, then cropped (the first chunk is read once more to see that it is not tiled).
    assert path.stat().st_size <= info["bytes_read"] < path.stat().st_size + 100


def test_region_reads_only_its_tiles(tiled_terrain, st_helens):
    size = tiled_terrain.stat().st_size
    samples, info = mrsv.decode(tiled_terrain, region=((40, 40), (60, 60)))  # inside one of the 16 tiles
    assert np.array_equal(samples, st_helens[40:60, 40:60])
    assert info["bytes"] == size and info["bytes_read"] < size / 8
    _, four = mrsv.decode(tiled_terrain, region=((20, 20), (40, 40)))  # four tiles
    assert info["bytes_read"] < four["bytes_read"] < size / 2
    # bytes= reads the prefix into memory, as 'mrsv decode --region --bytes'.
    same, _ = mrsv.decode(tiled_terrain, region=((40, 40), (60, 60)), bytes=size)
    assert np.array_equal(same, samples)


def test_region_at_reduced_resolution(tiled_terrain):
    whole, info = mrsv.decode(tiled_terrain, levels=1)
    assert whole.shape == (64, 64) and info["spacing"] == (60, 60) and info["origin"] == (1000, 2000)
    samples, info = mrsv.decode(tiled_terrain, region=((9, 8), (73, 41)), levels=1)
    # The lattice of every second sample inside the box: x 10..72, y 8..40.
    assert np.array_equal(samples, whole[4:21, 5:37])
    assert info["spacing"] == (60, 60) and info["origin"] == (1000 + 30 * 10, 2000 + 30 * 8)


def test_region_and_tile_refusals(tiled_terrain, tiled_head, st_helens, tmp_path):
    with pytest.raises(ValueError, match="region=: the region ends at x = 129, beyond the grid's 128"):
        mrsv.decode(tiled_terrain, region=((0, 0), (129, 10)))
    with pytest.raises(ValueError, match="empty along y"):
        mrsv.decode(tiled_terrain, region=((0, 5), (10, 5)))
    with pytest.raises(ValueError, match="corners of 2 numbers for a grid of 3 dimensions"):
        mrsv.decode(tiled_head, region=((0, 0), (4, 4)))
    with pytest.raises(ValueError, match="both give 1 to 3 numbers"):
        mrsv.decode(tiled_terrain, region=((0, 0), (4, 4, 1)))
    with pytest.raises(TypeError, match=r"region= must be \(\(x0, y0"):
        mrsv.decode(tiled_terrain, region=(0, 0, 4, 4))
    with pytest.raises(TypeError, match="region="):
        mrsv.decode(tiled_terrain, region=((0.5, 0), (4, 4)))
    # spec 11.6: 32-sample tiles are on the lattice of 2^5, not of 2^6.
    mrsv.decode(tiled_terrain, levels=5)
    with pytest.raises(ValueError, match=r"levels=: a tiled grid reduced by 6 levels needs tile sizes that are "
                                         r"multiples of 2\^6"):
        mrsv.decode(tiled_terrain, levels=6)
    with pytest.raises(ValueError, match=r"multiples of 2\^6"):
        mrsv.decode(tiled_terrain, levels=6, region=((0, 0), (64, 64)))
    with pytest.raises(ValueError, match="threads= must be a whole number from 1 to 1024"):
        mrsv.decode(tiled_terrain, threads=0)
    out = tmp_path / "x.mrsv"
    with pytest.raises(ValueError, match="tile= needs coding='wavelet'"):
        mrsv.encode(st_helens, out, tile=32, coding="stored")
    with pytest.raises(ValueError, match="tile= gives 3 sizes for a grid of 2 dimensions"):
        mrsv.encode(st_helens, out, tile=(32, 32, 8))
    with pytest.raises(ValueError, match="tile= takes at most 3 sizes"):
        mrsv.encode(st_helens, out, tile=(32, 32, 8, 8))
    with pytest.raises(ValueError, match="tile= size 0 is not a whole number from 1 to"):
        mrsv.encode(st_helens, out, tile=0)
    with pytest.raises(TypeError, match="tile="):
        mrsv.encode(st_helens, out, tile=32.0)
    with pytest.raises(ValueError, match="tile= does not take roi="):
        mrsv.encode(st_helens, out, tile=32, psnr=40, roi=("box", (0, 0), (10, 10)))
    with pytest.raises(ValueError, match="tile_size: the tiling makes 1050625 tiles, above the limit"):
        mrsv.encode(np.zeros((1025, 1025), np.uint8), out, tile=1)
    with pytest.raises(ValueError, match="threads= must be a whole number from 1 to 1024"):
        mrsv.encode(st_helens, out, tile=32, threads=2000)
    assert not out.exists()


def shared_side(vertices, x):
    """The rows of `vertices` on the line x (sorted, to compare as sets)."""
    side = vertices[vertices[:, 0] == x]
    return side[np.lexsort(side.T[::-1])]


@pytest.mark.parametrize("method", ["insertion", "quadtree"])
def test_mesh_boxes_meet_on_their_shared_side(method, tiled_terrain):
    # Boxes sharing the column x = 70 (inside a tile; the boxes are not tile-aligned).
    left, lt, _ = mrsv.mesh_grid(tiled_terrain, method=method, max_error=8, region=((0, 10), (71, 110)))
    right, rt, _ = mrsv.mesh_grid(tiled_terrain, method=method, max_error=8, region=((70, 10), (128, 110)))
    assert left[:, 0].min() == 1000 and left[:, 0].max() == right[:, 0].min() == 1000 + 70 * 30
    assert right[:, 1].min() == 2000 + 10 * 30 and right[:, 1].max() == 2000 + 109 * 30
    a, b = shared_side(left, 1000 + 70 * 30), shared_side(right, 1000 + 70 * 30)
    assert 2 <= len(a) < 100 and np.array_equal(a, b)


def test_mesh_region_is_the_cli_mesh(tiled_terrain, tmp_path):
    vertices, triangles, values = mrsv.mesh_grid(tiled_terrain, max_error=5, region=((20, 30), (90, 100)))
    run("mesh", "--quiet", "--max-error", "5", "--region", "20,30,90,100", tiled_terrain, tmp_path / "box.obj")
    v, f, _ = mrsv.read_mesh(tmp_path / "box.obj")
    assert np.array_equal(vertices, v) and np.array_equal(triangles, f)
    assert np.array_equal(values, vertices[:, 2])


def test_mesh_of_a_whole_tiled_stream(tiled_terrain, st_helens, tiled_head, tmp_path):
    untiled = tmp_path / "dem.mrsv"
    mrsv.encode(st_helens, untiled, spacing=(30, 30), origin=(1000, 2000))
    # The same samples, so the same mesh (the field is the decoded samples, spec 8.1).
    for a, b in zip(mrsv.mesh_grid(tiled_terrain, max_error=10), mrsv.mesh_grid(untiled, max_error=10)):
        assert np.array_equal(a, b)
    _, tets, _ = mrsv.mesh_grid(tiled_head, max_error=40, region=((0, 0, 0), (24, 24, 12)))
    assert tets.shape[1] == 4 and len(tets) > 0
    with pytest.raises(ValueError, match="levels= is not defined for tiled grids"):
        mrsv.mesh_grid(tiled_terrain, max_error=10, levels=1)
    with pytest.raises(ValueError, match="region= meshes the region's samples once: not with levels="):
        mrsv.mesh_grid(tiled_terrain, max_error=10, levels=1, region=((0, 0), (64, 64)))
