#include "skyfuse/options/number_checks.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <system_error>

namespace skyfuse::options {
namespace {

// The whole text as a number, or nothing: no sign of trailing words, spaces or a unit.
template <typename T>
std::optional<T> parse_all(const std::string& text) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end || text.empty()) return std::nullopt;
  return value;
}

std::optional<std::int64_t> whole(const std::string& text) {
  // CLI11 converts "+5" and the like; the check takes what the conversion takes, a leading '+'.
  return parse_all<std::int64_t>(!text.empty() && text.front() == '+' ? text.substr(1) : text);
}

std::optional<double> real(const std::string& text) {
  const auto value =
      parse_all<double>(!text.empty() && text.front() == '+' ? text.substr(1) : text);
  if (!value || !std::isfinite(*value)) return std::nullopt;
  return value;
}

}  // namespace

CLI::Validator whole_number_at_least(std::int64_t low) {
  const std::string wanted = fmt::format("a whole number >= {}", low);
  return CLI::Validator(
      [wanted, low](std::string& text) -> std::string {
        const auto value = whole(text);
        if (value && *value >= low) return {};
        return fmt::format("must be {}, got {}", wanted, text);
      },
      fmt::format("INT>={}", low));
}

CLI::Validator whole_number_in(std::int64_t low, std::int64_t high) {
  const std::string wanted = fmt::format("a whole number from {} to {}", low, high);
  return CLI::Validator(
      [wanted, low, high](std::string& text) -> std::string {
        const auto value = whole(text);
        if (value && *value >= low && *value <= high) return {};
        return fmt::format("must be {}, got {}", wanted, text);
      },
      fmt::format("INT in [{}, {}]", low, high));
}

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const auto value = real(text);
        if (value && *value > 0.0) return {};
        return fmt::format("must be a number > 0, got {}", text);
      },
      "POSITIVE");
}

CLI::Validator non_negative_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const auto value = real(text);
        if (value && *value >= 0.0) return {};
        return fmt::format("must be a number >= 0, got {}", text);
      },
      "NONNEGATIVE");
}

}  // namespace skyfuse::options
