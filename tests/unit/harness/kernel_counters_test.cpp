// The kernel's counters, read for this very process: a datagram sent to ourselves on loopback
// is counted, CPU burnt shows, memory touched raises the peak.
#include "run/kernel_counters.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <vector>

namespace skyfuse::harness {
namespace {

TEST(KernelCounters, ADatagramReceivedOnLoopbackIsCounted) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  socklen_t length = sizeof address;
  ASSERT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length), 0);

  const auto before = udp_datagrams_received(getpid());
  ASSERT_TRUE(before.has_value());
  constexpr int kSent = 5;
  for (int i = 0; i < kSent; ++i) {
    ASSERT_EQ(sendto(fd, "x", 1, 0, reinterpret_cast<sockaddr*>(&address), sizeof address), 1);
    char byte = 0;
    ASSERT_EQ(recv(fd, &byte, 1, 0), 1);
  }
  const auto after = udp_datagrams_received(getpid());
  close(fd);
  ASSERT_TRUE(after.has_value());
  // The namespace's counter: other processes may add to it, never take away.
  EXPECT_GE(*after - *before, static_cast<std::uint64_t>(kSent));
}

TEST(KernelCounters, CpuBurntAndMemoryTouchedShow) {
  const double cpu_before = cpu_seconds(getpid()).value();
  const auto peak_before = peak_resident_kib(getpid()).value();
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  volatile double sink = 0.0;
  while (std::chrono::steady_clock::now() < until) sink = sink + std::sqrt(sink + 1.0);
  std::vector<char> touched(64u << 20, 1);  // 64 MiB, every page written
  // The pages must be written, though nothing reads them: an empty asm that takes their address
  // and may read memory keeps the optimiser (clang's) from dropping the vector.
  asm volatile("" : : "r"(touched.data()) : "memory");
  const double cpu_after = cpu_seconds(getpid()).value();
  const auto peak_after = peak_resident_kib(getpid()).value();
  EXPECT_GE(cpu_after - cpu_before, 0.1);
  EXPECT_GE(peak_after, peak_before + 32u * 1024u) << touched[touched.size() / 2];
}

TEST(KernelCounters, AProcessThatIsGoneHasNoCounts) {
  const pid_t none = 0x3fffffff;  // above the kernel's pid limit
  EXPECT_FALSE(udp_datagrams_received(none).has_value());
  EXPECT_FALSE(cpu_seconds(none).has_value());
  EXPECT_FALSE(peak_resident_kib(none).has_value());
  EXPECT_FALSE(take_snapshot({}, {none}).udp_datagrams.has_value());
}

}  // namespace
}  // namespace skyfuse::harness
