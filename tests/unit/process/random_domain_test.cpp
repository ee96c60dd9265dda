#include <gtest/gtest.h>

#include <set>

#include "common/process/subprocess.hpp"

namespace fleetmap::process {
namespace {

TEST(RandomDomainIdTest, NeverHandsOutAClaimedDomainTwice) {
  // Each id stays claimed by this process until it exits, so parallel tests cannot share one.
  std::set<int> domains;
  for (int i = 0; i < 20; ++i) {
    const int domain = RandomDomainId();
    EXPECT_GE(domain, 1);
    EXPECT_LE(domain, 200);
    EXPECT_TRUE(domains.insert(domain).second) << "domain " << domain << " handed out twice";
  }
}

}  // namespace
}  // namespace fleetmap::process
