"""Arguments of the MRSV HDF5 filter for h5py (spec Annex C).

    f.create_dataset("dem", data=dem, chunks=(256, 256), **mrsv.hdf5_filter("max_error", 1))

HDF5 finds the filter plugin (libmrsv_h5filter.so) in HDF5_PLUGIN_PATH, e.g.
build/hdf5plugins; h5py itself needs nothing more.
"""
import struct

HDF5_FILTER_ID = 421  # MRSV_H5Z_FILTER_ID: from HDF5's range for filters under test (decision D75)
_MODES = {"lossless": 0, "rate": 1, "psnr": 2, "max_error": 3}


def hdf5_filter(mode="lossless", value=None):
    """The create_dataset keyword arguments that store each chunk as an MRSV grid stream.

    mode: "lossless" (the default, no value), "rate" (value: bits per sample),
    "psnr" (value: dB, reached by every chunk) or "max_error" (value: the
    largest absolute error in sample units, integer samples only). The
    plugin checks the value's range when the dataset is created.
    """
    if mode not in _MODES:
        raise ValueError(f"mode {mode!r} is not one of {', '.join(_MODES)}")
    if mode == "lossless":
        if value is not None:
            raise ValueError("lossless takes no value")
        return {"compression": HDF5_FILTER_ID, "compression_opts": (0,)}
    if value is None:
        raise ValueError(f"mode {mode!r} needs a value")
    low, high = struct.unpack("<II", struct.pack("<d", float(value)))
    return {"compression": HDF5_FILTER_ID, "compression_opts": (_MODES[mode], low, high)}
