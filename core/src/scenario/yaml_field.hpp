#pragma once
// A YAML node that knows where it came from, so that every error names the source, the field
// path and the value. Private to the loader: yaml-cpp never appears in a public header.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "skyfuse/core/types.hpp"

namespace skyfuse::detail {

class YamlField {
 public:
  YamlField(YAML::Node node, std::string path, const std::string& source);

  const std::string& path() const { return path_; }
  bool is_scalar() const { return node_.IsScalar(); }
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  /// The value as the user wrote it, for error messages.
  std::string text() const;

  YamlField required(const std::string& key) const;
  std::optional<YamlField> optional(const std::string& key) const;
  /// Refuses keys outside `allowed`, so a misspelt field is not silently ignored.
  void allow_only(std::initializer_list<std::string_view> allowed) const;
  void allow_only(std::span<const std::string_view> allowed) const;

  double number() const;
  double positive_number() const;
  double non_negative_number() const;
  std::int64_t integer() const;
  bool boolean() const;  ///< true or false, as YAML spells them
  std::string string() const;
  std::vector<YamlField> sequence() const;
  /// A sequence of exactly n finite numbers.
  Eigen::VectorXd numbers(int n) const;

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  YAML::Node node_;
  std::string path_;
  const std::string* source_;
};

}  // namespace skyfuse::detail
