// spec: 5.7, 5.10, 5.7.6 (encoder side).
#include "grid/array_encoding.h"

#include <algorithm>

#include "bitstream/range_coder_adapter.h"
#include "common/byte_writer.h"
#include "grid/baseline_coding.h"
#include "grid/precincts.h"
#include "grid/weighted_array_coding.h"
#include "grid/weighted_predictor.h"

namespace mrsv {
namespace {

// With no decomposition the coarsest block is the samples, and a void (valid
// 0) costs least when it holds exactly its prediction: its residual is 0, and
// the mask restores the no-data value anyway. Fills in raster order, so that
// each prediction sees the filled values as the decoder will.
void fillVoidsWithPredictions(int64_t* values, const ArrayBox& box, ArrayPrediction prediction,
                              const uint8_t* valid) {
  const size_t sx = box.size[0], sxy = sx * box.size[1];
  if (prediction == ArrayPrediction::kNeighbour) {
    for (uint32_t z = 0; z < box.size[2]; ++z)
      for (uint32_t y = 0; y < box.size[1]; ++y)
        for (uint32_t x = 0; x < box.size[0]; ++x) {
          const size_t i = x + y * sx + z * sxy;
          if (!valid[i]) values[i] = clampArrayValue(predictNeighbour(values, box, x, y, z));
        }
    return;
  }
  WeightedPredictor predictor;
  if (!predictor.init(box.size[0])) return;  // the pull-push fill stays
  for (uint32_t z = 0; z < box.size[2]; ++z)
    for (uint32_t y = 0; y < box.size[1]; ++y) {
      int64_t* row = values + y * sx + z * sxy;
      const int64_t* up = y > 0 ? row - sx : nullptr;
      const int64_t* up2 = y > 1 ? row - 2 * sx : nullptr;
      for (uint32_t x = 0; x < box.size[0]; ++x) {
        const int64_t p = predictor.predict(row, up, up2, x);
        if (!valid[row - values + x]) row[x] = clampArrayValue(p);
        predictor.record(x, row[x]);
      }
      predictor.nextRow();
    }
}

}  // namespace

// Appends one coded array in the stream's entropy mode (spec 5.7 or 5.10).
void encodeArray(uint8_t entropy_mode, int64_t* values, const ArrayBox& box,
                 ArrayPrediction prediction, const uint8_t* skip, std::vector<uint8_t>* out) {
  if (entropy_mode == kEntropyBaseline) {
    encodeBaselineArray(values, box, prediction, skip, out);
    return;
  }
  std::vector<int64_t> symbols(box.count());
  RangeEncoder rc(out);
  EncodingCoder coder{&rc};
  if (prediction == ArrayPrediction::kWeighted)
    codeWeightedArray(coder, values, symbols.data(), box);  // bands only: no skip
  else
    codeArray(coder, values, symbols.data(), box, prediction, skip);
  rc.finish();
}

// spec: 5.7.6 one coded array, in blocks apart when the header has precincts.
// `values` is contiguous over `box`; with `fill_valid` the voids of each coded
// array are filled with its predictions first (the coarsest block of samples).
void encodeBlockedArray(const WaveletHeader& wh, int64_t* values, const ArrayBox& box,
                        const int resolution[3], ArrayPrediction prediction, const uint8_t* skip,
                        const uint8_t* fill_valid, std::vector<uint8_t>* out) {
  if (wh.precinct_log2 == 0) {
    if (fill_valid) fillVoidsWithPredictions(values, box, prediction, fill_valid);
    encodeArray(wh.entropy_mode, values, box, prediction, skip, out);
    return;
  }
  const std::vector<ArrayBlock> blocks = arrayBlocks(box, resolution, wh.precinct_log2);
  const size_t row = box.size[0], slice = row * box.size[1];
  std::vector<uint8_t> coded;
  std::vector<int64_t> block_values;
  std::vector<uint8_t> block_skip, block_valid;
  ByteWriter table(out);
  const size_t table_at = out->size();
  for (size_t i = 0; i < blocks.size(); ++i) table.u32(0);
  for (size_t i = 0; i < blocks.size(); ++i) {
    const ArrayBlock& b = blocks[i];
    block_values.resize(b.box.count());
    copyBlockOut(values, row, slice, b, block_values.data());
    // A block whose values are all 0 is coded as length 0 (nothing to decode).
    if (std::all_of(block_values.begin(), block_values.end(), [](int64_t v) { return v == 0; }))
      continue;
    if (skip) {
      block_skip.resize(b.box.count());
      copyBlockOut(skip, row, slice, b, block_skip.data());
    }
    if (fill_valid) {
      block_valid.resize(b.box.count());
      copyBlockOut(fill_valid, row, slice, b, block_valid.data());
      fillVoidsWithPredictions(block_values.data(), b.box, prediction, block_valid.data());
    }
    coded.clear();
    encodeArray(wh.entropy_mode, block_values.data(), b.box, prediction,
                skip ? block_skip.data() : nullptr, &coded);
    const uint32_t n = static_cast<uint32_t>(coded.size());
    for (int k = 0; k < 4; ++k) (*out)[table_at + 4 * i + k] = static_cast<uint8_t>(n >> (8 * k));
    out->insert(out->end(), coded.begin(), coded.end());
  }
}

std::vector<uint8_t> bandChunkHead(uint16_t index, uint64_t step) {
  std::vector<uint8_t> head;
  ByteWriter w(&head);
  w.u16(index);
  w.u8(0);  // band_flags
  w.u8(0);
  w.u64(step);
  return head;
}

uint8_t encodeCoarsestBand(const WaveletHeader& wh, const std::vector<int64_t>& q, const ArrayBox& box,
                           const int resolution[3], WaveletEncodeOptions::Prediction prediction,
                           const uint8_t* fill_valid, std::vector<uint8_t>* out) {
  using Prediction = WaveletEncodeOptions::Prediction;
  if (wh.entropy_mode != kEntropyAdaptive) prediction = Prediction::kNeighbour;
  const uint8_t choice = prediction == Prediction::kNeighbour  ? kBandPredictionNeighbour
                         : prediction == Prediction::kWeighted ? kBandPredictionWeighted
                                                               : 0;
  // Weighted prediction wins on terrains, the Lorenzo predictor on most CT volumes.
  uint8_t best_flags = 0;
  for (uint8_t code : {kBandPredictionNeighbour, kBandPredictionWeighted}) {
    if (choice != 0 && choice != code) continue;
    std::vector<int64_t> values = q;
    std::vector<uint8_t> coded;
    encodeBlockedArray(wh, values.data(), box, resolution, static_cast<ArrayPrediction>(code), nullptr, fill_valid,
                       &coded);
    if (best_flags == 0 || coded.size() < out->size()) {
      out->swap(coded);
      best_flags = code;
    }
  }
  return best_flags;
}

}  // namespace mrsv
