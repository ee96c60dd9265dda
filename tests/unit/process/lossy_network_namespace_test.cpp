#include "common/process/lossy_network_namespace.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>

namespace fleetmap::process {
namespace {

// How many of `count` datagrams sent to ourselves on 127.0.0.1 arrive, in this thread's
// network namespace.
int DatagramsThatArrive(int count) {
  const int receiver = socket(AF_INET, SOCK_DGRAM, 0);
  const int sender = socket(AF_INET, SOCK_DGRAM, 0);
  EXPECT_GE(receiver, 0);
  EXPECT_GE(sender, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  EXPECT_EQ(bind(receiver, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  EXPECT_EQ(getsockname(receiver, reinterpret_cast<sockaddr*>(&address), &length), 0);
  timeval timeout{0, 200 * 1000};
  setsockopt(receiver, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  const char byte = 'x';
  for (int i = 0; i < count; ++i) {
    sendto(sender, &byte, 1, 0, reinterpret_cast<sockaddr*>(&address), sizeof(address));
  }
  int arrived = 0;
  char buffer = 0;
  while (recv(receiver, &buffer, 1, 0) == 1) ++arrived;
  close(sender);
  close(receiver);
  return arrived;
}

class LossyNetworkNamespaceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const Status available = LossyNetworkNamespace::CheckAvailable(); !available.ok()) {
      GTEST_SKIP() << "LossyNetworkNamespace " << available.message();
    }
  }
};

TEST_F(LossyNetworkNamespaceTest, DropsTheChosenShareOfDatagramsAndCleansUp) {
  std::string path;
  {
    auto all_lost = LossyNetworkNamespace::Create(100);
    if (all_lost.status().code() == StatusCode::kUnavailable) {
      GTEST_SKIP() << "no network namespace here: " << all_lost.status();
    }
    ASSERT_TRUE(all_lost.ok()) << all_lost.status();
    path = "/run/netns/" + (*all_lost)->name();
    EXPECT_TRUE(std::filesystem::exists(path));
    auto inside = (*all_lost)->Enter();
    ASSERT_TRUE(inside.ok()) << inside.status();
    EXPECT_EQ(DatagramsThatArrive(50), 0);
  }
  EXPECT_FALSE(std::filesystem::exists(path)) << "the namespace outlived its owner";

  auto lossless = LossyNetworkNamespace::Create(0);
  ASSERT_TRUE(lossless.ok()) << lossless.status();
  auto inside = (*lossless)->Enter();
  ASSERT_TRUE(inside.ok()) << inside.status();
  EXPECT_EQ(DatagramsThatArrive(50), 50);
}

TEST(LossyNetworkNamespaceCheckTest, RefusesLossOutsideZeroToHundred) {
  if (!LossyNetworkNamespace::CheckAvailable().ok()) {
    EXPECT_FALSE(LossyNetworkNamespace::Create(20).ok());  // says what is missing
    return;
  }
  EXPECT_FALSE(LossyNetworkNamespace::Create(101).ok());
  EXPECT_FALSE(LossyNetworkNamespace::Create(-1).ok());
}

}  // namespace
}  // namespace fleetmap::process
