#include "sim/core/json.hpp"

#include <cmath>

#include "sim/core/number_format.hpp"

namespace formsim::sim {

// Keys are searched from the last one: trees are built in order (a summary's thousands of links
// each fill their own object), so the key wanted is almost always the last one.
Json& Json::operator[](const std::string& key) {
  if (type_ == Type::kNull) type_ = Type::kObject;
  for (auto it = object_.rbegin(); it != object_.rend(); ++it)
    if (it->first == key) return it->second;
  object_.emplace_back(key, Json());
  return object_.back().second;
}

void Json::Push(Json v) {
  if (type_ == Type::kNull) type_ = Type::kArray;
  array_.push_back(std::move(v));
}

const Json* Json::Get(const std::string& key) const {
  for (auto it = object_.rbegin(); it != object_.rend(); ++it)
    if (it->first == key) return &it->second;
  return nullptr;
}

// Length of the valid UTF-8 sequence starting at s[i], or 0 when the byte starts none.
static std::size_t Utf8Length(const std::string& s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = b(i);
  std::size_t n = 0;
  unsigned cp = 0;
  if (c >= 0xc2 && c <= 0xdf) n = 2, cp = c & 0x1f;
  else if (c >= 0xe0 && c <= 0xef) n = 3, cp = c & 0x0f;
  else if (c >= 0xf0 && c <= 0xf4) n = 4, cp = c & 0x07;
  else return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(i + k) & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (b(i + k) & 0x3f);
  }
  // Overlong forms, surrogates and code points past U+10FFFF are not valid UTF-8.
  if ((n == 3 && cp < 0x800) || (n == 4 && (cp < 0x10000 || cp > 0x10ffff)) ||
      (cp >= 0xd800 && cp <= 0xdfff))
    return 0;
  return n;
}

static void Escape(std::string& out, const std::string& s) {
  out += '"';
  for (std::size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          AppendSprintf(out, "\\u%04x", c);
        } else if (c < 0x80) {
          out += static_cast<char>(c);
        } else if (const std::size_t n = Utf8Length(s, i)) {
          out.append(s, i, n);
          i += n - 1;
        } else {
          // Not UTF-8: keep the byte visible as the Latin-1 character of the same value.
          AppendSprintf(out, "\\u%04x", c);
        }
    }
  }
  out += '"';
}

void Json::DumpTo(std::string& out, int indent, int depth) const {
  const std::string pad(indent * (depth + 1), ' '), pad_end(indent * depth, ' ');
  const char* nl = indent > 0 ? "\n" : "";
  switch (type_) {
    case Type::kNull: out += "null"; break;
    case Type::kBool: out += bool_ ? "true" : "false"; break;
    case Type::kNumber:
      if (std::isfinite(number_)) AppendDouble(out, number_);
      else out += "null";
      break;
    case Type::kInteger: out += integer_; break;
    case Type::kString: Escape(out, string_); break;
    case Type::kArray:
      if (array_.empty()) { out += "[]"; break; }
      out += "[";
      out += nl;
      for (std::size_t i = 0; i < array_.size(); ++i) {
        out += pad;
        array_[i].DumpTo(out, indent, depth + 1);
        if (i + 1 < array_.size()) out += ",";
        out += nl;
      }
      out += pad_end + "]";
      break;
    case Type::kObject:
      if (object_.empty()) { out += "{}"; break; }
      out += "{";
      out += nl;
      for (std::size_t i = 0; i < object_.size(); ++i) {
        out += pad;
        Escape(out, object_[i].first);
        out += indent > 0 ? ": " : ":";
        object_[i].second.DumpTo(out, indent, depth + 1);
        if (i + 1 < object_.size()) out += ",";
        out += nl;
      }
      out += pad_end + "}";
      break;
  }
}

std::string Json::Dump(int indent) const {
  std::string out;
  DumpTo(out, indent, 0);
  out += '\n';
  return out;
}

}  // namespace formsim::sim
