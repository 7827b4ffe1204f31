// The DDS flags every command line shares (services/dds/cli).
#include "cover/dds/cli_options.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

namespace cover::dds {
namespace {

// `cover`'s task commands share one set of options over several subcommands: a --domain
// given to any of them is the domain (it once counted only on the last one added, and
// `cover list --domain 216` ran silently on domain 0).
TEST(DdsCliOptions, DomainGivenToAnyOfTheSubcommandsSharingTheOptionsCounts) {
  for (const char* chosen : {"submit", "list", "abort"}) {
    CLI::App app;
    DdsCliOptions dds;
    for (const char* name : {"submit", "list", "abort"}) dds.add_to(*app.add_subcommand(name));
    const char* argv[] = {"cover", chosen, "--domain", "216"};
    app.parse(4, const_cast<char**>(argv));
    EXPECT_EQ(dds.resolve("test").domain_id, 216) << chosen;
  }
}

}  // namespace
}  // namespace cover::dds
