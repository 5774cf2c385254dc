// The number-list values of the meta keys `spacing` and `origin` (spec 2.6),
// written and read by the grid formats that carry georeferencing.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace mrsv {

// The shortest decimal that reads back as exactly `v` (finite), so that a
// spacing of 30 is written "30" and a geotransform survives a round trip.
inline std::string formatMetaNumber(double v) {
  char text[40];
  for (int precision = 15; precision <= 17; ++precision) {
    std::snprintf(text, sizeof text, "%.*g", precision, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

inline std::string formatMetaNumberList(const std::vector<double>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : ",") + formatMetaNumber(v);
  return out;
}

// "a,b[,c]" to finite numbers; false when any item is not one.
inline bool parseMetaNumberList(const std::string& text, std::vector<double>* values) {
  values->clear();
  for (size_t start = 0; start <= text.size();) {
    size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    std::string item = text.substr(start, comma - start);
    char* end = nullptr;
    double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v)) return false;
    values->push_back(v);
    start = comma + 1;
  }
  return true;
}

}  // namespace mrsv
