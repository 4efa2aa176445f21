#include "commands/certs_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <random>
#include <stdexcept>

#include "report/output_files.hpp"
#include "security/access_grants.hpp"
#include "security/certificate_authority.hpp"
#include "security/security_documents.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::harness {
namespace {

using transport::SecurityFolder;

// Two folders' CAs must be told apart in certificates and messages; the name is not a secret.
std::string fresh_ca_name() {
  std::random_device device;
  return fmt::format("skyfuse CA {:08x}", device());
}

std::string describe(const AccessGrant& g) {
  const auto list = [](const std::vector<std::string>& topics) {
    return topics.empty() ? std::string("nothing") : fmt::format("{}", fmt::join(topics, ", "));
  };
  return fmt::format("publishes {}; subscribes {}", list(g.publish), list(g.subscribe));
}

// Creates the folder, refusing one that already holds a CA: its identities may be in use, and a
// new CA would silently lock them out.
void prepare_folder(const SecurityFolder& folder) {
  if (std::filesystem::exists(folder.ca_certificate())) {
    throw std::invalid_argument(fmt::format(
        "{} already holds a certificate authority; choose a new folder or remove it first",
        folder.dir.string()));
  }
  std::filesystem::create_directories(folder.dir);
  // The CA's and the nodes' private keys live here: owner only.
  std::filesystem::permissions(folder.dir, std::filesystem::perms::owner_all,
                               std::filesystem::perm_options::replace);
}

}  // namespace

void add_certs_command(CLI::App& app, CertsOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "certs",
      "Create a CA, one identity per node (harness, center, stations, an observer) and signed "
      "DDS-Security governance and permissions, for `skyfuse run --secure DIR`");
  cmd->add_option("DIR", o.dir, "Folder to create")->required();
  cmd->add_option("--stations", o.stations,
                  "Station identities station-1 ... station-N (default: every station of the "
                  "embedded scenario)")
      ->check(options::whole_number_in(1, kMaxCertifiedStations));
}

int run_certs(const CertsOptions& o) {
  const int stations =
      o.stations > 0 ? o.stations : static_cast<int>(load_default_scenario().stations.size());
  const SecurityFolder folder{std::filesystem::absolute(o.dir)};
  prepare_folder(folder);

  std::vector<int> station_ids;
  for (int id = 1; id <= stations; ++id) station_ids.push_back(id);
  std::vector<std::string> identities = transport::run_identities(station_ids);
  identities.push_back(transport::kObserverIdentity);

  const CertificateAuthority ca(folder, fresh_ca_name());
  std::vector<AccessGrant> grants;
  for (const std::string& identity : identities) {
    ca.issue_identity(identity);
    grants.push_back(access_grant(identity));
  }
  ca.sign_document(governance_xml(skyfuse_topics()), folder.governance_source(),
                   folder.governance());
  const auto now = std::chrono::system_clock::now();
  // A day of slack before now, so that a clock a little behind this one still accepts them.
  ca.sign_document(
      permissions_xml(grants, now - std::chrono::hours(24), now + std::chrono::hours(24 * 3650)),
      folder.permissions_source(), folder.permissions());
  write_file_atomically(folder.manifest(), fmt::format("{}\n", fmt::join(identities, "\n")));

  fmt::print("skyfuse certs: wrote {} (use: skyfuse run --secure {})\n", folder.dir.string(),
             o.dir);
  fmt::print("  ca.pem ca.key          CA \"{}\", EC prime256v1; identity and permissions CA\n",
             ca.name());
  fmt::print(
      "  governance.p7s         signed domain rules (text: governance.xml): no unauthenticated\n"
      "                         participant, join access control; discovery, liveliness and RTPS\n"
      "                         messages encrypted; {} access-controlled and encrypted\n",
      fmt::join(skyfuse_topics(), ", "));
  fmt::print(
      "  permissions.p7s        signed grants for {} identities, default DENY (text: "
      "permissions.xml)\n",
      identities.size());
  for (const AccessGrant& g : grants) {
    // The stations share one grant: one line for all of them.
    const bool station = transport::is_station_identity(g.identity);
    if (station && g.identity != transport::station_identity(1)) continue;
    const std::string name = station && stations > 1
                                 ? fmt::format("station-1 .. station-{}/", stations)
                                 : g.identity + "/";
    fmt::print("  {:<22} key.pem cert.pem; {}\n", name, describe(g));
  }
  fmt::print("  identities.txt         the {} identities above\n", identities.size());
  return 0;
}

}  // namespace skyfuse::harness
