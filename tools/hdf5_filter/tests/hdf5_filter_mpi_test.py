"""Parallel HDF5 with the MRSV filter: `mpirun -np 2 hdf5_filter_mpi_write`
writes the St. Helens crop from two ranks (each its own 64 rows, collectively)
with the plugin built against Debian's OpenMPI HDF5; h5py (serial HDF5, the
serial plugin) reads it back and checks every sample.

    hdf5_filter_mpi_test.py MPIRUN WRITER MPI_PLUGIN_DIR SERIAL_PLUGIN_DIR SOURCE_DIR
"""
import os
import pathlib
import subprocess
import sys
import tempfile


def main():
    mpirun, writer, mpi_plugins, serial_plugins, source = sys.argv[1:6]
    raw = pathlib.Path(source) / "demo" / "data" / "mt_st_helens_128x128_int16le.raw"
    with tempfile.TemporaryDirectory(prefix="mrsv_h5mpi_") as tmp:
        out = pathlib.Path(tmp) / "mpi.h5"
        command = [mpirun, "-np", "2", "--oversubscribe", "-x", "HDF5_PLUGIN_PATH"]
        if os.geteuid() == 0:
            command.append("--allow-run-as-root")
        command += [writer, str(raw), "128", "128", str(out)]
        env = dict(os.environ, HDF5_PLUGIN_PATH=mpi_plugins, OMPI_MCA_btl="self,vader")
        run = subprocess.run(command, env=env, capture_output=True, text=True, timeout=120)
        if run.returncode != 0:
            sys.exit(f"mpirun failed ({run.returncode}):\n{run.stdout}\n{run.stderr}")
        check = subprocess.run([sys.executable, "-c", CHECK, str(out), str(raw)],
                               env=dict(os.environ, HDF5_PLUGIN_PATH=serial_plugins),
                               capture_output=True, text=True)
        print(check.stdout, end="")
        if check.returncode != 0:
            sys.exit(check.stderr or "check failed")


# Runs in a fresh process: HDF5_PLUGIN_PATH is read when h5py loads HDF5.
CHECK = r"""
import sys
import h5py
import numpy as np

path, raw = sys.argv[1:3]
data = np.fromfile(raw, "<i2").reshape(128, 128)
with h5py.File(path, "r") as f:
    for name, bound in [("lossless", 0), ("max_error_2", 2), ("psnr_50", None)]:
        d = f[name]
        assert "421" in d._filters, name
        back = d[...].astype(np.int64)
        err = np.abs(back - data)
        stored = sum(d.id.get_chunk_info(i).size for i in range(d.id.get_num_chunks()))
        if bound is not None:
            assert err.max() <= bound, (name, err.max())
        else:
            mse = np.mean(err.astype(float) ** 2)
            assert 10 * np.log10(float(data.max() - data.min()) ** 2 / mse) >= 50, name
        assert stored < data.nbytes, (name, stored)
        print(f"{name}: {d.id.get_num_chunks()} chunks, {stored} bytes of {data.nbytes}, max error {err.max()}")
"""

if __name__ == "__main__":
    main()
