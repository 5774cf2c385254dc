/* Parallel HDF5 with the MRSV filter (issue 24): every MPI rank reads the
 * same terrain crop and writes its own rows of it, whole chunks, into one
 * chunked dataset per mode, collectively (filters in parallel writes need
 * collective I/O, HDF5 >= 1.10.2). hdf5_filter_mpi_test.py reads the file back
 * serially and checks it.
 *
 *   mpirun -np 2 hdf5_filter_mpi_write IN.raw SIZE_X SIZE_Y OUT.h5
 *
 * IN.raw: int16 little-endian, x fastest; SIZE_Y a multiple of 32 * ranks.
 * HDF5_PLUGIN_PATH must hold the plugin built against the MPI HDF5. */
#include <hdf5.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mrsv_hdf5_filter.h"

static int fail(const char* what) {
  fprintf(stderr, "hdf5_filter_mpi_write: %s\n", what);
  MPI_Abort(MPI_COMM_WORLD, 1);
  return 1;
}

/* One dataset in the given mode, each rank writing rows [y0, y0 + rows). */
static int writeDataset(hid_t file, const char* name, unsigned mode, double parameter, const short* rows_data,
                        hsize_t size_x, hsize_t size_y, hsize_t y0, hsize_t rows) {
  unsigned cd[3];
  unsigned long long bits;
  memcpy(&bits, &parameter, 8);
  cd[0] = mode;
  cd[1] = (unsigned)(bits & 0xffffffffu);
  cd[2] = (unsigned)(bits >> 32);
  hsize_t dims[2] = {size_y, size_x}, chunk[2] = {32, size_x < 64 ? size_x : 64};
  hid_t space = H5Screate_simple(2, dims, NULL);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 2, chunk);
  if (H5Pset_filter(dcpl, MRSV_H5Z_FILTER_ID, H5Z_FLAG_MANDATORY, 3, cd) < 0)
    return fail("H5Pset_filter: is the plugin in HDF5_PLUGIN_PATH?");
  hid_t dset = H5Dcreate2(file, name, H5T_STD_I16LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (dset < 0) return fail("H5Dcreate2 failed");
  hsize_t start[2] = {y0, 0}, count[2] = {rows, size_x};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
  hid_t memspace = H5Screate_simple(2, count, NULL);
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  if (H5Dwrite(dset, H5T_NATIVE_SHORT, memspace, space, dxpl, rows_data) < 0) return fail("H5Dwrite failed");
  H5Pclose(dxpl);
  H5Sclose(memspace);
  H5Dclose(dset);
  H5Pclose(dcpl);
  H5Sclose(space);
  return 0;
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (argc != 5) return fail("usage: mpirun -np N hdf5_filter_mpi_write IN.raw SIZE_X SIZE_Y OUT.h5");
  hsize_t size_x = strtoull(argv[2], NULL, 10), size_y = strtoull(argv[3], NULL, 10);
  if (size_x == 0 || size_y == 0 || size_y % (32 * (hsize_t)ranks) != 0)
    return fail("SIZE_Y must be a multiple of 32 times the number of ranks");
  hsize_t rows = size_y / (hsize_t)ranks, y0 = rows * (hsize_t)rank;
  short* data = malloc(rows * size_x * sizeof(short));
  FILE* in = fopen(argv[1], "rb");
  if (data == NULL || in == NULL) return fail("cannot read IN.raw");
  if (fseek(in, (long)(y0 * size_x * 2), SEEK_SET) != 0 || fread(data, 2, rows * size_x, in) != rows * size_x)
    return fail("IN.raw is shorter than SIZE_X x SIZE_Y int16 samples");
  fclose(in);

  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL);
  hid_t file = H5Fcreate(argv[4], H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  if (file < 0) return fail("cannot create OUT.h5");
  writeDataset(file, "lossless", MRSV_H5Z_MODE_LOSSLESS, 0, data, size_x, size_y, y0, rows);
  writeDataset(file, "max_error_2", MRSV_H5Z_MODE_MAX_ERROR, 2, data, size_x, size_y, y0, rows);
  writeDataset(file, "psnr_50", MRSV_H5Z_MODE_PSNR, 50, data, size_x, size_y, y0, rows);
  H5Fclose(file);
  H5Pclose(fapl);
  free(data);
  MPI_Finalize();
  return 0;
}
