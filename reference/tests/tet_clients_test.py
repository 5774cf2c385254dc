#!/usr/bin/env python3
"""Our .vtu and .vtk files as the real clients read them: VTK 9 and meshio.

Usage: tet_clients_test.py MRSV_BINARY SHARED_DATA_DIR

Runs `mrsv tetrahedralize` on the combustion chamber (PLOT3D, 5 fields) and on
a 16^3 crop of the Stanford CT head, writes .vtu and .vtk (binary and ascii),
.mesh and .node, then opens the VTK files with vtkXMLUnstructuredGridReader,
vtkUnstructuredGridReader and meshio.read and compares point and cell counts,
the points, the tets and every field with the .mesh and .node files written by
mrsv (parsed here). Then the other way round: files written by VTK and meshio
(appended raw and base64 data, separately encoded headers, legacy 5.1) are read
back by mrsv. A missing module is a failure, not a skip: CI installs
python3-vtk9 and python3-meshio through tools/setup.sh.
"""
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def run(mrsv, *args):
    result = subprocess.run([mrsv, "tetrahedralize", "--quiet", *args], capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"mrsv tetrahedralize {' '.join(args)} failed: {result.stderr.strip()}")
    return result.stdout


def read_medit(path):
    """Points and 0-based tets of a MEDIT file as mrsv writes it (no comments)."""
    with open(path) as f:
        words = f.read().split()
    points, tets = None, None
    i = 0
    while i < len(words):
        if words[i] == "Vertices":
            n = int(words[i + 1])
            points = np.array(words[i + 2:i + 2 + 4 * n], dtype=np.float64).reshape(n, 4)[:, :3]
            i += 2 + 4 * n
        elif words[i] == "Tetrahedra":
            n = int(words[i + 1])
            tets = np.array(words[i + 2:i + 2 + 5 * n], dtype=np.int64).reshape(n, 5)[:, :4] - 1
            i += 2 + 5 * n
        else:
            i += 1
    return points, tets


def read_node(path):
    """Points and attributes (named by the '# fields:' comment) of a .node file."""
    names = []
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("# fields:"):
                names = line.split(":", 1)[1].split()
            line = line.split("#", 1)[0].split()
            if line:
                rows.append(line)
    n, dim, attributes, markers = (int(x) for x in rows[0])
    data = np.array([[float(x) for x in r[1:4 + attributes]] for r in rows[1:1 + n]])
    return data[:, :3], {name: data[:, 3 + k] for k, name in enumerate(names)}


def vtk_read(path):
    reader = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtk.vtkUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float64)
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    types = vtk_to_numpy(grid.GetCellTypesArray())
    data = grid.GetPointData()
    fields = {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)).astype(np.float64)
              for i in range(data.GetNumberOfArrays())}
    return points, cells, types, fields


def compare(label, points, tets, fields, ref_points, ref_tets, ref_fields, exact=True):
    """Exact unless the file was written as text by a client that rounds
    (VTK's legacy ASCII and meshio's ASCII VTU keep about 7 to 9 digits)."""
    same = np.array_equal if exact else (lambda a, b: np.allclose(a, b, rtol=1e-6, atol=1e-12))
    check(len(points) == len(ref_points), f"{label}: {len(points)} points, expected {len(ref_points)}")
    check(len(tets) == len(ref_tets), f"{label}: {len(tets)} tets, expected {len(ref_tets)}")
    if len(points) == len(ref_points):
        check(same(points, ref_points), f"{label}: points differ")
    if len(tets) == len(ref_tets):
        check(np.array_equal(tets, ref_tets), f"{label}: tets differ")
    check(sorted(fields) == sorted(ref_fields), f"{label}: fields {sorted(fields)}, expected {sorted(ref_fields)}")
    for name, values in ref_fields.items():
        if name in fields:
            check(same(fields[name], values), f"{label}: field {name} differs")


