#pragma once
/// \file A minimal ordered JSON value for summaries (objects keep insertion order, so the
/// same run writes the same bytes). Non-finite numbers are written as null.

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace formsim::sim {

class Json {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };
  Json() = default;
  Json(double v) : type_(Type::kNumber), number_(v) {}
  Json(int v) : type_(Type::kNumber), number_(v) {}
  Json(long v) : type_(Type::kNumber), number_(static_cast<double>(v)) {}
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
  std::vector<Json> array_;
  std::vector<std::pair<std::string, Json>> object_;
};

}  // namespace formsim::sim
