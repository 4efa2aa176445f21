// `skyfuse run --secure`: real processes over loopback DDS with DDS-Security (M = 4).
//
// - The authorised network reproduces the plain run's files byte for byte.
// - A participant without a certificate from the run's CA - another CA's, or no security at all
//   - speaks for station 2 all through a run and hears nothing: no tick, no increment, no
//   measurement; no reader of the run matches it, and no receiver counts or fuses anything.
// - An identity of the run's CA without a publish grant (observer) is refused its writer.
// - The same probe with an identity of the run's CA is heard and counted: the zeros above come
//   from the CA, not from a probe that cannot listen.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

constexpr int kStations = 4;
constexpr const char* kRunId = "6161";

std::filesystem::path make_certs(const std::filesystem::path& dir) {
  const Completed certs = run_to_completion(
      {bin("skyfuse"), "certs", dir.string(), "--stations", std::to_string(kStations)},
      dir.string() + ".log", 60s);
  EXPECT_EQ(certs.status.code, 0) << certs.output;
  return dir;
}

std::vector<std::string> run_args(int domain, const std::filesystem::path& out,
                                  const std::optional<std::filesystem::path>& secure) {
  std::vector<std::string> args = {
      bin("skyfuse"), "run",  "--stations", std::to_string(kStations), "--steps", "200",
      "--run-id",     kRunId, "--domain",   std::to_string(domain),    "--out",   out.string()};
  if (secure) {
    // Room for several starts: Fast DDS 2.9 sometimes stalls a secure discovery (secure_start.hpp).
    args.insert(args.end(), {"--secure", secure->string(), "--discovery-timeout", "60"});
  }
  return args;
}

Completed run(int domain, const std::filesystem::path& out,
              const std::optional<std::filesystem::path>& secure = std::nullopt) {
  return run_to_completion(run_args(domain, out, secure), out.string() + ".log", 180s);
}

// A probe speaking for station 2 of the run, as `identity` (none: no security), until stopped.
std::unique_ptr<Process> start_probe(int domain, const std::filesystem::path& log,
                                     std::vector<std::string> identity) {
  std::vector<std::string> args = {
      bin("skyfuse-rogue"), "--probe", "--domain", std::to_string(domain),
      "--run-id",           kRunId,    "--victim", "2",
      "--timeout",          "170"};
  args.insert(args.end(), identity.begin(), identity.end());
  return std::make_unique<Process>(args, log);
}

std::string stop(Process& probe) {
  probe.signal(SIGINT);
  const auto status = probe.wait(30s);
  EXPECT_TRUE(status.has_value() && status->exited && status->code == 0) << probe.output();
  return probe.output();
}

// The number on the probe's line "probe <what> N"; -1 if there is no such line.
long probe_count(const std::string& output, const std::string& what) {
  std::smatch match;
  if (!std::regex_search(output, match, std::regex("probe " + what + " (\\d+)\\n"))) return -1;
  return std::stol(match[1]);
}

nlohmann::json summary_of(const std::filesystem::path& out) {
  return nlohmann::json::parse(read_file(out / "summary.json"));
}

long refused_in_total(const std::filesystem::path& out) {
  long total = 0;
  for (const auto& [kind, count] : summary_of(out)["dropped_by_kind"].items()) {
    total += count.get<long>();
  }
  return total;
}

void expect_same_files(const std::filesystem::path& a, const std::filesystem::path& b) {
  for (const char* file : {"tracks.csv", "steps.csv", "measurements.csv"}) {
    EXPECT_EQ(read_file(a / file), read_file(b / file)) << file;
  }
}

// Another CA's folder whose permissions its owner rewrote to give every identity every topic:
// an attacker signs whatever grants it likes with its own CA.
std::filesystem::path attacker_certs(const std::filesystem::path& dir) {
  make_certs(dir);
  std::string xml = read_file(dir / "permissions.xml");
  xml = std::regex_replace(xml, std::regex("<subscribe>\\s*<topics>"),
                           "<subscribe><topics><topic>skyfuse_measurement</topic>");
  std::ofstream(dir / "permissions.xml") << xml;
  const Completed signing = run_to_completion(
      {"/usr/bin/openssl", "smime", "-sign", "-text", "-in", (dir / "permissions.xml").string(),
       "-out", (dir / "permissions.p7s").string(), "-signer", (dir / "ca.pem").string(), "-inkey",
       (dir / "ca.key").string()},
      dir.string() + "-sign.log", 30s);
  EXPECT_EQ(signing.status.code, 0) << signing.output;
  return dir;
}

// A fresh folder with the run's identities, and a plain run of the same options to compare
// the secure one with.
struct SecureCase {
  std::filesystem::path dir;
  std::filesystem::path pki;
  Completed plain;
};