def client_round(mrsv, work, label, source_args):
    base = os.path.join(work, label)
    for ext in (".mesh", ".node", ".vtu", ".vtk"):
        run(mrsv, *source_args, base + ext)
    run(mrsv, "--ascii", *source_args, base + "_ascii.vtu")
    run(mrsv, "--ascii", *source_args, base + "_ascii.vtk")
    ref_points, ref_tets = read_medit(base + ".mesh")
    node_points, ref_fields = read_node(base + ".node")
    check(np.array_equal(node_points, ref_points), f"{label}: .node and .mesh points differ")
    check(len(ref_fields) > 0, f"{label}: no fields in the .node file")
    for name in (".vtu", ".vtk", "_ascii.vtu", "_ascii.vtk"):
        path = base + name
        points, cells, types, fields = vtk_read(path)
        check(np.all(types == 10), f"VTK {label}{name}: cells that are not tetrahedra")
        compare(f"VTK {label}{name}", points, cells, fields, ref_points, ref_tets, ref_fields)
        mesh = meshio.read(path)
        tets = np.concatenate([c.data for c in mesh.cells if c.type == "tetra"])
        check(all(c.type == "tetra" for c in mesh.cells), f"meshio {label}{name}: cells that are not tetra")
        compare(f"meshio {label}{name}", mesh.points.astype(np.float64), tets,
                {k: np.asarray(v, dtype=np.float64).ravel() for k, v in mesh.point_data.items()},
                ref_points, ref_tets, ref_fields)
    print(f"{label}: {len(ref_points)} points, {len(ref_tets)} tets, fields {sorted(ref_fields)}: "
          "VTK and meshio agree with the .mesh and .node files")
    return base, ref_points, ref_tets, ref_fields


def read_back(mrsv, work, label, path, ref_points, ref_tets, ref_fields, exact=True):
    """A file written by a client, converted by mrsv to .mesh and .node and compared."""
    out = os.path.join(work, label + "_back")
    run(mrsv, path, out + ".mesh")
    run(mrsv, path, out + ".node")
    points, tets = read_medit(out + ".mesh")
    _, fields = read_node(out + ".node")
    compare(f"mrsv reading {label}", points, tets, fields, ref_points, ref_tets, ref_fields, exact)


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    mrsv, shared = sys.argv[1], sys.argv[2]
    tet = os.path.join(shared, "tet")
    with tempfile.TemporaryDirectory() as work:
        base, points, tets, fields = client_round(mrsv, work, "chamber", [
            os.path.join(tet, "combustion_chamber_plot3d_57x33x25_f32be.xyz"),
            "--q", os.path.join(tet, "combustion_chamber_plot3d_57x33x25_f32be.q")])
        check(len(tets) == 215042, f"chamber: {len(tets)} tets, expected 215,042 (2 hexahedra cut from a corner, D45)")

        ct = os.path.join(work, "ct.raw")
        subprocess.run(["zstd", "-d", "-q", "-f", "-o", ct,
                        os.path.join(shared, "volume", "ct_head_stanford_cthead_256x256x99_uint8.raw.zst")],
                       check=True)
        _, _, ct_tets, _ = client_round(mrsv, work, "ct", [
            ct, "--dims", "256,256,99", "--type", "uint8", "--crop", "112,112,40,16,16,16"])
        check(len(ct_tets) == 6 * 15 ** 3, f"ct: {len(ct_tets)} tets, expected {6 * 15 ** 3}")

        # The other way: what VTK and meshio write, mrsv reads.
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(base + ".vtu")
        reader.Update()
        for mode, encode in (("appended_raw", None), ("appended_base64", True), ("binary", None), ("ascii", None)):
            writer = vtk.vtkXMLUnstructuredGridWriter()
            writer.SetInputData(reader.GetOutput())
            writer.SetCompressorTypeToNone()
            if mode == "binary":
                writer.SetDataModeToBinary()
            elif mode == "ascii":
                writer.SetDataModeToAscii()
            else:
                writer.SetDataModeToAppended()
                writer.SetEncodeAppendedData(bool(encode))
            path = os.path.join(work, f"vtk_{mode}.vtu")
            writer.SetFileName(path)
            writer.Write()
            read_back(mrsv, work, f"vtk_{mode}.vtu", path, points, tets, fields)
        for binary in (True, False):
            writer = vtk.vtkUnstructuredGridWriter()
            writer.SetInputData(reader.GetOutput())
            if binary:
                writer.SetFileTypeToBinary()
            path = os.path.join(work, f"vtk_{'binary' if binary else 'ascii'}.vtk")
            writer.SetFileName(path)
            writer.Write()
            read_back(mrsv, work, os.path.basename(path), path, points, tets, fields, exact=binary)
        mesh = meshio.read(base + ".vtu")
        for name, kwargs in (("meshio_binary.vtu", {"binary": True, "compression": None}),
                             ("meshio_ascii.vtu", {"binary": False}),
                             ("meshio_binary.vtk", {"binary": True}),
                             ("meshio_ascii.vtk", {"binary": False})):
            path = os.path.join(work, name)
            meshio.write(path, mesh, **kwargs)
            read_back(mrsv, work, name, path, points, tets, fields, exact=kwargs["binary"])
        print("mrsv reads the .vtu and .vtk files VTK and meshio write")
    if failures:
        print(f"tet_clients_test: {len(failures)} failures")
        return 1
    print("tet_clients_test: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
