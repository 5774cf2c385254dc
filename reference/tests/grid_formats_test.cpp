// The grid file readers (NRRD, PGM, .hgt, headerless raw) on the real terrains
// and volumes of ../shared/data written in each format, on hand-written
// headers in the variants the formats allow, and on malformed files: every
// error is one line naming the file, where (line, offset or field) and the
// rule broken.
#include "mrsv/grid_formats.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <vector>

#include "mrsv/file_io.h"
#include "mrsv/raw_grid.h"
#include "shared_data.h"

namespace mrsv {
namespace {

std::vector<uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

std::vector<uint8_t> concat(std::vector<uint8_t> a, const std::vector<uint8_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

test::SharedGrid shared(const std::string& relative) {
  test::SharedGrid grid;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) + "/" + relative, &grid));
  return grid;
}

// The first `n` samples of a grid, a real-data payload for small files.
std::vector<uint8_t> firstSamples(const test::SharedGrid& grid, size_t n) {
  size_t bytes = n * sampleSize(grid.header.sample_type);
  return {grid.samples.begin(), grid.samples.begin() + static_cast<long>(bytes)};
}

bool read(GridFormat format, const std::vector<uint8_t>& bytes, GridInput* in, std::string* error) {
  return readGridBytes("in.grid", format, RawLayout{}, bytes, in, error);
}

