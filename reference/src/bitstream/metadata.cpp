// spec: 2.6 meta chunk.
#include "mrsv/metadata.h"


#include "mrsv/limits.h"

namespace mrsv {
namespace {

bool isKeyChar(unsigned char c, bool first) {
  if (c >= 'a' && c <= 'z') return true;
  if (first) return false;
  return (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
}

// Length of the UTF-8 sequence starting at s[i], 0 if it is not well formed
// (overlong forms, surrogates and code points above U+10FFFF are rejected).
size_t utf8SequenceLength(const std::string& s, size_t i) {
  unsigned char c = static_cast<unsigned char>(s[i]);
  size_t n;
  uint32_t cp;
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) { n = 2; cp = c & 0x1F; }
  else if (c >= 0xE0 && c <= 0xEF) { n = 3; cp = c & 0x0F; }
  else if (c >= 0xF0 && c <= 0xF4) { n = 4; cp = c & 0x07; }
  else return 0;
  if (s.size() - i < n) return 0;
  for (size_t k = 1; k < n; ++k) {
    unsigned char cc = static_cast<unsigned char>(s[i + k]);
    if ((cc & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (cc & 0x3F);
  }
  if ((n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000) || cp > 0x10FFFF ||
      (cp >= 0xD800 && cp <= 0xDFFF))
    return 0;
  return n;
}

// spec: 2.6 number = [+-] (digits [. digits] | . digits) [(e|E) [+-] digits].
// Checked by grammar, not strtod, so that the host's locale cannot matter.
bool isDecimalNumber(const std::string& s) {
  size_t i = 0, n = s.size();
  auto digits = [&]() {
    size_t start = i;
    while (i < n && s[i] >= '0' && s[i] <= '9') ++i;
    return i - start;
  };
  if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
  size_t whole = digits(), fraction = 0;
  if (i < n && s[i] == '.') {
    ++i;
    fraction = digits();
  }
  if (whole + fraction == 0) return false;
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == n;
}

// spec: 2.6 registered keys whose values are lists of decimal numbers.
bool isNumberListKey(const std::string& key) { return key == "spacing" || key == "origin"; }

bool isNumberList(const std::string& value) {
  size_t count = 0, start = 0;
  while (true) {
    size_t comma = value.find(',', start);
    std::string item = value.substr(start, comma == std::string::npos ? std::string::npos
                                                                       : comma - start);
    if (item.empty()) return false;
    if (!isDecimalNumber(item)) return false;
    ++count;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return count >= 1 && count <= 3;
}

}  // namespace

const std::string* Metadata::find(const std::string& key) const {
  for (const auto& e : entries)
    if (e.first == key) return &e.second;
  return nullptr;
}

void Metadata::set(const std::string& key, const std::string& value) {
  for (auto& e : entries)
    if (e.first == key) {
      e.second = value;
      return;
    }
  entries.emplace_back(key, value);
}

std::string metadataEntryProblem(const std::string& key, const std::string& value) {
  if (key.empty() || key.size() > kMaxMetadataKey)
    return "key must be 1 to " + std::to_string(kMaxMetadataKey) + " bytes";
  for (size_t i = 0; i < key.size(); ++i)
    if (!isKeyChar(static_cast<unsigned char>(key[i]), i == 0))
      return "key '" + key + "' must match [a-z][a-z0-9_.-]*";
  for (size_t i = 0; i < value.size();) {
    unsigned char c = static_cast<unsigned char>(value[i]);
    if (c < 0x20 || c == 0x7F) return "value of '" + key + "' contains a control character";
    size_t n = utf8SequenceLength(value, i);
    if (n == 0) return "value of '" + key + "' is not valid UTF-8";
    i += n;
  }
  if (isNumberListKey(key) && !isNumberList(value))
    return "value of '" + key + "' must be 1 to 3 comma-separated decimal numbers";
  return {};
}

Error parseMetadata(const uint8_t* payload, size_t size, uint64_t payload_offset, Metadata* out) {
  out->entries.clear();
  auto fail = [&](size_t at, std::string message) {
    return Error{Status::kBadMetadata, payload_offset + at, "meta", std::move(message)};
  };
  if (size > kMaxMetadataPayload)
    return fail(0, "payload of " + std::to_string(size) + " bytes exceeds the limit of " +
                       std::to_string(kMaxMetadataPayload));
  size_t pos = 0;
  while (pos < size) {
    size_t eol = pos;
    while (eol < size && payload[eol] != '\n') ++eol;
    if (eol == size) return fail(pos, "entry is not terminated by LF");
    std::string line(reinterpret_cast<const char*>(payload + pos), eol - pos);
    size_t eq = line.find('=');
    if (eq == std::string::npos) return fail(pos, "entry has no '='");
    std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if (std::string problem = metadataEntryProblem(key, value); !problem.empty())
      return fail(pos, problem);
    if (out->find(key)) return fail(pos, "key '" + key + "' appears twice");
    if (out->entries.size() == kMaxMetadataEntries)
      return fail(pos, "more than " + std::to_string(kMaxMetadataEntries) + " entries");
    out->entries.emplace_back(std::move(key), std::move(value));
    pos = eol + 1;
  }
  return {};
}

std::vector<uint8_t> serializeMetadata(const Metadata& metadata) {
  std::vector<uint8_t> out;
  for (const auto& e : metadata.entries) {
    std::string line = e.first + "=" + e.second + "\n";
    out.insert(out.end(), line.begin(), line.end());
  }
  return out;
}

}  // namespace mrsv