SecureCase secure_case(int domain) {
  SecureCase c{test_dir(), {}, {}};
  c.pki = make_certs(c.dir / "pki");
  c.plain = run(domain, c.dir / "plain");
  return c;
}

TEST(DdsSecure, CertsWritesOneIdentityPerNodeAndSignedDocuments) {
  const auto dir = test_dir();
  const Completed certs = run_to_completion(
      {bin("skyfuse"), "certs", (dir / "pki").string(), "--stations", "3"}, dir / "certs.log", 60s);
  ASSERT_EQ(certs.status.code, 0) << certs.output;
  for (const char* name :
       {"harness", "center", "station-1", "station-2", "station-3", "observer"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "pki" / name / "cert.pem")) << name;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "pki" / name / "key.pem")) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "pki" / "station-4"));
  for (const char* file : {"ca.pem", "governance.p7s", "permissions.p7s", "identities.txt"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "pki" / file)) << file;
  }
  EXPECT_THAT(certs.output, HasSubstr("signed grants for 6 identities"));
  EXPECT_THAT(certs.output, HasSubstr("observer/"));
  EXPECT_THAT(certs.output, HasSubstr("publishes nothing"));

  const Completed again =
      run_to_completion({bin("skyfuse"), "certs", (dir / "pki").string()}, dir / "again.log", 60s);
  EXPECT_EQ(again.status.code, 2);
  EXPECT_THAT(again.output, HasSubstr("already holds a certificate authority"));
}

TEST(DdsSecure, AnAuthorisedNetworkReproducesThePlainRun) {
  const SecureCase c = secure_case(160);
  ASSERT_EQ(c.plain.status.code, 0) << c.plain.output;
  const Completed secure = run(160, c.dir / "secure", c.pki);
  ASSERT_EQ(secure.status.code, 0) << secure.output;

  expect_same_files(c.dir / "secure", c.dir / "plain");
  EXPECT_EQ(refused_in_total(c.dir / "secure"), 0);
}

struct Outsider {
  const char* name;
  int domain;
  bool own_ca;  ///< a certificate from another CA; false: no security at all
};

void PrintTo(const Outsider& outsider, std::ostream* os) {
  *os << outsider.name;
}

class DdsSecureOutsider : public ::testing::TestWithParam<Outsider> {};

TEST_P(DdsSecureOutsider, HearsNothingAndGetsNothingFused) {
  const Outsider outsider = GetParam();
  const SecureCase c = secure_case(outsider.domain);
  ASSERT_EQ(c.plain.status.code, 0) << c.plain.output;
  const auto& dir = c.dir;
  std::vector<std::string> identity;
  if (outsider.own_ca) {
    identity = {"--secure", attacker_certs(dir / "attacker").string(), "--identity", "station-2"};
  }

  const auto probe = start_probe(outsider.domain, dir / "probe.log", identity);
  const Completed secure = run(outsider.domain, dir / "secure", c.pki);
  const std::string heard = stop(*probe);
  ASSERT_EQ(secure.status.code, 0) << secure.output;

  // It tried all through the run...
  EXPECT_GT(probe_count(heard, "sent increment"), 0) << heard;
  EXPECT_GT(probe_count(heard, "sent measurement"), 0) << heard;
  // ...and nothing reached it, nor it anyone.
  EXPECT_THAT(heard, HasSubstr("probe heard ticks up to step none"));
  EXPECT_EQ(probe_count(heard, "heard increment"), 0) << heard;
  EXPECT_EQ(probe_count(heard, "heard measurement"), 0) << heard;
  EXPECT_EQ(probe_count(heard, "matched increment readers"), 0) << heard;
  EXPECT_EQ(probe_count(heard, "matched measurement readers"), 0) << heard;
  EXPECT_EQ(refused_in_total(dir / "secure"), 0);
  expect_same_files(dir / "secure", dir / "plain");
}

