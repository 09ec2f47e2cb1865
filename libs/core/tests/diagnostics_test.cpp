// Diagnostics: repeated warnings counted once, and memory bounded past kMaxUnique different
// ones (a hostile file's million bad keys cost a counter, not a million strings).
#include <gtest/gtest.h>

#include <string>

#include "fresnel/core/error.h"

using fresnel::Diagnostics;

TEST(Diagnostics, RepeatsAreCountedOnce) {
    Diagnostics d;
    for (int i = 0; i < 5; ++i) d.warn("a.gltf", "/x", "odd");
    d.warn("a.gltf", "/y", "odd");
    ASSERT_EQ(d.warnings().size(), 2u);
    EXPECT_EQ(d.count(0), 5u);
    EXPECT_EQ(d.total(), 6u);
    EXPECT_EQ(d.lines().front(), "a.gltf: /x: odd (x5)");
}

TEST(Diagnostics, PastTheLimitWarningsAreOnlyCounted) {
    Diagnostics d;
    const std::size_t n = 1'000'000;
    for (std::size_t i = 0; i < n; ++i) d.warn("scene.fresnel.json", "/k" + std::to_string(i), "unknown key");
    EXPECT_EQ(d.warnings().size(), Diagnostics::kMaxUnique);
    EXPECT_EQ(d.suppressed(), n - Diagnostics::kMaxUnique);
    EXPECT_EQ(d.total(), n);
    const auto lines = d.lines();
    ASSERT_EQ(lines.size(), Diagnostics::kMaxUnique + 1);
    EXPECT_EQ(lines.back(), std::to_string(n - Diagnostics::kMaxUnique) + " more warnings not shown (past 200 different ones)");
    d.warn("scene.fresnel.json", "/k0", "unknown key");  // one already kept still counts where it is
    EXPECT_EQ(d.count(0), 2u);
}
