// Removal policies (slam/removal_policy.hpp): which node goes, by name.
#include "slam/removal_policy.hpp"

#include <gtest/gtest.h>

namespace lifelong::slam {
namespace {

const std::map<NodeId, double> kGains{{4, 9.0}, {7, 2.0}, {9, 2.0}, {12, 30.0}};

TEST(RemovalPolicy, InformationGainTakesTheLowestAtOrBelowTheThreshold) {
  const auto policy = MakeRemovalPolicy("information-gain", {5.0, 0});
  ASSERT_NE(policy, nullptr);
  EXPECT_EQ(policy->Name(), "information-gain");
  EXPECT_EQ(policy->Next(kGains, 100), NodeId{7});  // 7 and 9 tie: the smaller id
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 100), std::nullopt);
  EXPECT_EQ(policy->Next({{4, 5.0}}, 100), NodeId{4});  // at the threshold: goes
  EXPECT_EQ(policy->Next({}, 100), std::nullopt);
}

TEST(RemovalPolicy, InformationGainAlsoRemovesPastItsBudget) {
  const auto policy = MakeRemovalPolicy("information-gain", {0.0, 50});
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 51), NodeId{4});
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 50), std::nullopt);
}

TEST(RemovalPolicy, NodeBudgetRemovesOnlyPastTheBudgetWhateverTheGain) {
  const auto policy = MakeRemovalPolicy("node-budget", {0.0, 50});
  ASSERT_NE(policy, nullptr);
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 51), NodeId{4});
  EXPECT_EQ(policy->Next(kGains, 50), std::nullopt);  // gains of 2 bits stay within budget
  const auto unbounded = MakeRemovalPolicy("node-budget", {0.0, 0});
  EXPECT_EQ(unbounded->Next(kGains, 1000), std::nullopt);
}

TEST(RemovalPolicy, NamesAreTheRegistry) {
  for (const std::string& name : RemovalPolicyNames()) {
    const auto policy = MakeRemovalPolicy(name, {});
    ASSERT_NE(policy, nullptr) << name;
    EXPECT_EQ(policy->Name(), name);
  }
  EXPECT_EQ(MakeRemovalPolicy("gain", {}), nullptr);
}

}  // namespace
}  // namespace lifelong::slam
