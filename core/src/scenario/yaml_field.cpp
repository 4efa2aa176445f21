#include "scenario/yaml_field.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::detail {

YamlField::YamlField(YAML::Node node, std::string path, const std::string& source)
    : node_(std::move(node)), path_(std::move(path)), source_(&source) {}

std::string YamlField::text() const {
  if (node_.IsScalar()) return node_.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node_;
  return out.c_str();
}

void YamlField::fail(const std::string& problem) const {
  // The top-level mapping's line is just where the file starts: not worth printing.
  const YAML::Mark mark = node_.Mark();
  const bool top = path_.empty();
  const std::string where = !top && mark.line >= 0 ? fmt::format(" (line {})", mark.line + 1) : "";
  throw ConfigError(
      fmt::format("{}: {}: {}{}", *source_, top ? "(top level)" : path_, problem, where));
}

YamlField YamlField::required(const std::string& key) const {
  if (!node_.IsMap()) fail(fmt::format("expected a mapping with '{}', got '{}'", key, text()));
  const YAML::Node child = node_[key];
  if (!child) fail(fmt::format("missing field '{}'", key));
  return YamlField(child, path_.empty() ? key : path_ + "." + key, *source_);
}

std::optional<YamlField> YamlField::optional(const std::string& key) const {
  if (!node_.IsMap()) fail(fmt::format("expected a mapping, got '{}'", text()));
  const YAML::Node child = node_[key];
  if (!child || child.IsNull()) return std::nullopt;
  return YamlField(child, path_.empty() ? key : path_ + "." + key, *source_);
}

void YamlField::allow_only(std::initializer_list<std::string_view> allowed) const {
  allow_only(std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

void YamlField::allow_only(std::span<const std::string_view> allowed) const {
  if (!node_.IsMap()) fail(fmt::format("expected a mapping, got '{}'", text()));
  for (const auto& entry : node_) {
    // YAML allows any node as a key (`? [a, b] : 1`); as<std::string>() would throw yaml-cpp's
    // own exception for those, past every caller that expects a ConfigError.
    const YamlField key_field(entry.first, path_, *source_);
    if (!key_field.is_scalar()) {
      key_field.fail(fmt::format("expected a field name, got '{}'", key_field.text()));
    }
    const std::string key = entry.first.Scalar();
    const bool known = std::any_of(allowed.begin(), allowed.end(),
                                   [&](std::string_view name) { return key == name; });
    if (!known) {
      YamlField(entry.first, path_.empty() ? key : path_ + "." + key, *source_)
          .fail(fmt::format("unknown field (allowed: {})", fmt::join(allowed, ", ")));
    }
  }
}

double YamlField::number() const {
  double value = 0.0;
  if (!node_.IsScalar() || !YAML::convert<double>::decode(node_, value)) {
    fail(fmt::format("expected a number, got '{}'", text()));
  }
  if (!std::isfinite(value)) fail(fmt::format("must be finite, got '{}'", text()));
  return value;
}

double YamlField::positive_number() const {
  const double value = number();
  if (value <= 0.0) fail(fmt::format("must be > 0, got {}", text()));
  return value;
}

double YamlField::non_negative_number() const {
  const double value = number();
  if (value < 0.0) fail(fmt::format("must be >= 0, got {}", text()));
  return value;
}

std::int64_t YamlField::integer() const {
  std::int64_t value = 0;
  if (!node_.IsScalar() || !YAML::convert<std::int64_t>::decode(node_, value)) {
    fail(fmt::format("expected an integer, got '{}'", text()));
  }
  return value;
}

bool YamlField::boolean() const {
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value)) {
    fail(fmt::format("expected true or false, got '{}'", text()));
  }
  return value;
}

std::string YamlField::string() const {
  if (!node_.IsScalar()) fail(fmt::format("expected a string, got '{}'", text()));
  return node_.Scalar();
}

std::vector<YamlField> YamlField::sequence() const {
  if (!node_.IsSequence()) fail(fmt::format("expected a list, got '{}'", text()));
  std::vector<YamlField> items;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    items.emplace_back(node_[i], fmt::format("{}[{}]", path_, i), *source_);
  }
  return items;
}

Eigen::VectorXd YamlField::numbers(int n) const {
  const std::vector<YamlField> items = sequence();
  if (static_cast<int>(items.size()) != n) {
    fail(fmt::format("expected a list of {} numbers, got '{}'", n, text()));
  }
  Eigen::VectorXd values(n);
  for (int i = 0; i < n; ++i) values(i) = items[static_cast<std::size_t>(i)].number();
  return values;
}

}  // namespace skyfuse::detail
