#include "reproduce/claims.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "report/output_files.hpp"

namespace skyfuse::harness {
namespace {

std::string paper_figure(const Claim& claim) {
  if (const double* number = std::get_if<double>(&claim.paper)) {
    return fmt::format("{:.4g} {}", *number, claim.unit);
  }
  return std::get<std::string>(claim.paper);
}

}  // namespace

bool Reproduction::all_hold() const {
  return std::all_of(claims.begin(), claims.end(), [](const Claim& c) { return c.holds; });
}

void print_claims(const Reproduction& reproduction, std::FILE* out) {
  fmt::print(out, "\npaper {}: {}\n", reproduction.paper, reproduction.title);
  fmt::print(out, "  {:<58} {:>16} {:>16}  {}\n", "claim", "paper", "this run", "holds");
  for (const Claim& c : reproduction.claims) {
    fmt::print(out, "  {:<58} {:>16} {:>16}  {}\n", c.text, paper_figure(c),
               fmt::format("{:.4g} {}", c.value, c.unit), c.holds ? "yes" : "NO");
  }
  const auto held = std::count_if(reproduction.claims.begin(), reproduction.claims.end(),
                                  [](const Claim& c) { return c.holds; });
  fmt::print(out, "paper {}: {} of {} claims hold{}\n", reproduction.paper, held,
             reproduction.claims.size(), reproduction.all_hold() ? "" : " -- NOT reproduced");
}

void write_reproduce_json(const Reproduction& reproduction, const std::filesystem::path& path) {
  nlohmann::json claims = nlohmann::json::array();
  for (const Claim& c : reproduction.claims) {
    nlohmann::json paper;
    if (const double* number = std::get_if<double>(&c.paper)) {
      paper = *number;
    } else {
      paper = std::get<std::string>(c.paper);
    }
    claims.push_back({{"id", c.id},
                      {"text", c.text},
                      {"paper", paper},
                      {"value", c.value},
                      {"unit", c.unit},
                      {"holds", c.holds}});
  }
  const nlohmann::json doc = {{"paper", reproduction.paper},
                              {"title", reproduction.title},
                              {"claims", claims},
                              {"all_hold", reproduction.all_hold()},
                              {"details", reproduction.details}};
  write_file_atomically(path, doc.dump(2) + "\n");
}

}  // namespace skyfuse::harness
