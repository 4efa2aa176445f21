#include "integration/run_fixture.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace skyfuse::test {

std::map<std::pair<int, int>, StateRow> read_tracks(const std::filesystem::path& csv) {
  std::map<std::pair<int, int>, StateRow> tracks;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string field;
    std::getline(fields, field, ',');
    const int step = std::stoi(field);
    std::getline(fields, field, ',');
    const int source = std::stoi(field);
    StateRow row{};
    for (double& v : row) {
      std::getline(fields, field, ',');
      v = std::strtod(field.c_str(), nullptr);
    }
    tracks[{step, source}] = row;
  }
  return tracks;
}

}  // namespace skyfuse::test
