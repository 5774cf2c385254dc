"""mrsv.mesh_grid: adaptive meshes of a terrain and a CT crop within max_error."""
import numpy as np
import pytest

import mrsv


@pytest.fixture(scope="module")
def terrain(tmp_path_factory, st_helens):
    path = tmp_path_factory.mktemp("rec") / "dem.mrsv"
    mrsv.encode(st_helens, path, progressive=True, spacing=(30, 30))
    return path


def interpolate(vertices, triangles, values, x, y):
    """The mesh's value at grid point (x, y) (vertices in grid units)."""
    for t in triangles:
        (x0, y0), (x1, y1), (x2, y2) = vertices[t, :2]
        d = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
        a = ((y1 - y2) * (x - x2) + (x2 - x1) * (y - y2)) / d
        b = ((y2 - y0) * (x - x2) + (x0 - x2) * (y - y2)) / d
        c = 1 - a - b
        if min(a, b, c) >= -1e-9:
            return a * values[t[0]] + b * values[t[1]] + c * values[t[2]]
    raise AssertionError(f"({x}, {y}) is in no triangle")


@pytest.mark.parametrize("method, remove", [("insertion", False), ("insertion", True), ("quadtree", False),
                                            ("quadtree", True)])
def test_terrain_within_max_error(method, remove, terrain, st_helens):
    vertices, triangles, values = mrsv.mesh_grid(terrain, method=method, max_error=20, remove_vertices=remove)
    assert triangles.shape[1] == 3 and len(vertices) == len(values) < st_helens.size / 4
    assert vertices[:, 0].max() == 127 * 30  # spacing from the meta chunk
    grid = vertices[:, :2] / 30
    rng = np.random.default_rng(1)
    for x, y in rng.integers(0, 128, size=(40, 2)):
        assert abs(interpolate(grid, triangles, values, x, y) - st_helens[y, x]) <= 20 + 1e-9


def test_removal_pass_has_fewer_triangles(terrain):
    _, tree, _ = mrsv.mesh_grid(terrain, method="quadtree", max_error=5)
    _, removed, _ = mrsv.mesh_grid(terrain, method="quadtree", max_error=5, remove_vertices=True)
    _, inserted, _ = mrsv.mesh_grid(terrain, max_error=5)
    # The quadtree's pass (spec 9.7, D89) aims at issue 22's 1.5 x insertion's triangles, not below them.
    assert len(inserted) < len(tree) and len(removed) < len(tree) and 2 * len(removed) <= 3 * len(inserted)
    _, inserted_removed, _ = mrsv.mesh_grid(terrain, max_error=5, remove_vertices=True)
    assert len(inserted_removed) < len(inserted)
    with pytest.raises(ValueError, match="remove_vertices"):
        mrsv.mesh_grid(terrain, triangles=500, remove_vertices=True)


def test_border_cleanup(terrain):
    """Spec 8.8: by default the inner vertices next to the sides are tried once for removal."""
    def sides(vertices):
        grid = vertices[:, :2] / 30
        on = (grid[:, 0] == 0) | (grid[:, 1] == 0) | (grid[:, 0] == 127) | (grid[:, 1] == 127)
        return sorted(map(tuple, grid[on]))

    for e in (5, 20):
        cleaned_vertices, cleaned, _ = mrsv.mesh_grid(terrain, max_error=e)
        raw_vertices, raw, _ = mrsv.mesh_grid(terrain, max_error=e, border_cleanup=False)
        assert len(cleaned) < len(raw)
        assert len(raw) - len(cleaned) == 2 * (len(raw_vertices) - len(cleaned_vertices))
        assert sides(cleaned_vertices) == sides(raw_vertices)


def test_cell_budget_and_levels(terrain):
    _, triangles, _ = mrsv.mesh_grid(terrain, triangles=500)
    assert 500 <= len(triangles) <= 502
    coarse, _, _ = mrsv.mesh_grid(terrain, max_error=5, levels=2)
    fine, _, _ = mrsv.mesh_grid(terrain, max_error=5)
    assert len(coarse) < len(fine)


def test_volume(tmp_path, ct_head):
    path = tmp_path / "ct.mrsv"
    mrsv.encode(ct_head[:16, :16, :16], path)
    vertices, tets, values = mrsv.mesh_grid(path, max_error=30)
    assert tets.shape[1] == 4 and len(vertices) == len(values)


def test_mesh_grid_arguments(terrain):
    with pytest.raises(ValueError, match="give max_error"):
        mrsv.mesh_grid(terrain)
    with pytest.raises(ValueError, match="use triangles="):
        mrsv.mesh_grid(terrain, tets=100)
    with pytest.raises(ValueError, match="method="):
        mrsv.mesh_grid(terrain, method="marching", max_error=1)
