// docker/compose.yaml run for real: docker/podman-run builds an image from a Debian 12 base
// bootstrapped here and this build's executables, runs the harness, the center and four
// stations each in its own container on one bridge network (discovery through the harness's
// server, no multicast), and removes everything but the cached base. The tracks must equal the
// in-process run's bit for bit.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <set>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

const std::string kBaseImage = "localhost/skyfuse-base:bookworm";

bool on_path(const std::string& tool) {
  return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0;
}

// The lines `podman <args>` prints.
std::multiset<std::string> podman_lines(const std::string& args) {
  std::multiset<std::string> lines;
  FILE* pipe = popen(("podman " + args + " 2>/dev/null").c_str(), "r");
  if (pipe == nullptr) return lines;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) lines.insert(buffer);
  pclose(pipe);
  return lines;
}

// Every container, network and image podman has, but the base image that is kept on purpose.
std::multiset<std::string> podman_objects() {
  std::multiset<std::string> all;
  for (const auto& c : podman_lines("ps -a --format 'container {{.Names}}'")) all.insert(c);
  for (const auto& n : podman_lines("network ls --format 'network {{.Name}}'")) all.insert(n);
  for (const auto& i :
       podman_lines("images -a --format 'image {{.Repository}}:{{.Tag}} {{.ID}}'")) {
    if (i.find(kBaseImage) == std::string::npos) all.insert(i);
  }
  return all;
}

TEST(Containers, AComposeRunOfFourStationsEqualsTheInProcessRunBitForBitAndLeavesNothingBehind) {
  if (!on_path("podman")) GTEST_SKIP() << "podman is not installed (./quickstart test installs it)";
  const std::string conf = std::string(SKYFUSE_SOURCE_DIR) + "/docker/containers.conf";
  setenv("CONTAINERS_CONF", conf.c_str(), 1);
  const auto dir = test_dir();
  const auto before = podman_objects();

  constexpr int kStations = 4;  // as docker/compose.yaml has them
  constexpr int kSteps = 200;
  const Completed done = run_to_completion(
      {std::string(SKYFUSE_SOURCE_DIR) + "/docker/podman-run", "--bin-dir", SKYFUSE_BIN_DIR,
       "--steps", std::to_string(kSteps), "--out", (dir / "out").string()},
      dir / "podman-run.log", 20min);
  ASSERT_EQ(done.status.code, 0) << done.output;

  const auto summary = expect_default_run_equals_twin(dir / "out", kStations, kSteps);
  EXPECT_EQ(summary.at("network").at("discovery").get<std::string>().rfind("server ", 0), 0u)
      << summary.at("network");

  EXPECT_EQ(podman_objects(), before) << "containers, networks or images were left behind";
  EXPECT_EQ(podman_lines("images --format '{{.Repository}}:{{.Tag}}'").count(kBaseImage + "\n"),
            1u);
}

}  // namespace
}  // namespace skyfuse::test