// A failed read: false, one line starting with the name, containing `what`.
void expectError(GridFormat format, const std::vector<uint8_t>& bytes, const std::string& what) {
  GridInput in;
  std::string error;
  EXPECT_FALSE(read(format, bytes, &in, &error)) << "accepted; wanted an error with: " << what;
  EXPECT_EQ(error.rfind("in.grid: ", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_NE(error.find(what), std::string::npos) << "error '" << error << "' lacks '" << what << "'";
}

// --- NRRD -------------------------------------------------------------------

TEST(GridFormatsNrrd, OurWriterRoundTripsRealVolumesAndTerrainsInBothByteOrders) {
  for (const char* name : {"volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst",
                           "volume/ct_tooth_103x94x161_uint8.raw.zst",
                           "terrain/mt_st_helens_317x460_int16le.raw.zst"}) {
    test::SharedGrid grid = shared(name);
    const uint32_t size[3] = {grid.header.size_x, grid.header.size_y, grid.header.size_z};
    for (bool big : {false, true}) {
      std::vector<uint8_t> file;
      std::string error;
      ASSERT_TRUE(encodeGridOutput("out.nrrd", grid.header, Metadata{}, size, grid.samples, big, &file, &error)) << error;
      GridInput in;
      ASSERT_TRUE(read(GridFormat::kNrrd, file, &in, &error)) << name << ": " << error;
      EXPECT_EQ(in.header.num_dims, grid.header.num_dims);
      EXPECT_EQ(in.header.size_x, grid.header.size_x);
      EXPECT_EQ(in.header.size_y, grid.header.size_y);
      EXPECT_EQ(in.header.size_z, grid.header.size_z);
      EXPECT_EQ(in.header.sample_type, grid.header.sample_type);
      EXPECT_TRUE(in.samples == grid.samples) << name << (big ? " big-endian" : " little-endian");
    }
  }
}

TEST(GridFormatsNrrd, EveryTypeSpellingOfTheNrrdFormat) {
  const struct {
    const char* spelling;
    SampleType type;
  } kSpellings[] = {
      {"uchar", SampleType::kUint8},        {"unsigned char", SampleType::kUint8},
      {"uint8", SampleType::kUint8},        {"uint8_t", SampleType::kUint8},
      {"short", SampleType::kInt16},        {"short int", SampleType::kInt16},
      {"signed short", SampleType::kInt16}, {"signed short int", SampleType::kInt16},
      {"int16", SampleType::kInt16},        {"int16_t", SampleType::kInt16},
      {"ushort", SampleType::kUint16},      {"unsigned short", SampleType::kUint16},
      {"unsigned short int", SampleType::kUint16}, {"uint16", SampleType::kUint16},
      {"uint16_t", SampleType::kUint16},    {"int", SampleType::kInt32},
      {"signed int", SampleType::kInt32},   {"int32", SampleType::kInt32},
      {"int32_t", SampleType::kInt32},      {"float", SampleType::kFloat32},
      {"double", SampleType::kFloat64},     {"Short", SampleType::kInt16},
  };
  for (const auto& k : kSpellings) {
    const size_t n = 6 * sampleSize(k.type);
    std::vector<uint8_t> data(n);
    for (size_t i = 0; i < n; ++i) data[i] = static_cast<uint8_t>(i * 7 + 1);
    std::string head = std::string("NRRD0004\ntype: ") + k.spelling + "\ndimension: 2\nsizes: 3 2\n" +
                       "endian: little\nencoding: raw\n\n";
    GridInput in;
    std::string error;
    ASSERT_TRUE(read(GridFormat::kNrrd, concat(bytesOf(head), data), &in, &error)) << k.spelling << ": " << error;
    EXPECT_EQ(in.header.sample_type, k.type) << k.spelling;
    EXPECT_EQ(in.samples, data) << k.spelling;
  }
}

TEST(GridFormatsNrrd, HandWrittenHeaderVariants) {
  // A real 3-D block: the first 4x3x2 samples of the VTK head CT (uint16).
  test::SharedGrid grid = shared("volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst");
  std::vector<uint8_t> le = firstSamples(grid, 24), be = le;
  swapSampleBytes(&be, 2);
  const struct {
    const char* header;
    bool big;
    const char* spacing;  // metadata expected, "" for none
    const char* origin;
  } kCases[] = {
      // Every version, CRLF line ends, comments, key:=value pairs, descriptive fields.
      {"NRRD0001\ntype: ushort\ndimension: 3\nsizes: 4 3 2\nendian: little\nencoding: raw\n\n", false, "", ""},
      {"NRRD0005\r\n# a comment\r\ntype: unsigned short\r\ndimension: 3\r\nsizes: 4 3 2\r\n"
       "endian: big\r\nencoding: raw\r\nmodality:=CT\r\nkinds: domain domain domain\r\n\r\n", true, "", ""},
      // Spacings, space origin with and without blanks in the vector.
      {"NRRD0004\ntype: uint16\ndimension: 3\nspace: left-posterior-superior\nsizes: 4 3 2\n"
       "space directions: (3.2,0,0) (0,3.2,0) (0,0,1.5)\nspace origin: (-1.5, 2, 30.25)\n"
       "endian: big\nencoding: raw\n\n", true, "", "-1.5,2,30.25"},
      {"NRRD0003\ntype: uint16\ndimension: 3\nsizes: 4 3 2\nspacings: 3.2 3.2 1.5\n"
       "space origin: (0,0,0)\nendian: little\nencoding: raw\nline skip: 0\nbyte skip: 0\n\n",
       false, "3.2,3.2,1.5", "0,0,0"},
      // Unknown spacings (nan) give no metadata; field names are case-blind.
      {"NRRD0004\nTYPE: uint16\nDimension: 3\nsizes: 4 3 2\nspacings: nan nan nan\nEndian: Little\n"
       "Encoding: RAW\n\n", false, "", ""},
      // No encoding field: raw, the format's only encoding before NRRD0002.
      {"NRRD0004\ntype: uint16\ndimension: 3\nsizes: 4 3 2\nendian: little\n\n", false, "", ""},
  };
  for (const auto& c : kCases) {
    GridInput in;
    std::string error;
    ASSERT_TRUE(read(GridFormat::kNrrd, concat(bytesOf(c.header), c.big ? be : le), &in, &error))
        << c.header << error;
    EXPECT_EQ(in.header.num_dims, 3);
    EXPECT_EQ(in.header.size_x, 4u);
    EXPECT_EQ(in.header.size_y, 3u);
    EXPECT_EQ(in.header.size_z, 2u);
    EXPECT_EQ(in.samples, le) << c.header;
    const std::string* spacing = in.metadata.find("spacing");
    const std::string* origin = in.metadata.find("origin");
    EXPECT_EQ(spacing ? *spacing : "", c.spacing) << c.header;
    EXPECT_EQ(origin ? *origin : "", c.origin) << c.header;
  }
}

TEST(GridFormatsNrrd, OneAndTwoDimensionsAndUint8WithoutEndian) {
  test::SharedGrid grid = shared("volume/ct_tooth_103x94x161_uint8.raw.zst");
  std::vector<uint8_t> data = firstSamples(grid, 12);
  GridInput in;
  std::string error;
  ASSERT_TRUE(read(GridFormat::kNrrd,
                   concat(bytesOf("NRRD0004\ntype: uchar\ndimension: 1\nsizes: 12\nencoding: raw\n\n"), data),
                   &in, &error)) << error;
  EXPECT_EQ(in.header.num_dims, 1);
  EXPECT_EQ(in.header.size_x, 12u);
  EXPECT_EQ(in.samples, data);
  ASSERT_TRUE(read(GridFormat::kNrrd,
                   concat(bytesOf("NRRD0004\ntype: uchar\ndimension: 2\nsizes: 4 3\nspacings: 1 2\n\n"), data),
                   &in, &error)) << error;
  EXPECT_EQ(in.header.num_dims, 2);
  EXPECT_EQ(in.header.size_y, 3u);
  ASSERT_NE(in.metadata.find("spacing"), nullptr);
  EXPECT_EQ(*in.metadata.find("spacing"), "1,2");
}

TEST(GridFormatsNrrd, UnsupportedFeaturesAndMalformedHeadersGiveOneLine) {
  const std::string ok_head = "type: int16\ndimension: 2\nsizes: 2 2\nendian: little\n";
  const std::vector<uint8_t> data(8, 1);
  const struct {
    std::string header;
    const char* what;
  } kCases[] = {
      {"", "line 1: not an NRRD file"},
      {"NRRD0006\n" + ok_head + "\n", "line 1: not an NRRD file"},
      {"NRRD\n" + ok_head + "\n", "line 1: not an NRRD file"},
      {"P5\n2 2\n255\n", "line 1: not an NRRD file"},
      {"NRRD0004\ntype: int16\ndimension 2\n\n", "line 3: 'dimension 2' is not a comment or a 'field: value' line"},
      {"NRRD0004\ndimension: 2\nsizes: 2 2\nendian: little\n\n", "the header has no 'type' field"},
      {"NRRD0004\ntype: int16\nsizes: 2 2\nendian: little\n\n", "the header has no 'dimension' field"},
      {"NRRD0004\ntype: int16\ndimension: 2\nendian: little\n\n", "the header has no 'sizes' field"},
      {"NRRD0004\ntype: int16\ndimension: 2\nsizes: 2 2\n\n", "the header has no 'endian' field, which int16"},
      {"NRRD0004\ntype: int8\ndimension: 2\nsizes: 2 2\n\n", "line 2: field 'type' 'int8' is not one of"},
      {"NRRD0004\ntype: uint32\ndimension: 2\nsizes: 2 2\nendian: little\n\n", "field 'type' 'uint32'"},
      {"NRRD0004\ntype: block\nblock size: 2\ndimension: 2\nsizes: 2 2\n\n", "field 'type' 'block'"},
      {"NRRD0004\n" + ok_head + "encoding: ascii\n\n", "line 6: field 'encoding' 'ascii' is not supported"},
      {"NRRD0004\n" + ok_head + "encoding: text\n\n", "field 'encoding' 'text' is not supported"},
      {"NRRD0004\n" + ok_head + "encoding: gzip\n\n", "field 'encoding' 'gzip' is not supported"},
      {"NRRD0004\n" + ok_head + "encoding: gz\n\n", "field 'encoding' 'gz' is not supported"},
      {"NRRD0004\n" + ok_head + "encoding: bzip2\n\n", "field 'encoding' 'bzip2' is not supported"},
      {"NRRD0004\n" + ok_head + "encoding: hex\n\n", "field 'encoding' 'hex' is not supported"},
      {"NRRD0004\n" + ok_head + "data file: head.raw\n\n", "line 6: field 'data file': detached data is not supported"},
      {"NRRD0004\n" + ok_head + "datafile: LIST\n\n", "field 'data file': detached"},
      {"NRRD0004\n" + ok_head + "byte skip: -1\n\n", "line 6: field 'byte skip' -1 is not supported"},
      {"NRRD0004\n" + ok_head + "line skip: 3\n\n", "field 'line skip' 3 is not supported"},
      {"NRRD0004\ntype: int16\ndimension: 2\nsizes: 2 2\nendian: middle\n\n", "line 5: field 'endian' 'middle' is not little or big"},
      {"NRRD0004\ntype: int16\ndimension: 4\nsizes: 2 2 1 1\nendian: little\n\n", "line 3: field 'dimension' '4' is not 1, 2 or 3"},
      {"NRRD0004\ntype: int16\ndimension: 2x\nsizes: 2 2\nendian: little\n\n", "field 'dimension' '2x'"},
      {"NRRD0004\ntype: int16\ndimension: 3\nsizes: 2 2\nendian: little\n\n", "line 4: field 'sizes' has 2 numbers, not 'dimension' (3)"},
      {"NRRD0004\ntype: int16\ndimension: 2\nsizes: 2 0\nendian: little\n\n", "line 4: field 'sizes': dimensions must be at least 1"},
      {"NRRD0004\ntype: int16\ndimension: 2\nsizes: 2 -2\nendian: little\n\n", "field 'sizes': '-2' is not a positive whole number"},
      {"NRRD0004\ntype: int16\ndimension: 2\nsizes: 2 99999999999\nendian: little\n\n", "field 'sizes'"},
      {"NRRD0004\ntype: int16\ndimension: 2\nsizes: 2 20000000\nendian: little\n\n", "size_y must be 1 to"},
      {"NRRD0004\n" + ok_head + "spacings: 1 1 1\n\n", "line 6: field 'spacings' has 3 numbers, not one per axis (2)"},
      {"NRRD0004\n" + ok_head + "spacings: 1 abc\n\n", "field 'spacings' '1 abc' is not a list of decimal numbers"},
      {"NRRD0004\n" + ok_head + "space origin: (0,0,0)\n\n", "field 'space origin' has 3 numbers"},
      {"NRRD0004\n" + ok_head + "space origin: (0,x)\n\n", "field 'space origin' '(0,x)' is not a list"},
      // A binary value is shown tamed, keeping the error on one line.
      {"NRRD0004\ntype: \x01\x02\rshort\ndimension: 2\nsizes: 2 2\n\n", "field 'type' '???short'"},
  };
  for (const auto& c : kCases) expectError(GridFormat::kNrrd, concat(bytesOf(c.header), data), c.what);
  expectError(GridFormat::kNrrd, bytesOf("NRRD0004\n" + ok_head), "line 5: the header does not end with a blank line");
  // Data shorter or longer than the sizes.
  std::vector<uint8_t> head = bytesOf("NRRD0004\n" + ok_head + "\n");
  expectError(GridFormat::kNrrd, concat(head, std::vector<uint8_t>(7)), "file has 7 bytes of samples but 2x2x1 int16 needs 8");
  expectError(GridFormat::kNrrd, concat(head, std::vector<uint8_t>(9)), "file has 9 bytes");
}

// --- PGM --------------------------------------------------------------------

TEST(GridFormatsPgm, OurWriterRoundTripsRealSlices) {
  // An 8-bit CT slice and a 16-bit one (most significant byte first in the file).
  for (const char* name : {"volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst",
                           "volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst"}) {
    test::SharedGrid grid = shared(name);
    GridHeader slice = grid.header;
    slice.num_dims = 2;
    slice.size_z = 1;
    // Slice 40: inside the head, not the empty first slices.
    const size_t slice_bytes = size_t{slice.size_x} * slice.size_y * sampleSize(slice.sample_type);
    std::vector<uint8_t> samples(grid.samples.begin() + static_cast<long>(40 * slice_bytes),
                                 grid.samples.begin() + static_cast<long>(41 * slice_bytes));
    const uint32_t size[3] = {slice.size_x, slice.size_y, 1};
    std::vector<uint8_t> file;
    std::string error;
    ASSERT_TRUE(encodeGridOutput("slice.pgm", slice, Metadata{}, size, samples, false, &file, &error)) << error;
    GridInput in;
    ASSERT_TRUE(read(GridFormat::kPgm, file, &in, &error)) << name << ": " << error;
    EXPECT_EQ(in.header.num_dims, 2);
    EXPECT_EQ(in.header.size_x, slice.size_x);
    EXPECT_EQ(in.header.size_y, slice.size_y);
    EXPECT_EQ(in.header.sample_type, slice.sample_type);
    EXPECT_TRUE(in.samples == samples) << name;
  }
}

// Slice 40 of the 12-bit VTK head CT as P5 and P2 with maxval 4095 and comments.
TEST(GridFormatsPgm, HandWrittenP5AndP2WithCommentsAndMaxval) {
  test::SharedGrid grid = shared("volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst");
  std::vector<uint8_t> le(grid.samples.begin() + 40 * 64 * 64 * 2, grid.samples.begin() + 41 * 64 * 64 * 2);
  std::vector<uint8_t> be = le;
  swapSampleBytes(&be, 2);
  std::string plain = "P2\n# VTK headsq slice 40\n64 # width\n64\n4095\n";
  for (size_t i = 0; i < le.size(); i += 2)
    plain += std::to_string(le[i] | le[i + 1] << 8) + ((i / 2) % 17 == 16 ? "\n" : " ");
  plain += "\n# end\n";
  for (const auto& file : {concat(bytesOf("P5 # 16-bit\n#second comment\n64\t64\r\n4095\n"), be),
                           bytesOf(plain)}) {
    GridInput in;
    std::string error;
    ASSERT_TRUE(read(GridFormat::kPgm, file, &in, &error)) << error;
    EXPECT_EQ(in.header.size_x, 64u);
    EXPECT_EQ(in.header.size_y, 64u);
    EXPECT_EQ(in.header.sample_type, SampleType::kUint16);
    EXPECT_TRUE(in.samples == le);
  }
  // maxval 255 is one byte per sample, 256 two.
  GridInput in;
  std::string error;
  ASSERT_TRUE(read(GridFormat::kPgm, bytesOf("P2 2 1 255 0 255"), &in, &error)) << error;
  EXPECT_EQ(in.header.sample_type, SampleType::kUint8);
  EXPECT_EQ(in.samples, (std::vector<uint8_t>{0, 255}));
  ASSERT_TRUE(read(GridFormat::kPgm, bytesOf("P2 2 1 256 0 256"), &in, &error)) << error;
  EXPECT_EQ(in.header.sample_type, SampleType::kUint16);
  EXPECT_EQ(in.samples, (std::vector<uint8_t>{0, 0, 0, 1}));
  ASSERT_TRUE(read(GridFormat::kPgm, bytesOf("P5 1 1 1\n\x01"), &in, &error)) << error;
  EXPECT_EQ(in.samples, (std::vector<uint8_t>{1}));
}

TEST(GridFormatsPgm, MalformedFilesGiveOneLine) {
  const struct {
    std::string file;
    const char* what;
  } kCases[] = {
      {"", "offset 0: not a PGM file (it must start with P5 or P2)"},
      {"P6 1 1 255\n\x01\x02\x03", "offset 0: not a PGM file"},
      {"P52 2 255\n", "offset 2: the magic number is not followed by white space"},
      {"P5", "offset 2: expected the width (a decimal number) but the file ends"},
      {"P5 x 2 255\n", "offset 3: expected the width"},
      {"P5 2 2\n", "offset 7: expected the maxval (a decimal number) but the file ends"},
      {"P5 1234567890 2 255\n", "offset 3: width has more than 9 digits"},
      {"P5 2a 2 255\n", "offset 4: width is not followed by white space"},
      {"P5 0 2 255\n", "width and height must be at least 1"},
      {"P5 2 2 0\n", "maxval must be 1 to 65535"},
      {"P5 2 2 65536\n", "maxval must be 1 to 65535"},
      {"P5 2 2 255", "offset 10: the file ends after maxval"},
      {"P5 1 1 255#c\n\x01", "offset 10: maxval is not followed by one white-space byte"},
      {"P5 20000000 2 255\n", "size_x must be 1 to"},
      {"P5 2 1 100\n\x05\xC8", "offset 12: sample 200 is above maxval 100"},
      {std::string("P5 2 1 1000\n\x00\x05\x03\xE9", 16), "offset 14: sample 1001 is above maxval 1000"},
      {std::string("P5 2 2 255\n\x00\x01\x02", 14), "file has 3 bytes of samples but 2x2x1 uint8 needs 4"},
      {"P2 2 2 255 1 2 3", "expected the next sample (a decimal number) but the file ends"},
      {"P2 2 1 255 1 x", "offset 13: expected the next sample"},
      {"P2 2 1 255 1 256", "offset 13: sample 256 is above maxval 255"},
      {"P2 2 1 255 1 2 3", "offset 15: data after the 2x1 samples"},
      {"P2 1000 1000 255 1 2 3", "the file is too short for 1000x1000 samples"},
  };
  for (const auto& c : kCases) expectError(GridFormat::kPgm, bytesOf(c.file), c.what);
}

// --- SRTM .hgt ----------------------------------------------------------------

// The three SRTM-3 tiles, written as .hgt (big-endian) files and read by path:
// size from the file length, the voids as nodata -32768.
TEST(GridFormatsHgt, RealSrtm3TilesWithVoids) {
  const struct {
    const char* raw;
    const char* hgt;
    size_t voids;  // from ../shared/data/README.md
  } kTiles[] = {
      {"terrain/srtm3_N46W122_mt_rainier_1201x1201_int16le.raw.zst", "N46W122.hgt", 9033},
      {"terrain/srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", "N35E138.HGT", 2437},
      {"terrain/srtm3_N27E086_mt_everest_1201x1201_int16le.raw.zst", "N27E086.hgt", 130953},
  };
  std::string dir = testing::TempDir() + "mrsv-hgt-XXXXXX";
  ASSERT_NE(mkdtemp(dir.data()), nullptr);
  for (const auto& tile : kTiles) {
    test::SharedGrid grid = shared(tile.raw);
    std::vector<uint8_t> file = grid.samples;
    swapSampleBytes(&file, 2);
    std::string path = dir + "/" + tile.hgt;
    std::string error;
    ASSERT_EQ(gridFormatOf(path), GridFormat::kHgt);
    ASSERT_TRUE(writeFileAtomically(path, file, &error)) << error;
    GridInput in;
    ASSERT_TRUE(readGridInput(path, RawLayout{}, &in, &error)) << error;
    unlink(path.c_str());
    EXPECT_EQ(in.header.num_dims, 2);
    EXPECT_EQ(in.header.size_x, 1201u);
    EXPECT_EQ(in.header.size_y, 1201u);
    EXPECT_EQ(in.header.sample_type, SampleType::kInt16);
    EXPECT_TRUE(in.header.hasNodata());
    EXPECT_EQ(in.header.nodata_bits, 0x8000u);
    EXPECT_TRUE(in.samples == grid.samples) << tile.hgt;
    size_t voids = 0;
    for (size_t i = 0; i < in.samples.size(); i += 2) {
      int16_t v;
      std::memcpy(&v, &in.samples[i], 2);
      voids += v == -32768;
    }
    EXPECT_EQ(voids, tile.voids) << tile.hgt;
    ASSERT_NE(in.metadata.find("crs"), nullptr);
    EXPECT_EQ(*in.metadata.find("crs"), "EPSG:4326");
  }
  rmdir(dir.c_str());
}

TEST(GridFormatsHgt, OneArcSecondSizeAndBadSizes) {
  GridInput in;
  std::string error;
  ASSERT_TRUE(read(GridFormat::kHgt, std::vector<uint8_t>(2u * 3601 * 3601), &in, &error)) << error;
  EXPECT_EQ(in.header.size_x, 3601u);
  EXPECT_EQ(in.header.size_y, 3601u);
  for (size_t size : {size_t{0}, size_t{2}, size_t{2 * 1201 * 1201 + 1}, size_t{2 * 1201 * 1200}})
    expectError(GridFormat::kHgt, std::vector<uint8_t>(size),
                "file size " + std::to_string(size) + " bytes is not a square of at least 2x2 int16 samples");
}

// --- headerless raw and file errors -------------------------------------------

TEST(GridFormatsRaw, LayoutFromOptionsBothByteOrdersAndErrors) {
  test::SharedGrid grid = shared("terrain/mt_st_helens_317x460_int16le.raw.zst");
  RawLayout raw;
  raw.has_layout = true;
  raw.header = grid.header;
  std::vector<uint8_t> be = grid.samples;
  swapSampleBytes(&be, 2);
  GridInput in;
  std::string error;
  for (bool big : {false, true}) {
    raw.big_endian = big;
    ASSERT_TRUE(readGridBytes("in.raw", GridFormat::kRaw, raw, big ? be : grid.samples, &in, &error)) << error;
    EXPECT_TRUE(in.samples == grid.samples);
  }
  EXPECT_FALSE(readGridBytes("in.raw", GridFormat::kRaw, raw, firstSamples(grid, 100), &in, &error));
  EXPECT_EQ(error, "in.raw: file has 200 bytes of samples but 317x460x1 int16 needs 291640");
  EXPECT_FALSE(readGridBytes("in.raw", GridFormat::kRaw, RawLayout{}, grid.samples, &in, &error));
  EXPECT_EQ(error, "in.raw: headerless raw input needs --dims and --type");
  EXPECT_FALSE(readGridInput("/nonexistent/x.nrrd", RawLayout{}, &in, &error));
  EXPECT_EQ(error, "/nonexistent/x.nrrd: No such file or directory");
}

TEST(GridFormatsRaw, FormatFromTheExtensionInAnyCase) {
  EXPECT_EQ(gridFormatOf("a/b.NRRD"), GridFormat::kNrrd);
  EXPECT_EQ(gridFormatOf("b.pgm"), GridFormat::kPgm);
  EXPECT_EQ(gridFormatOf("N46W122.hgt"), GridFormat::kHgt);
  EXPECT_EQ(gridFormatOf("x.raw"), GridFormat::kRaw);
  EXPECT_EQ(gridFormatOf("nrrd"), GridFormat::kRaw);
}

}  // namespace
}  // namespace mrsv
