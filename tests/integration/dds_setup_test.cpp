// Running the system the ways a user sets it up: nodes started by hand (on any host, here one)
// and driven by `skyfuse run --external`, and QoS replaced by a Fast DDS XML file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

TEST(DdsSetup, NodesStartedByHandJoinAHarnessInExternalMode) {
  const auto dir = test_dir();
  const std::vector<std::string> common = {"--stations", "2",    "--steps",  "150",
                                           "--run-id",   "9001", "--domain", "130"};
  auto with = [&](std::vector<std::string> head) {
    head.insert(head.end(), common.begin(), common.end());
    return head;
  };
  Process station1(with({bin("skyfuse-station"), "--id", "1"}), dir / "s1.log");
  Process station2(with({bin("skyfuse-station"), "--id", "2"}), dir / "s2.log");
  Process center(with({bin("skyfuse-center")}), dir / "center.log");
  const Completed harness = run_to_completion(
      with({bin("skyfuse"), "run", "--external", "--out", (dir / "out").string()}),
      dir / "harness.log", 60s);
  ASSERT_EQ(harness.status.code, 0) << harness.output;
  for (Process* p : {&station1, &station2, &center}) {
    const auto status = p->wait(10s);
    ASSERT_TRUE(status.has_value()) << p->output();
    EXPECT_EQ(status->code, 0) << p->output();
  }
  EXPECT_EQ(read_tracks(dir / "out" / "tracks.csv").size(), 150U * 3U);
}

TEST(DdsSetup, AnXmlProfileReplacesTheBuiltInQos) {
  // A tick writer made BEST_EFFORT cannot serve the RELIABLE tick readers of the nodes, so the
  // tick topic never matches: proof that the file's profile, not the built-in one, was used.
  const auto dir = test_dir();
  const auto xml = dir / "profiles.xml";
  std::ofstream(xml) << R"(<?xml version="1.0" encoding="UTF-8"?>
<profiles xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <data_writer profile_name="skyfuse_tick_writer">
    <qos><reliability><kind>BEST_EFFORT</kind></reliability></qos>
  </data_writer>
</profiles>
)";
  const Completed r = run_to_completion(
      {bin("skyfuse"), "run", "--stations", "1", "--steps", "10", "--domain", "131", "--qos",
       xml.string(), "--discovery-timeout", "3", "--out", (dir / "out").string()},
      dir / "run.log", 60s);
  EXPECT_EQ(r.status.code, 1);
  EXPECT_THAT(r.output, HasSubstr("discovery timed out after 3.0 s"));
  EXPECT_THAT(r.output, HasSubstr("tick readers 0/2"));
}

TEST(DdsSetup, RefusesAnXmlFileThatDoesNotLoad) {
  const auto dir = test_dir();
  const auto xml = dir / "broken.xml";
  std::ofstream(xml) << "<profiles><participant";
  const Completed r =
      run_to_completion({bin("skyfuse"), "run", "--stations", "1", "--steps", "10", "--domain",
                         "132", "--qos", xml.string(), "--out", (dir / "out").string()},
                        dir / "run.log", 60s);
  EXPECT_NE(r.status.code, 0);
  EXPECT_THAT(r.output, HasSubstr("--qos: cannot load Fast DDS XML profiles from " + xml.string()));
}

}  // namespace
}  // namespace skyfuse::test

namespace skyfuse::test {
namespace {

TEST(DdsSetup, TheContainerProfileRunsInANetworkNamespaceOfItsOwn) {
  // docker/fastdds_profile.xml uses every interface and multicast discovery. Run it where the
  // only interface is a private loopback (a new network namespace), so nothing leaves the host.
  if (geteuid() != 0) GTEST_SKIP() << "needs root for unshare --net";
  const auto dir = test_dir();
  const std::string command =
      "ip link set lo up && exec " + bin("skyfuse") +
      " run --stations 2 --steps 100 --domain 5 --discovery-timeout 20 --qos " +
      std::string(SKYFUSE_SOURCE_DIR) + "/docker/fastdds_profile.xml --out " +
      (dir / "out").string();
  const Completed r = run_to_completion({"/usr/bin/unshare", "--net", "/bin/sh", "-c", command},
                                        dir / "run.log", std::chrono::seconds(60));
  ASSERT_EQ(r.status.code, 0) << r.output;
  EXPECT_EQ(read_tracks(dir / "out" / "tracks.csv").size(), 100U * 3U);
}

}  // namespace
}  // namespace skyfuse::test
