// mrsv.StreamDecoder: the streaming decoder (stream_decoder.h, spec 2.7) for
// bytes that arrive in pieces (a socket, a download): each chunk decoded once
// when complete, grid levels handed out as their bands arrive.
#include <cstring>
#include <memory>

#include "common.h"
#include "mrsv/stream_decoder.h"

namespace mrsv::python {
namespace {

const char* dtypeName(SampleType type) {
  switch (type) {
    case SampleType::kUint8: return "u1";
    case SampleType::kInt16: return "<i2";
    case SampleType::kUint16: return "<u2";
    case SampleType::kInt32: return "<i4";
    case SampleType::kFloat32: return "<f4";
    default: return "<f8";
  }
}

// Samples (x fastest) as a numpy array of shape (z, y, x) cut to num_dims.
py::array gridArray(const GridHeader& h, const uint32_t size[3], const std::vector<uint8_t>& samples) {
  std::vector<py::ssize_t> shape;
  for (int axis = h.num_dims - 1; axis >= 0; --axis) shape.push_back(size[axis]);
  py::array out(py::dtype(dtypeName(h.sample_type)), shape);
  std::memcpy(out.mutable_data(), samples.data(), samples.size());
  return out;
}

class PyStreamDecoder {
 public:
  PyStreamDecoder() {
    DecodeOptions options;
    options.whole_array_synthesis = true;  // level() synthesises in place (the same samples)
    decoder_ = std::make_unique<StreamDecoder>(options);
  }

  py::list feed(const py::bytes& data) {
    const std::string_view bytes(data);
    Error e;
    std::vector<StreamUnit> units;
    {
      py::gil_scoped_release release;
      e = decoder_->feed(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
      units = decoder_->takeUnits();
    }
    if (!e.ok()) raiseStreamError(e);
    py::list out;
    for (const StreamUnit& u : units) {
      py::dict d;
      d["chunk"] = u.chunk_type.str();
      d["offset"] = u.offset;
      d["end"] = u.end_offset;
      d["index"] = u.index;
      d["complete_level"] = u.complete_level;
      out.append(d);
    }
    return out;
  }

  void finish() {
    Error e;
    {
      py::gil_scoped_release release;
      e = decoder_->finish();
    }
    if (!e.ok()) raiseStreamError(e);
  }

  py::object content() const {
    switch (decoder_->content()) {
      case StreamContent::kGrid: return py::str("grid");
      case StreamContent::kMesh: return py::str("mesh");
      case StreamContent::kTetMesh: return py::str("tets");
      default: return py::none();
    }
  }

  py::object problem() const {
    const Error& p = decoder_->problem();
    if (p.ok()) return py::none();
    py::dict d;
    d["code"] = statusCode(p.status);
    d["offset"] = p.offset;
    d["field"] = p.field;
    d["rule"] = p.message;
    return d;
  }

  py::array level(int r) {
    uint32_t size[3];
    std::vector<uint8_t> samples;
    Error e = decoder_->gridLevelSamples(r, size, &samples);
    if (!e.ok()) {
      if (e.status == Status::kInvalidArgument) throw py::value_error(e.message);
      raiseStreamError(e);
    }
    return gridArray(decoder_->grid().header, size, samples);
  }

  py::array samples() {
    const DecodedGrid& g = decoder_->grid();
    if (!decoder_->finished() || decoder_->content() != StreamContent::kGrid || !g.has_samples)
      throw py::value_error("samples are there once finish() has decoded a grid with sample data");
    return gridArray(g.header, g.output_size, g.samples);
  }

  int completeLevel() const { return decoder_->gridCompleteLevel(); }
  uint64_t bytesFed() const { return decoder_->bytesFed(); }

 private:
  std::unique_ptr<StreamDecoder> decoder_;
};

}  // namespace

void registerStream(py::module_& m) {
  py::class_<PyStreamDecoder>(m, "StreamDecoder", R"doc(A decoder fed bytes as they arrive (spec 2.7).

    d = mrsv.StreamDecoder()
    for piece in pieces:                 # any sizes
        for unit in d.feed(piece):       # chunks decoded by this piece
            if unit["complete_level"] >= 1:
                coarse = d.level(unit["complete_level"])   # coarse to fine, each once
    d.finish()
    samples = d.samples()                # as mrsv.decode gives

feed() raises mrsv.Error on a framing error (final at once); other errors
are raised by finish() (Annex A.2 ranks a later chunk's framing first), and
`problem` tells as soon as a chunk has broken a rule (nothing after it is
decoded). Results equal mrsv.decode of the same bytes, levels mrsv.decode(levels=r).)doc")
      .def(py::init<>())
      .def("feed", &PyStreamDecoder::feed, py::arg("data"),
           "the next bytes; returns the chunks decoded (dicts: chunk, offset, end, index, complete_level)")
      .def("finish", &PyStreamDecoder::finish, "the stream ends: its last rules, then the grid's samples")
      .def("level", &PyStreamDecoder::level, py::arg("r"),
           "a grid's samples r levels above the finest (1 <= r <= complete_level), synthesised from the level above")
      .def("samples", &PyStreamDecoder::samples, "the grid's samples after finish()")
      .def_property_readonly("content", &PyStreamDecoder::content, "'grid', 'mesh', 'tets' or None (not yet known)")
      .def_property_readonly("problem", &PyStreamDecoder::problem, "the first rule broken so far, or None")
      .def_property_readonly("complete_level", &PyStreamDecoder::completeLevel,
                             "the finest grid level whose samples the bytes so far fix (-1: none)")
      .def_property_readonly("bytes_fed", &PyStreamDecoder::bytesFed);
}

}  // namespace mrsv::python
