// What the one-shot grid decoders share with the streaming decoder.
#pragma once

#include "grid/wavelet_decode.h"
#include "mrsv/stream_decoder.h"

namespace mrsv {

// decodeGrid(), and with `keep` decodeGridKeepingCoefficients(): a
// StreamDecoder fed all the bytes at once.
Error decodeGridOneShot(const uint8_t* data, size_t size, const DecodeOptions& options,
                        DecodedGrid* out, WaveletCoefficients* keep);

}  // namespace mrsv
