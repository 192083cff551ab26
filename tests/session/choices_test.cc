// SPDX-License-Identifier: Apache-2.0
// The string choices of `rendering` become enums when the session is parsed; any other value is
// an error naming the file, the key and the value.
#include "mrh/settings/choices.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mrh/session/session.h"
#include "session/session_test_util.h"

namespace mrh::session {
namespace {

using testing::Minimal;
using testing::Parse;
using testing::ThrowsInvalidExactly;

TEST(ChoicesTest, DefaultsAreTheDocumentedOnes) {
  const settings::RenderingSettings r = Parse(Minimal("")).engine.rendering;
  EXPECT_EQ(r.torque_model, settings::TorqueModel::kContact);
  EXPECT_EQ(r.proxy_solver, settings::ProxySolver::kActiveSet);
  EXPECT_EQ(r.proxy_reaction, settings::ProxyReaction::kLocal);
  EXPECT_EQ(r.local_model, settings::LocalModel::kContact);
}

TEST(ChoicesTest, EveryNamedValueIsParsed) {
  const settings::RenderingSettings r =
      Parse(Minimal(R"("rendering": {"torque_model": "thesis", "proxy_solver": "pgs",
                                     "proxy_reaction": "impulse",
                                     "local_model": "perturbation"})"))
          .engine.rendering;
  EXPECT_EQ(r.torque_model, settings::TorqueModel::kThesis);
  EXPECT_EQ(r.proxy_solver, settings::ProxySolver::kPgs);
  EXPECT_EQ(r.proxy_reaction, settings::ProxyReaction::kImpulse);
  EXPECT_EQ(r.local_model, settings::LocalModel::kPerturbation);
}

TEST(ChoicesTest, UnknownValueIsAnErrorNamingFileKeyValueAndChoices) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"proxy_solver": "newton"})"));
      },
      ThrowsInvalidExactly("session.json: rendering.proxy_solver: unknown value "
                           "\"newton\"; expected one of \"active-set\", \"pgs\""));
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"torque_model": "euler"})"));
      },
      ThrowsInvalidExactly("session.json: rendering.torque_model: unknown value "
                           "\"euler\"; expected one of \"contact\", \"thesis\""));
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"proxy_reaction": "late"})"));
      },
      ThrowsInvalidExactly("session.json: rendering.proxy_reaction: unknown value "
                           "\"late\"; expected one of \"local\", \"impulse\""));
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"local_model": "Contact"})"));
      },
      ThrowsInvalidExactly("session.json: rendering.local_model: unknown value "
                           "\"Contact\"; expected one of \"contact\", \"perturbation\""));
}

TEST(ChoicesTest, NamesAndValuesRoundTrip) {
  for (const auto& c : settings::kTorqueModels) {
    EXPECT_EQ(settings::ParseChoice<settings::TorqueModel>(c.name), c.value);
    EXPECT_EQ(settings::ChoiceName(c.value), c.name);
  }
  for (const auto& c : settings::kProxySolvers) {
    EXPECT_EQ(settings::ParseChoice<settings::ProxySolver>(c.name), c.value);
  }
  for (const auto& c : settings::kProxyReactions) {
    EXPECT_EQ(settings::ParseChoice<settings::ProxyReaction>(c.name), c.value);
  }
  for (const auto& c : settings::kLocalModels) {
    EXPECT_EQ(settings::ParseChoice<settings::LocalModel>(c.name), c.value);
  }
  EXPECT_FALSE(settings::ParseChoice<settings::LocalModel>("").has_value());
}

}  // namespace
}  // namespace mrh::session
