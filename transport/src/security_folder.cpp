#include "skyfuse/transport/security_folder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

namespace skyfuse::transport {
namespace {

constexpr std::string_view kParticipantPrefix = "skyfuse-";
constexpr std::string_view kStationPrefix = "station-";

int listed_station_count(const std::vector<std::string>& identities) {
  return static_cast<int>(std::count_if(identities.begin(), identities.end(),
                                        [](const auto& id) { return is_station_identity(id); }));
}

// What a user needs to read when the folder lacks an identity: which, what the folder holds,
// and the command that makes one that fits.
std::string missing_identity_message(const SecurityFolder& folder, const std::string& identity,
                                     const std::vector<std::string>& listed) {
  std::string message =
      fmt::format("--secure {}: no identity '{}' in it", folder.dir.string(), identity);
  if (is_station_identity(identity)) {
    message += fmt::format(
        " (it was made for {} stations; run `skyfuse certs DIR --stations N` "
        "with N at least the largest station id of the run)",
        listed_station_count(listed));
  }
  return message;
}

}  // namespace

std::string station_identity(int station_id) {
  return fmt::format("{}{}", kStationPrefix, station_id);
}

bool is_station_identity(const std::string& identity) {
  return identity.starts_with(kStationPrefix);
}

std::string identity_for_participant(const std::string& participant_name) {
  if (participant_name.starts_with(kParticipantPrefix)) {
    return participant_name.substr(kParticipantPrefix.size());
  }
  return participant_name;
}

std::vector<std::string> run_identities(const std::vector<int>& station_ids) {
  std::vector<std::string> identities = {kHarnessIdentity, kCenterIdentity};
  for (int id : station_ids) identities.push_back(station_identity(id));
  return identities;
}

std::vector<std::string> SecurityFolder::listed_identities() const {
  std::ifstream in(manifest());
  if (!in) {
    throw SecurityFolderError(
        fmt::format("--secure {}: not a folder written by `skyfuse certs` ({} is missing)",
                    dir.string(), manifest().string()));
  }
  std::vector<std::string> identities;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) identities.push_back(line);
  }
  return identities;
}

void SecurityFolder::check(const std::vector<std::string>& identities) const {
  const std::vector<std::string> listed = listed_identities();
  for (const std::string& identity : identities) {
    if (std::find(listed.begin(), listed.end(), identity) == listed.end()) {
      throw SecurityFolderError(missing_identity_message(*this, identity, listed));
    }
  }
  std::vector<std::filesystem::path> needed = {ca_certificate(), governance(), permissions()};
  for (const std::string& identity : identities) {
    needed.push_back(certificate(identity));
    needed.push_back(private_key(identity));
  }
  for (const auto& file : needed) {
    if (!std::filesystem::is_regular_file(file)) {
      throw SecurityFolderError(
          fmt::format("--secure {}: {} is missing (recreate the folder with "
                      "`skyfuse certs`)",
                      dir.string(), file.string()));
    }
  }
}

}  // namespace skyfuse::transport
