/* The MRSV HDF5 filter: its identifier and the layout of its cd_values
 * (spec: Annex C). Plain C, so that C, C++ and MPI programs setting the
 * filter with H5Pset_filter share the numbers with the plugin. */
#ifndef MRSV_HDF5_FILTER_H
#define MRSV_HDF5_FILTER_H

/* From the range 256-511 that HDF5 leaves for filters under test (decision
 * D75); 305 and 307 in it are registered (LZO, BZIP2) and avoided. An
 * official identifier is to be requested from The HDF Group. */
#define MRSV_H5Z_FILTER_ID 421

/* Modes, the rate and quality controls of `mrsv encode`. */
#define MRSV_H5Z_MODE_LOSSLESS 0  /* every sample exact (the default) */
#define MRSV_H5Z_MODE_RATE 1      /* parameter: bits per sample */
#define MRSV_H5Z_MODE_PSNR 2      /* parameter: PSNR in dB of every chunk */
#define MRSV_H5Z_MODE_MAX_ERROR 3 /* parameter: max absolute error, sample units */

/* What the user gives to H5Pset_filter: nothing (lossless), {mode} or
 * {mode, parameter low word, parameter high word}, the parameter an IEEE 754
 * binary64 whose bit pattern is split in two 32-bit words, low word first. */

/* What set_local stores with the dataset (Annex C.2): */
#define MRSV_H5Z_CD_VERSION_VALUE 1
#define MRSV_H5Z_CD_VERSION 0      /* MRSV_H5Z_CD_VERSION_VALUE */
#define MRSV_H5Z_CD_MODE 1
#define MRSV_H5Z_CD_PARAM_LO 2
#define MRSV_H5Z_CD_PARAM_HI 3
#define MRSV_H5Z_CD_SAMPLE_TYPE 4  /* spec 3.1 sample_type: 1 uint8 ... 6 float64 */
#define MRSV_H5Z_CD_FLAGS 5        /* bit 0: NODATA holds the no-data value */
#define MRSV_H5Z_CD_NODATA_LO 6    /* bit pattern of the user-defined fill value */
#define MRSV_H5Z_CD_NODATA_HI 7
#define MRSV_H5Z_CD_RANK 8         /* rank of the chunk, 1 to 32 */
#define MRSV_H5Z_CD_DIMS 9         /* the chunk dims, slowest first (C order) */
#define MRSV_H5Z_CD_FLAG_NODATA 1u

#endif
