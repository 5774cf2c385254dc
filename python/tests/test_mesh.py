"""Progressive triangle meshes: encode_mesh and ProgressiveMesh on real models."""
import numpy as np
import pytest

import mrsv
from conftest import shared


@pytest.fixture(scope="module")
def cow(tmp_path_factory):
    vertices, faces, scalars = mrsv.read_mesh(shared("surface/cow_viewpoint_2903v_5804tri.obj"))
    path = tmp_path_factory.mktemp("pm") / "cow.mrsv"
    report = mrsv.encode_mesh(vertices, faces, path, bits=16)
    return vertices, faces, path, report


def nearest(points, reference):
    """Index of the nearest reference point for each point (chunked brute force)."""
    out = np.empty(len(points), dtype=np.int64)
    for start in range(0, len(points), 256):
        d = ((points[start : start + 256, None, :] - reference[None, :, :]) ** 2).sum(axis=2)
        out[start : start + 256] = d.argmin(axis=1)
    return out


def triangle_set(faces):
    """Triangles up to rotation (orientation kept)."""
    rolled = [tuple(np.roll(f, -int(np.argmin(f)))) for f in faces]
    return set(rolled)


def test_read_mesh(cow):
    vertices, faces, _, _ = cow
    assert vertices.shape == (2903, 3) and vertices.dtype == np.float64
    assert faces.shape == (5804, 3) and faces.dtype == np.int32


def test_levels_coarse_to_fine(cow):
    _, _, path, report = cow
    pm = mrsv.ProgressiveMesh(path)
    assert pm.complete and pm.level == pm.finest_level == pm.levels - 1 == report["splits"]
    counts = [pm.vertex_count_at(k) for k in range(0, pm.levels, 97)]
    assert counts == sorted(counts) and counts[0] == report["base_vertex_count"]
    faces = [pm.face_count_at(k) for k in (0, pm.finest_level // 2, pm.finest_level)]
    assert faces[0] < faces[1] < faces[2] == report["face_count"]
    pm.set_level(0)
    assert pm.vertices.shape == (report["base_vertex_count"], 3)
    assert pm.faces.shape == (report["base_face_count"], 3)
    assert pm.faces.max() < pm.vertex_count


@pytest.mark.parametrize("options", [{"placement": "endpoint"}, {}])
def test_finest_level_is_the_input(options, tmp_path):
    vertices, faces, _ = mrsv.read_mesh(shared("surface/cow_viewpoint_2903v_5804tri.obj"))
    path = tmp_path / "cow.mrsv"
    report = mrsv.encode_mesh(vertices, faces, path, **options)
    pm = mrsv.ProgressiveMesh(path)
    assert (pm.vertex_count, pm.face_count) == (report["vertex_count"], 5804)
    step = pm.header["position_step"]
    decoded = pm.vertices
    match = nearest(decoded, vertices)
    # Every vertex on one of the 27 grid points around its nearest (the
    # encoder's choice, decision D34): within 1.5 quantisation steps per axis.
    # The repair split one non-manifold vertex into two copies at one position.
    assert np.abs(decoded - vertices[match]).max() <= 1.5 * step + 1e-12
    assert triangle_set(match[pm.faces]) == triangle_set(faces)


def test_moving_down_and_up_gives_the_same_level(cow):
    _, _, path, _ = cow
    pm = mrsv.ProgressiveMesh(path)
    pm.level = 500
    v, f = pm.vertices, pm.faces
    pm.level = pm.finest_level
    pm.level = 10
    pm.level = 500
    assert np.array_equal(v, pm.vertices) and np.array_equal(f, pm.faces)


def test_finest_level_within(cow):
    _, _, path, _ = cow
    pm = mrsv.ProgressiveMesh(path)
    level = pm.finest_level_within(1000)
    assert pm.face_count_at(level) <= 1000 < pm.face_count_at(level + 1)


def test_prefix_has_fewer_levels(cow):
    _, _, path, _ = cow
    data = path.read_bytes()
    pm = mrsv.ProgressiveMesh(path, bytes=len(data) // 2)
    full = mrsv.ProgressiveMesh(data)
    assert not pm.complete and 0 < pm.finest_level < full.finest_level
    assert mrsv.check(path)["kind"] == "mesh"


def test_level_out_of_range(cow):
    _, _, path, _ = cow
    pm = mrsv.ProgressiveMesh(path)
    with pytest.raises(IndexError):
        pm.set_level(pm.finest_level + 1)
    with pytest.raises(IndexError):
        pm.level = -1


def test_bad_mesh_arguments(tmp_path):
    v = np.zeros((3, 3))
    with pytest.raises(ValueError, match="out of range"):
        mrsv.encode_mesh(v, [[0, 1, 3]], tmp_path / "x.mrsv")
    with pytest.raises(ValueError, match="shape"):
        mrsv.encode_mesh(v, [[0, 1]], tmp_path / "x.mrsv")
    with pytest.raises(TypeError, match="integers"):
        mrsv.encode_mesh(v, [[0.0, 1.0, 2.0]], tmp_path / "x.mrsv")
    with pytest.raises(ValueError, match="placement"):
        mrsv.encode_mesh(v, [[0, 1, 2]], tmp_path / "x.mrsv", placement="middle")


def test_grid_is_not_a_mesh(st_helens, tmp_path):
    path = tmp_path / "g.mrsv"
    mrsv.encode(st_helens, path)
    with pytest.raises(ValueError, match="mrsv.decode"):
        mrsv.ProgressiveMesh(path)
