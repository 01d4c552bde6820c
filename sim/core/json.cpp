#include "sim/core/json.hpp"

#include <cmath>
#include <cstdio>

namespace formsim::sim {

Json& Json::operator[](const std::string& key) {
  if (type_ == Type::kNull) type_ = Type::kObject;
  for (auto& kv : object_)
    if (kv.first == key) return kv.second;
  object_.emplace_back(key, Json());
  return object_.back().second;
}

void Json::Push(Json v) {
  if (type_ == Type::kNull) type_ = Type::kArray;
  array_.push_back(std::move(v));
}

const Json* Json::Get(const std::string& key) const {
  for (const auto& kv : object_)
    if (kv.first == key) return &kv.second;
  return nullptr;
}

static void Escape(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
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
      if (std::isfinite(number_)) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.10g", number_);
        out += buf;
      } else {
        out += "null";
      }
      break;
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
