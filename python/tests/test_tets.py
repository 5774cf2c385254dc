"""Progressive tet meshes: encode_tets and ProgressiveTetMesh on a CT crop and a hand."""
import numpy as np
import pytest

import mrsv
from conftest import shared


def volumes(vertices, tets):
    a, b, c, d = (vertices[tets[:, i]] for i in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)


@pytest.fixture(scope="module")
def ct_crop(tmp_path_factory, ct_head):
    crop = ct_head[8:24, 24:40, 24:40]  # 16^3 samples: 6 * 15^3 tets
    vertices, tets, fields = mrsv.tetrahedralize(crop, spacing=(1, 1, 2))
    path = tmp_path_factory.mktemp("pt") / "ct.mrsv"
    report = mrsv.encode_tets(vertices, tets, path, fields=fields)
    return crop, vertices, tets, fields, path, report


def test_tetrahedralize(ct_crop):
    crop, vertices, tets, fields, _, _ = ct_crop
    assert vertices.shape == (16**3, 3) and tets.shape == (6 * 15**3, 4)
    assert np.array_equal(np.sort(fields["value"]), np.sort(crop.ravel().astype(float)))
    assert vertices[:, 2].max() == 30  # z spacing 2
    assert (volumes(vertices, tets) > 0).all()


def test_levels_and_the_finest_level(ct_crop):
    crop, vertices, tets, fields, path, report = ct_crop
    pt = mrsv.ProgressiveTetMesh(path)
    assert pt.finest_level == report["splits"] and pt.complete
    assert (pt.vertex_count, pt.tet_count) == (16**3, 6 * 15**3)
    counts = [pt.tet_count_at(k) for k in (0, pt.finest_level // 3, pt.finest_level)]
    assert counts[0] < counts[1] < counts[2]
    # Integer field values spanning fewer than 2^16 values are kept exactly.
    assert np.array_equal(np.sort(pt.fields["value"]), np.sort(fields["value"]))
    for level in (0, pt.finest_level // 2, pt.finest_level):
        pt.level = level
        assert pt.tets.shape == (pt.tet_count_at(level), 4)
        assert pt.vertices.shape == (pt.vertex_count_at(level), 3)
        assert pt.fields["value"].shape == (pt.vertex_count,)
        assert (volumes(pt.vertices, pt.tets) > 0).all()


def test_finest_positions_are_the_input(ct_crop):
    _, vertices, _, _, path, _ = ct_crop
    pt = mrsv.ProgressiveTetMesh(path)
    step = pt.header["position_step"]
    decoded = pt.vertices[np.lexsort(pt.vertices.T[::-1])]
    expected = vertices[np.lexsort(vertices.T[::-1])]
    assert np.abs(decoded - expected).max() <= 0.5 * step + 1e-9


def test_hand(tmp_path):
    vertices, tets, fields = mrsv.read_tets(shared("tet/hand_7234v_29998tet.mesh"))
    assert vertices.shape == (7234, 3) and tets.shape == (29998, 4) and fields == {}
    path = tmp_path / "hand.mrsv"
    report = mrsv.encode_tets(vertices, tets, path)
    pt = mrsv.ProgressiveTetMesh(path)
    assert (pt.vertex_count, pt.tet_count) == (7234, 29998)
    assert pt.tet_count_at(0) == report["base_tet_count"] < 29998
    level = pt.finest_level_within(10000)
    pt.set_level(level)
    assert pt.tet_count <= 10000
    report = mrsv.check(path)
    assert report["kind"] == "tets" and report["tet_count"] == 29998


def test_prefix_and_wrong_kind(ct_crop, tmp_path):
    path = ct_crop[4]
    data = path.read_bytes()
    pt = mrsv.ProgressiveTetMesh(data, bytes=len(data) * 2 // 3)
    assert not pt.complete and pt.finest_level < mrsv.ProgressiveTetMesh(data).finest_level
    with pytest.raises(ValueError, match="ProgressiveTetMesh"):
        mrsv.ProgressiveMesh(path)
    with pytest.raises(ValueError, match="ProgressiveTetMesh"):
        mrsv.decode(path)
