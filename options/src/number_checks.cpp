#include "skyfuse/options/number_checks.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

#include "skyfuse/asterix/udp.hpp"

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

// A check that `parse` reads the text and `accept` takes the value; else "must be <wanted>".
template <typename Parse, typename Accept>
CLI::Validator number_check(Parse parse, Accept accept, std::string wanted, std::string name) {
  return CLI::Validator(
      [parse, accept, wanted = std::move(wanted)](std::string& text) -> std::string {
        const auto value = parse(text);
        if (value && accept(*value)) return {};
        return fmt::format("must be {}, got {}", wanted, text);
      },
      std::move(name));
}

}  // namespace

CLI::Validator whole_number_at_least(std::int64_t low) {
  return number_check(
      whole, [low](std::int64_t v) { return v >= low; }, fmt::format("a whole number >= {}", low),
      fmt::format("INT>={}", low));
}

CLI::Validator whole_number_in(std::int64_t low, std::int64_t high) {
  return number_check(
      whole, [low, high](std::int64_t v) { return v >= low && v <= high; },
      fmt::format("a whole number from {} to {}", low, high),
      fmt::format("INT in [{}, {}]", low, high));
}

CLI::Validator positive_number() {
  return number_check(
      real, [](double v) { return v > 0.0; }, "a number > 0", "POSITIVE");
}

CLI::Validator non_negative_number() {
  return number_check(
      real, [](double v) { return v >= 0.0; }, "a number >= 0", "NONNEGATIVE");
}

CLI::Validator udp_endpoint() {
  return CLI::Validator(
      [](const std::string& text) {
        std::string error;
        return asterix::parse_udp_endpoint(text, error) ? std::string() : error;
      },
      "");
}

}  // namespace skyfuse::options
