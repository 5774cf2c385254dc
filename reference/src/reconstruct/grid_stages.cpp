// spec: 8.7 the stages of a stream prefix: one per complete wavelet level.
#include "mrsv/grid_mesh.h"
#include <algorithm>

#include "wavelet/axis_plan.h"

namespace mrsv {

std::vector<ReconstructionStage> reconstructionStages(const DecodedGrid& grid, uint64_t size, unsigned levels) {
  std::vector<ReconstructionStage> stages;
  const std::vector<ReconstructionStage> whole = levels == 0 ? std::vector<ReconstructionStage>{{size, 0}}
                                                               : std::vector<ReconstructionStage>{};
  if (grid.header.coding != GridCoding::kWavelet || grid.bands_decoded == 0) return whole;
  const uint32_t samples[3] = {grid.header.size_x, grid.header.size_y, grid.header.size_z};
  const int axis_levels[3] = {grid.wavelet.levels[0], grid.wavelet.levels[1], grid.wavelet.levels[2]};
  wavelet::GridPlan plan;
  if (!wavelet::makeGridPlan(grid.header.num_dims, samples, grid.wavelet.order, axis_levels, &plan)) return whole;
  const std::vector<wavelet::Band> bands = wavelet::bandsOf(plan);
  // The end of each band's chunk, in band order.
  std::vector<uint64_t> band_end;
  for (const ChunkView& c : grid.container.chunks)
    if (c.chunk_type == kChunkBand) band_end.push_back(c.endOffset());
  const size_t decoded = std::min<size_t>({grid.bands_decoded, band_end.size(), bands.size()});
  // After the scaling block the lattice has step 2^L; after the last band of
  // detail level l, 2^(l-1).
  for (size_t j = 1; j <= decoded; ++j) {
    const bool level_done = j == bands.size() || bands[j].level < bands[j - 1].level || bands[j - 1].mask == 0;
    if (level_done) stages.push_back({band_end[j - 1], unsigned(j == 1 ? plan.maxLevels() : bands[j - 1].level - 1)});
  }
  if (stages.empty()) return whole;
  if (levels == 0) {
    // The last stage reads every byte given (a residual after the bands, or
    // bands of an incomplete level, refine its samples).
    stages.back().bytes = size;
    return stages;
  }
  while (!stages.empty() && stages.back().shift < levels) stages.pop_back();
  return stages;
}

}  // namespace mrsv
