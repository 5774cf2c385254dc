// File formats are chosen by extension, in any case (mesh and tet formats).
#pragma once

#include <cstddef>
#include <string>

namespace mrsv {

// Whether `path` ends with `extension` (lower case, with its dot), ignoring
// the case of ASCII letters in `path`.
inline bool hasExtension(const std::string& path, const char* extension) {
  const size_t n = std::char_traits<char>::length(extension);
  if (path.size() < n) return false;
  for (size_t i = 0; i < n; ++i) {
    char c = path[path.size() - n + i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != extension[i]) return false;
  }
  return true;
}

}  // namespace mrsv
