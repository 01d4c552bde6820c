#pragma once
/// \file A minimal ordered JSON value for summaries (objects keep insertion order, so the
/// same run writes the same bytes). Numbers are written as the shortest text that reads back
/// to the same double; integers (seeds, counts) exactly; non-finite numbers as null. Strings
/// are escaped so that any bytes give valid JSON (invalid UTF-8 bytes become \u00XX).

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace formsim::sim {

class Json {
 public:
  enum class Type { kNull, kBool, kNumber, kInteger, kString, kArray, kObject };
  Json() = default;
  Json(double v) : type_(Type::kNumber), number_(v) {}
  Json(int v) : type_(Type::kNumber), number_(v) {}
  Json(long v) : Json(static_cast<long long>(v)) {}
  Json(long long v) : type_(Type::kInteger), number_(static_cast<double>(v)), integer_(std::to_string(v)) {}
  Json(unsigned long long v) : type_(Type::kInteger), number_(static_cast<double>(v)), integer_(std::to_string(v)) {}
  Json(unsigned long v) : Json(static_cast<unsigned long long>(v)) {}
  Json(bool v) : type_(Type::kBool), bool_(v) {}
  Json(const char* s) : type_(Type::kString), string_(s) {}
  Json(std::string s) : type_(Type::kString), string_(std::move(s)) {}
  static Json Object() { Json j; j.type_ = Type::kObject; return j; }
  static Json Array() { Json j; j.type_ = Type::kArray; return j; }

  /// Object access: inserts the key (keeping order) when missing.
  Json& operator[](const std::string& key);
  void Push(Json v);  ///< array append
  Type type() const { return type_; }
  double number() const { return number_; }
  const std::string& str() const { return string_; }
  const Json* Get(const std::string& key) const;  ///< nullptr when absent
  const std::vector<Json>& items() const { return array_; }

  std::string Dump(int indent = 2) const;

 private:
  void DumpTo(std::string& out, int indent, int depth) const;
  Type type_ = Type::kNull;
  double number_ = 0.0;
  bool bool_ = false;
  std::string string_;
  std::string integer_;  ///< exact digits of an integer
  std::vector<Json> array_;
  std::vector<std::pair<std::string, Json>> object_;
};

}  // namespace formsim::sim