INSTANTIATE_TEST_SUITE_P(AnotherCaOrNone, DdsSecureOutsider,
                         ::testing::Values(Outsider{"another_ca", 161, true},
                                           Outsider{"no_security", 162, false}),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(DdsSecure, AnObserverMayNotPublishAnIncrement) {
  const int domain = 163;
  const SecureCase c = secure_case(domain);
  ASSERT_EQ(c.plain.status.code, 0) << c.plain.output;
  const auto& [dir, pki, plain] = c;

  Process secure(run_args(domain, dir / "secure", pki), dir / "secure.log");
  const Completed observer =
      run_to_completion({bin("skyfuse-rogue"), "--probe", "--domain", std::to_string(domain),
                         "--run-id", kRunId, "--secure", pki.string(), "--identity", "observer"},
                        dir / "observer.log", 60s);
  const auto status = secure.wait(180s);
  ASSERT_TRUE(status.has_value() && status->code == 0) << secure.output();

  // Its certificate and permissions loaded (the participant exists); only the writer was refused.
  EXPECT_EQ(observer.status.code, 7) << observer.output;
  EXPECT_THAT(observer.output,
              HasSubstr("identity 'observer' may not publish on skyfuse_increment: DDS-Security "
                        "access control refused the writer"));
  EXPECT_EQ(refused_in_total(dir / "secure"), 0);
  expect_same_files(dir / "secure", dir / "plain");
}

TEST(DdsSecure, AnIdentityOfTheRunsCaIsHeardAndItsSamplesAreRefused) {
  const int domain = 164;
  const SecureCase c = secure_case(domain);
  ASSERT_EQ(c.plain.status.code, 0) << c.plain.output;
  const auto& [dir, pki, plain] = c;

  const auto probe =
      start_probe(domain, dir / "probe.log", {"--secure", pki.string(), "--identity", "station-2"});
  const Completed secure = run(domain, dir / "secure", pki);
  const std::string heard = stop(*probe);
  ASSERT_EQ(secure.status.code, 0) << secure.output;

  // Stations' increment readers matched it and it heard the increments... (not always all
  // four: one secure pair in a few never finishes its handshake on Fast DDS 2.9 - the stall
  // the harness restarts a run for, which the probe, started once, cannot escape)
  EXPECT_GE(probe_count(heard, "matched increment readers"), 1) << heard;
  EXPECT_GT(probe_count(heard, "heard increment"), 0) << heard;
  // ...and what it sent in station 2's name reached the receivers, which refused it as coming
  // from a writer other than station 2's: authentication says who may speak, not for whom.
  EXPECT_GT(probe_count(heard, "sent increment"), 0) << heard;
  EXPECT_GT(summary_of(dir / "secure")["dropped_by_kind"]["duplicate"].get<long>(), 0);
  expect_same_files(dir / "secure", dir / "plain");
}

// A run of many aircraft with DDS-Security: every station's picture and the center's the
// in-process run's in every round, as without it. The stations publish scans (flat) or bundles
// (the tree), pictures and whole pictures that their grants must name: one run of each.
TEST(DdsSecure, ManyAircraftHoldTheInProcessPictureInEveryRound) {
  const auto dir = test_dir();
  const auto pki = make_certs(dir / "pki");
  for (const std::string exchange : {"flat", "tree"}) {
    const auto out = dir / exchange;
    const Completed secure = run_to_completion({bin("skyfuse"),
                                                "run",
                                                "--scenario",
                                                bin("scenarios/uam-city.yaml"),
                                                "--stations",
                                                std::to_string(kStations),
                                                "--steps",
                                                "40",
                                                "--exchange",
                                                exchange,
                                                "--fanout",
                                                "2",
                                                "--domain",
                                                "185",
                                                "--secure",
                                                pki.string(),
                                                "--discovery-timeout",
                                                "60",
                                                "--out",
                                                out.string()},
                                               dir / (exchange + ".log"), 180s);
    ASSERT_EQ(secure.status.code, 0) << secure.output;
    const nlohmann::json summary = summary_of(out);
    EXPECT_EQ(summary.at("exchange").get<std::string>(), exchange);
    EXPECT_TRUE(summary.at("peers_identical").get<bool>()) << exchange;
    EXPECT_TRUE(summary.at("equals_in_process").get<bool>()) << exchange;
    EXPECT_TRUE(summary.at("center_equals_in_process").get<bool>()) << exchange;
    EXPECT_EQ(summary.at("steps").get<int>(), 40);
    EXPECT_EQ(refused_in_total(out), 0) << exchange;
  }
}

TEST(DdsSecure, AFolderMadeForFewerStationsOrMissingAKeyIsRefused) {
  const auto dir = test_dir();
  const int domain = 165;
  const Completed certs = run_to_completion(
      {bin("skyfuse"), "certs", (dir / "pki").string(), "--stations", "2"}, dir / "certs.log", 60s);
  ASSERT_EQ(certs.status.code, 0) << certs.output;

  const Completed fewer = run(domain, dir / "fewer", dir / "pki");
  EXPECT_EQ(fewer.status.code, 2);
  EXPECT_THAT(fewer.output, HasSubstr("no identity 'station-3' in it (it was made for 2 stations"));

  std::filesystem::remove(dir / "pki" / "center" / "key.pem");
  const Completed missing =
      run_to_completion({bin("skyfuse"), "run", "--stations", "2", "--steps", "10", "--domain",
                         std::to_string(domain), "--secure", (dir / "pki").string(), "--out",
                         (dir / "missing").string()},
                        dir / "missing.log", 60s);
  EXPECT_EQ(missing.status.code, 2);
  EXPECT_THAT(missing.output,
              HasSubstr((dir / "pki" / "center" / "key.pem").string() + " is missing"));
  EXPECT_TRUE(find_processes({"--domain", std::to_string(domain)}).empty());
}

}  // namespace
}  // namespace skyfuse::test
