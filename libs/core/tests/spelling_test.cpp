#include "fresnel/core/spelling.h"

#include <gtest/gtest.h>

using fresnel::did_you_mean;
using fresnel::nearest_name;

TEST(Spelling, NearestName) {
    const std::vector<std::string> commands = {"render", "info", "bake", "trace", "view"};
    EXPECT_EQ(nearest_name("rendr", commands), "render");
    EXPECT_EQ(nearest_name("RENDER", commands), "render");
    EXPECT_EQ(nearest_name("traec", commands), "trace");  // a transposition: two edits
    EXPECT_EQ(nearest_name("compile", commands), "");      // nothing near
    EXPECT_EQ(nearest_name("", commands), "");
    EXPECT_EQ(nearest_name("x", {}), "");
    EXPECT_EQ(nearest_name("--szie", {"--size", "--spp", "--seed"}), "--size");
    EXPECT_EQ(did_you_mean("normals", {"none", "normal", "tangent"}), " (did you mean 'normal'?)");
    EXPECT_EQ(did_you_mean("zzzz", {"normal"}), "");
}
