#!/usr/bin/python3
"""Building a PT (`mrsv encode MESH.vtu`, every consistency test on) against VTK's
vtkUnstructuredGridQuadricDecimation, the one maintained tet-mesh decimator (issue 21),
in turn in one run: VTK decimates the same .vtu to the PT's base vertex count (or as far
as it gets). Prints vertices removed per second for both and their ratio. VTK checks
neither inversions, the link condition nor boundary self-intersections; ours does.

usage: /usr/bin/python3 tools/bench/tet_vtk_peer.py [--mrsv build/mrsv] [--rounds N] MESH.vtu...
(python3-vtk9; make the CT crop with `build/mrsv tetrahedralize --dims 256,256,99 --type uint8
--crop 112,112,40,32,32,32 ct.raw ct.vtu`, the LOX post as in tools/bench/README.md)
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('meshes', nargs='+', metavar='MESH.vtu')
    parser.add_argument('--mrsv', default=os.path.join(os.path.dirname(__file__), '..', '..', 'build', 'mrsv'))
    parser.add_argument('--rounds', type=int, default=2, help='best of N for each side (2)')
    args = parser.parse_args()
    import vtk
    for path in args.meshes:
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(path)
        reader.Update()
        grid = reader.GetOutput()
        points, tets = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
        if points == 0:
            sys.exit(f'{path}: no points read')
        ours, theirs = 1e30, 1e30
        with tempfile.TemporaryDirectory() as scratch:
            stream = os.path.join(scratch, 'pt.mrsv')
            for _ in range(args.rounds):
                start = time.perf_counter()
                subprocess.run([args.mrsv, 'encode', '--quiet', path, stream], check=True)
                ours = min(ours, time.perf_counter() - start)
                info = subprocess.run([args.mrsv, 'info', stream], check=True, capture_output=True, text=True).stdout
                base = int(re.search(r'base (\d+) vertices', info).group(1))
                decimate = vtk.vtkUnstructuredGridQuadricDecimation()
                decimate.SetInputData(grid)
                decimate.SetNumberOfTetsOutput(0)
                decimate.SetTargetReduction(1.0 - base / points)
                start = time.perf_counter()
                decimate.Update()
                theirs = min(theirs, time.perf_counter() - start)
        left = decimate.GetOutput().GetNumberOfPoints()
        ours_rate, theirs_rate = (points - base) / ours, (points - left) / theirs
        print(f'{os.path.basename(path)}: {points} vertices, {tets} tets; PT build (mrsv encode, whole process) '
              f'to {base} vertices {ours:.3f} s, {ours_rate:.0f} vertices/s; VTK quadric decimation to {left} '
              f'vertices {theirs:.3f} s, {theirs_rate:.0f} vertices/s; PT/VTK {ours_rate / theirs_rate:.2f}x')


if __name__ == '__main__':
    main()
