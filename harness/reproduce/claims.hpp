#pragma once
// What `skyfuse reproduce` reports for every paper: the paper's claims, each with the number of
// this run that decides it, printed side by side and written to reproduce.json as
//   {"paper": "003", "title": ..., "claims": [{"id", "text", "paper", "value", "unit",
//    "holds"}], "all_hold": ..., "details": {...}}.

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

namespace skyfuse::harness {

struct Claim {
  std::string id;    ///< stable, for scripts: "rmse_below_0_3_m"
  std::string text;  ///< the claim in words, as the paper makes it
  /// What the paper reports: a number, or words where it gives none.
  std::variant<double, std::string> paper;
  double value = 0.0;  ///< this run's number that decides the claim
  std::string unit;
  bool holds = false;
};

struct Reproduction {
  std::string paper;  ///< "000"
  std::string title;
  std::vector<Claim> claims;
  /// Paper-specific figures (tables, settings) for reproduce.json.
  nlohmann::json details = nlohmann::json::object();

  bool all_hold() const;
};

/// The claims as a table: paper's figure, this run's, holds or not; then one verdict line.
void print_claims(const Reproduction& reproduction, std::FILE* out);
void write_reproduce_json(const Reproduction& reproduction, const std::filesystem::path& path);

}  // namespace skyfuse::harness
